// Reprojection residuals for Ceres (the Ceres pattern: plain structs holding their observations,
// a templated operator(), a static Create()). The objective, over every observation (X, q) of a
// view whose frame is posed by camera_from_view:
//
//   Σ ‖ project(θ, δT · camera_from_view_ref · X) − q ‖²,   δT = (Exp(ω), ρ)
//
// Parameter blocks:
//   [0] θ: all of the lens model's parameters [fx, fy, cx, cy, s, distortion…]; the ones held
//       fixed are kept so by a ceres::SubsetManifold;
//   [1] δ = (ω, ρ) ∈ ℝ⁶: a left perturbation of the view's reference pose
//       (docs/conventions.md#poses-in-optimisation), starting at 0.
// A point that falls behind the camera makes operator() return false: Ceres rejects the step.
// It is never turned into a zero residual.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "vstcal/calib/correspondences.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

// Residual (predicted − measured) of one point under one pose; false behind the camera.
template <typename Model, typename T>
bool ReprojectionResidual(const T* intrinsics, const Rigid3<T>& camera_from_view, const Observation& o, T* residual) {
  // R·X with X in double: Jet × double avoids promoting X to Jets.
  T p_cam[3];
  for (int i = 0; i < 3; ++i) {
    p_cam[i] = camera_from_view.R(i, 0) * o.point.x() + camera_from_view.R(i, 1) * o.point.y() +
               camera_from_view.R(i, 2) * o.point.z() + camera_from_view.t(i);
  }
  T px[2];
  if (!Model::Project(intrinsics, p_cam, px)) return false;
  residual[0] = px[0] - o.pixel.x();
  residual[1] = px[1] - o.pixel.y();
  return true;
}

template <typename T>
Rigid3<T> PerturbedPose(const Rigid3d& reference, const T* delta) {
  return PerturbLeft(reference.cast<T>(), Vec3<T>(delta[0], delta[1], delta[2]), Vec3<T>(delta[3], delta[4], delta[5]));
}

// All observations of one view under one pose: the pose is built once per evaluation. Used when
// no robust loss is asked for (a Ceres loss applies to a whole residual block).
template <typename Model>
struct ViewReprojectionCost {
  const std::vector<Observation>* observations;
  Rigid3d reference;

  template <typename T>
  bool operator()(const T* intrinsics, const T* delta, T* residuals) const {
    const Rigid3<T> pose = PerturbedPose(reference, delta);
    for (size_t i = 0; i < observations->size(); ++i) {
      if (!ReprojectionResidual<Model>(intrinsics, pose, (*observations)[i], residuals + 2 * i)) return false;
    }
    return true;
  }

  static ceres::CostFunction* Create(const std::vector<Observation>& observations, const Rigid3d& reference) {
    return new ceres::AutoDiffCostFunction<ViewReprojectionCost, ceres::DYNAMIC, Model::kNumParams, 6>(
        new ViewReprojectionCost{&observations, reference}, 2 * static_cast<int>(observations.size()));
  }
};

// One observation: a residual block per point, so that a robust loss applies point by point.
template <typename Model>
struct PointReprojectionCost {
  Observation observation;
  Rigid3d reference;

  template <typename T>
  bool operator()(const T* intrinsics, const T* delta, T* residual) const {
    return ReprojectionResidual<Model>(intrinsics, PerturbedPose(reference, delta), observation, residual);
  }

  static ceres::CostFunction* Create(const Observation& observation, const Rigid3d& reference) {
    return new ceres::AutoDiffCostFunction<PointReprojectionCost, 2, Model::kNumParams, 6>(
        new PointReprojectionCost{observation, reference});
  }
};

}  // namespace vstcal
