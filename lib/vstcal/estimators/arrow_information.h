// Block-arrow least-squares information and its inverse with every pose eliminated
// (docs/math/uncertainty.md#schur). A calibration's parameters are a few global ones — the free
// intrinsics (for a rig of cameras, also each camera's extrinsics) — and one 6-vector pose tangent
// per view that only that view's residuals touch, so its information matrix JᵀWJ is
//
//        [ U     W_1  …  W_P ]        U: g × g,  W_v: g × 6,  V_v: 6 × 6
//   M =  [ W_1ᵀ  V_1         ]
//        [  ⋮         ⋱      ]
//        [ W_Pᵀ           V_P ]
//
// It is kept in square-root form, never as M: each pose's rows are reduced by Householder QR to
// [R_v  R_vg] (6 × (6 + g)), and what they leave on the globals alone is folded into one g × g
// triangle R_g, so that R_gᵀR_g = S = U − Σ W_v V_v⁻¹ W_vᵀ, the Schur complement of the poses,
// formed without squaring any condition number. Storage and work are linear in the number of
// poses P; nothing of size (g + 6P)² is formed. The inverse is taken on the Jacobi-scaled problem
// (columns divided by √diag M: unit diagonal), so neither the verdict nor the covariance depends
// on the units of the parameters, and its blocks are scaled back.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "vstcal/geometry/rigid3.h"
#include "vstcal/scene/parameter_covariance.h"  // kObservabilityFloor

namespace vstcal {


class ArrowInformation {
 public:
  ArrowInformation(int num_global, int num_poses);

  // Adds the rows J = [J_g | J_p] (J: rows × (global_columns.size() + 6)) whose first columns are
  // the globals `global_columns` (indices, in order) and whose last 6 are pose `pose`'s tangent.
  // Weights are the caller's: a row weighted by w is multiplied by √w. Any number of calls per
  // pose, in any order.
  void AddRows(std::span<const int> global_columns, int pose, const Eigen::Ref<const Eigen::MatrixXd>& J);

  int num_global() const { return static_cast<int>(R_global_.rows()); }
  int num_poses() const { return static_cast<int>(R_pose_.size()); }
  // The square-root blocks: R_g (g × g, upper), and per pose [R_v | R_vg] (6 × (6 + g), R_v upper).
  const Eigen::MatrixXd& global_root() const { return R_global_; }
  const Matrix6Xd& pose_root(int pose) const { return R_pose_[pose]; }
  // diag M: the globals' and each pose's.
  const Eigen::VectorXd& global_diagonal() const { return diagonal_global_; }
  const Vector6d& pose_diagonal(int pose) const { return diagonal_pose_[pose]; }

 private:
  Eigen::MatrixXd R_global_;
  std::vector<Matrix6Xd> R_pose_;
  Eigen::VectorXd diagonal_global_;
  std::vector<Vector6d> diagonal_pose_;
};

// σ² M⁻¹ by blocks: the globals' covariance S⁻¹, each pose's 6 × 6 covariance and its covariance
// with the globals. Two poses are correlated only through the globals:
// Cov(δ_v, δ_w) = Σ_vg Σ_gg⁻¹ Σ_gw for v ≠ w, which is therefore not stored.
struct ArrowCovariance {
  Eigen::MatrixXd global;              // g × g
  std::vector<Matrix6d> pose;          // Σ_vv
  std::vector<Matrix6Xd> pose_global;  // Σ_vg, 6 × g
};

// Whether M is regular, judged on the scaled problem: the smallest eigenvalue of every scaled pose
// block V̂_v and of the scaled Schur complement Ŝ (squared smallest singular values of their
// roots; their diagonals are at most 1) must exceed kObservabilityFloor. The direction of that
// smallest eigenvalue says which parameters carry (almost) no information.
struct ArrowObservability {
  bool observable = false;
  double smallest_eigenvalue = 0;    // of Ŝ, or of the singular pose block V̂_v
  std::optional<int> singular_pose;  // the pose whose own block is singular; nullopt: the globals
  // Unit vector in scaled coordinates along that eigenvalue: over the g globals (also when
  // observable: the least determined combination), or over the singular pose's 6.
  Eigen::VectorXd weakest_direction;
};

struct ArrowInverse {
  ArrowObservability observability;
  ArrowCovariance covariance;  // scale · M⁻¹; empty unless observable
};

ArrowInverse InvertArrow(const ArrowInformation& information, double scale);

}  // namespace vstcal
