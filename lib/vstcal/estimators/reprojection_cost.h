// Reprojection residuals for Ceres. The objective, over every observation (X, q, w) of a view whose
// frame is posed by the reference camera_from_view:
//
//   Σ w ‖ project(θ, δT · camera_from_view_ref · X) − q ‖²,   δT = (Exp(ω), ρ)
//
// w is the observation's weight (correspondences@1, docs/formats.md#weights), applied by the one
// weighted residual (weighted_reprojection.h).
// Parameter blocks:
//   [0] θ: all of the lens model's parameters [fx, fy, cx, cy, s, distortion…]; the refinement
//       moves them along its FreeIntrinsics basis (a Ceres manifold), the rest stay put;
//   [1] δ = (ω, ρ) ∈ ℝ⁶: a left perturbation of the view's reference pose
//       (docs/conventions.md#poses-in-optimisation), starting at 0.
// Jacobians: ∂q/∂θ and ∂q/∂p from the lens model's ProjectWithJacobians (the one projection,
// its distortion differentiated by Jets), and with p = Exp(ω) y + ρ, y = camera_from_view_ref · X,
//   ∂p/∂ω = −[Exp(ω) y]× J_l(ω),  ∂p/∂ρ = I.
// A point that falls behind the camera makes Evaluate return false: Ceres rejects the step. It is
// never turned into a zero residual.
#pragma once

#include <span>

#include <ceres/cost_function.h>

#include "vstcal/estimators/weighted_reprojection.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal {

template <typename Model>
class ReprojectionCost final : public ceres::CostFunction {
 public:
  // One residual block for all `observations` (no robust loss: a Ceres loss applies to a whole
  // block), or for a single observation (robust losses, point by point).
  ReprojectionCost(std::span<const Observation> observations, const Rigid3d& camera_from_view_ref)
      : observations_(observations, camera_from_view_ref) {
    set_num_residuals(2 * static_cast<int>(observations.size()));
    mutable_parameter_block_sizes()->push_back(Model::kNumParams);
    mutable_parameter_block_sizes()->push_back(6);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::Matrix<double, 6, 1>> delta(parameters[1]);
    const Eigen::Vector3d omega = delta.head<3>();
    const bool want_intrinsics = jacobians && jacobians[0];
    const bool want_pose = jacobians && jacobians[1];
    const Eigen::Matrix3d E = RotationFromRotvec(omega);
    const Eigen::Matrix3d Jl = want_pose ? LeftJacobianSO3(omega) : Eigen::Matrix3d::Identity();
    for (size_t i = 0; i < observations_.size(); ++i) {
      if (!EvaluatePoint(i, parameters[0], E, Jl, delta.tail<3>(), residuals + 2 * i,
                         want_intrinsics ? jacobians[0] + 2 * i * Model::kNumParams : nullptr,
                         want_pose ? jacobians[1] + 12 * i : nullptr)) {
        return false;
      }
    }
    return true;
  }

  // Observation i alone at δ = 0: its 2 weighted residuals and, when asked, their rows of ∂r/∂θ
  // (2 × kNumParams) and ∂r/∂δ (2 × 6), row-major. False when the point is behind the camera.
  bool EvaluatePointAtReference(size_t i, const double* params, double* residual, double* d_params, double* d_pose) const {
    return EvaluatePoint(i, params, Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(),
                         residual, d_params, d_pose);
  }

  size_t size() const { return observations_.size(); }

 private:
  // E = Exp(ω), Jl = J_l(ω), ρ: the perturbation, shared by the block's points.
  bool EvaluatePoint(size_t i, const double* params, const Eigen::Matrix3d& E, const Eigen::Matrix3d& Jl,
                     const Eigen::Vector3d& rho, double* residual, double* d_params, double* d_pose) const {
    const Eigen::Vector3d e = E * observations_.point(i);
    const Eigen::Vector3d p = e + rho;
    RowMajor2x3 d_q_d_p;
    double w;
    if (!observations_.Residual<Model>(i, params, p, residual, d_params, d_pose ? &d_q_d_p : nullptr, &w)) return false;
    if (d_pose) {
      Eigen::Map<Eigen::Matrix<double, 2, 6, Eigen::RowMajor>> d(d_pose);
      d.leftCols<3>() = -w * d_q_d_p * Hat(e) * Jl;
      d.rightCols<3>() = w * d_q_d_p;
    }
    return true;
  }

  WeightedObservations observations_;  // in the frame camera_from_view_ref
};

}  // namespace vstcal
