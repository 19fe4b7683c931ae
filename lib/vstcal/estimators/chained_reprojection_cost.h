// Reprojection residuals of the right camera of a rig whose board poses are the left camera's:
// over every observation (X, q, w) of a view,
//
//   Σ w ‖ project(θ_R, δT_rl · right_from_left_ref · δT_v · left_from_board_ref · X) − q ‖²
//
// δT = (Exp(ω), ρ) left perturbations (docs/conventions.md#poses-in-optimisation). The left
// camera's residuals are estimators/reprojection_cost.h's with the same δT_v, so both cameras share one
// board pose per view (docs/math/stereo.md#joint-problem). Parameter blocks: [0] θ_R (the lens
// model's whole layout), [1] δ_rl ∈ ℝ⁶, [2] δ_v ∈ ℝ⁶. With y = left_from_board_ref · X,
//   a = Exp(ω_v) y + ρ_v,  b = R_rl a + t_rl,  p = Exp(ω_rl) b + ρ_rl:
//   ∂p/∂ω_rl = −[Exp(ω_rl) b]× J_l(ω_rl),  ∂p/∂ρ_rl = I,
//   ∂p/∂ω_v = −Exp(ω_rl) R_rl [Exp(ω_v) y]× J_l(ω_v),  ∂p/∂ρ_v = Exp(ω_rl) R_rl.
// A point behind the right camera makes Evaluate return false: Ceres rejects the step.
#pragma once

#include <span>

#include <ceres/cost_function.h>

#include "vstcal/estimators/weighted_reprojection.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal {

template <typename Model>
class ChainedReprojectionCost final : public ceres::CostFunction {
 public:
  ChainedReprojectionCost(std::span<const Observation> observations, const Rigid3d& right_from_left_ref,
                          const Rigid3d& left_from_board_ref)
      : right_from_left_(right_from_left_ref), observations_(observations, left_from_board_ref) {
    set_num_residuals(2 * static_cast<int>(observations.size()));
    mutable_parameter_block_sizes()->push_back(Model::kNumParams);
    mutable_parameter_block_sizes()->push_back(6);
    mutable_parameter_block_sizes()->push_back(6);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Perturbation rl(parameters[1], jacobians && jacobians[1]);
    const Perturbation v(parameters[2], jacobians && jacobians[2]);
    for (size_t i = 0; i < observations_.size(); ++i) {
      if (!EvaluatePoint(i, parameters[0], rl, v, residuals + 2 * i,
                         jacobians && jacobians[0] ? jacobians[0] + 2 * i * Model::kNumParams : nullptr,
                         jacobians && jacobians[1] ? jacobians[1] + 12 * i : nullptr,
                         jacobians && jacobians[2] ? jacobians[2] + 12 * i : nullptr)) {
        return false;
      }
    }
    return true;
  }

  // Observation i alone at δ_rl = δ_v = 0: its 2 weighted residuals and, when asked, their rows of
  // ∂r/∂θ (2 × kNumParams), ∂r/∂δ_rl and ∂r/∂δ_v (2 × 6 each), row-major.
  bool EvaluatePointAtReference(size_t i, const double* params, double* residual, double* d_params, double* d_rl,
                                double* d_view) const {
    static constexpr double kZero[6] = {0, 0, 0, 0, 0, 0};
    return EvaluatePoint(i, params, Perturbation(kZero, true), Perturbation(kZero, true), residual, d_params, d_rl, d_view);
  }

  size_t size() const { return observations_.size(); }

 private:
  struct Perturbation {
    Perturbation(const double* delta, bool with_jacobian) {
      const Eigen::Map<const Eigen::Matrix<double, 6, 1>> d(delta);
      E = RotationFromRotvec(Eigen::Vector3d(d.head<3>()));
      rho = d.tail<3>();
      Jl = with_jacobian ? LeftJacobianSO3(Eigen::Vector3d(d.head<3>())) : Eigen::Matrix3d::Identity();
    }
    Eigen::Matrix3d E, Jl;
    Eigen::Vector3d rho;
  };

  bool EvaluatePoint(size_t i, const double* params, const Perturbation& rl, const Perturbation& v, double* residual,
                     double* d_params, double* d_rl, double* d_view) const {
    using RowMajor2x6 = Eigen::Matrix<double, 2, 6, Eigen::RowMajor>;
    const Eigen::Vector3d ev = v.E * observations_.point(i);
    const Eigen::Vector3d b = right_from_left_.R * (ev + v.rho) + right_from_left_.t;
    const Eigen::Vector3d eb = rl.E * b;
    const Eigen::Vector3d p = eb + rl.rho;
    RowMajor2x3 d_q_d_p;
    double w;
    if (!observations_.Residual<Model>(i, params, p, residual, d_params, (d_rl || d_view) ? &d_q_d_p : nullptr, &w)) {
      return false;
    }
    if (d_rl) {
      Eigen::Map<RowMajor2x6> d(d_rl);
      d.leftCols<3>() = -w * d_q_d_p * Hat(eb) * rl.Jl;
      d.rightCols<3>() = w * d_q_d_p;
    }
    if (d_view) {
      const RowMajor2x3 d_q_d_a = w * d_q_d_p * rl.E * right_from_left_.R;
      Eigen::Map<RowMajor2x6> d(d_view);
      d.leftCols<3>() = -d_q_d_a * Hat(ev) * v.Jl;
      d.rightCols<3>() = d_q_d_a;
    }
    return true;
  }

  Rigid3d right_from_left_;
  WeightedObservations observations_;  // in the frame left_from_board_ref
};

}  // namespace vstcal
