// Reprojection residuals for Ceres. The objective, over every observation (X, q) of a view whose
// frame is posed by the reference camera_from_view:
//
//   Σ ‖ project(θ, δT · camera_from_view_ref · X) − q ‖²,   δT = (Exp(ω), ρ)
//
// Parameter blocks:
//   [0] θ: all of the lens model's parameters [fx, fy, cx, cy, s, distortion…]; the ones held
//       fixed are kept so by a ceres::SubsetManifold;
//   [1] δ = (ω, ρ) ∈ ℝ⁶: a left perturbation of the view's reference pose
//       (docs/conventions.md#poses-in-optimisation), starting at 0.
// Jacobians: ∂q/∂θ and ∂q/∂p from the lens model's ProjectWithJacobians (the one projection,
// its distortion differentiated by Jets), and with p = Exp(ω) y + ρ, y = camera_from_view_ref · X,
//   ∂p/∂ω = −[Exp(ω) y]× J_l(ω),  ∂p/∂ρ = I.
// A point that falls behind the camera makes Evaluate return false: Ceres rejects the step. It is
// never turned into a zero residual.
#pragma once

#include <span>
#include <vector>

#include <ceres/cost_function.h>

#include "vstcal/calib/correspondences.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

template <typename Model>
class ReprojectionCost final : public ceres::CostFunction {
 public:
  // One residual block for all `observations` (no robust loss: a Ceres loss applies to a whole
  // block), or for a single observation (robust losses, point by point).
  ReprojectionCost(std::span<const Observation> observations, const Rigid3d& camera_from_view_ref) {
    for (const Observation& o : observations) {
      y_.push_back(camera_from_view_ref * o.point);
      pixels_.push_back(o.pixel);
    }
    set_num_residuals(2 * static_cast<int>(observations.size()));
    mutable_parameter_block_sizes()->push_back(Model::kNumParams);
    mutable_parameter_block_sizes()->push_back(6);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* params = parameters[0];
    const Eigen::Map<const Eigen::Matrix<double, 6, 1>> delta(parameters[1]);
    const Eigen::Vector3d omega = delta.head<3>(), rho = delta.tail<3>();
    const Eigen::Matrix3d E = RotationFromRotvec(omega);
    const bool want_intrinsics = jacobians && jacobians[0];
    const bool want_pose = jacobians && jacobians[1];
    const Eigen::Matrix3d Jl = want_pose ? LeftJacobianSO3(omega) : Eigen::Matrix3d::Identity();
    using RowMajor2x3 = Eigen::Matrix<double, 2, 3, Eigen::RowMajor>;
    for (size_t i = 0; i < y_.size(); ++i) {
      const Eigen::Vector3d e = E * y_[i];
      const Eigen::Vector3d p = e + rho;
      double q[2];
      RowMajor2x3 d_q_d_p;
      double* d_params = want_intrinsics ? jacobians[0] + 2 * i * Model::kNumParams : nullptr;
      if (!Model::ProjectWithJacobians(params, p.data(), q, d_params, want_pose ? d_q_d_p.data() : nullptr)) return false;
      residuals[2 * i] = q[0] - pixels_[i].x();
      residuals[2 * i + 1] = q[1] - pixels_[i].y();
      if (want_pose) {
        Eigen::Map<Eigen::Matrix<double, 2, 6, Eigen::RowMajor>> d_pose(jacobians[1] + 12 * i);
        d_pose.leftCols<3>() = -d_q_d_p * Hat(e) * Jl;
        d_pose.rightCols<3>() = d_q_d_p;
      }
    }
    return true;
  }

 private:
  std::vector<Eigen::Vector3d> y_;  // camera_from_view_ref · X
  std::vector<Eigen::Vector2d> pixels_;
};

}  // namespace vstcal
