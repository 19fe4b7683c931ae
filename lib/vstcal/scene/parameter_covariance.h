// The covariance of estimated parameters as camera files carry it (docs/formats.md#camera-covariance),
// and its propagation to anything linear in them.
//
// Named parameters (docs/conventions.md#poses-in-optimisation): intrinsics by their lens-model
// names ("fx", "k1", …); a pose's tangent as "<pose>.rx", ".ry", ".rz" (left-perturbation rotation
// ω, radians) and ".tx", ".ty", ".tz" (ρ, length unit), e.g. "camera_from_world.rx". A pose may
// instead be kept apart as a PoseCovariance block — what a planar-views calibration writes, one
// block per view, so that the file grows linearly with the views: two views' poses are
// correlated only through the named parameters, Cov(δ_v, δ_w) = Σ_vg Σ_gg⁻¹ Σ_gw
// (docs/math/uncertainty.md#schur), which is therefore not stored.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vstcal/geometry/rigid3.h"

namespace vstcal {

// A scaled eigenvalue below this is no information: with unit diagonals it means a parameter is
// a combination of the others to 1 part in 10¹¹ (variance inflation > 10¹¹), far below what any
// noise level leaves usable and far above the rounding of an exactly singular problem (≈ 1e-15).
inline constexpr double kObservabilityFloor = 1e-11;

struct PoseCovariance {
  std::string pose;           // "views[3].camera_from_board"
  Matrix6d matrix;            // Cov(δ), δ = (rx, ry, rz, tx, ty, tz)
  Matrix6Xd with_parameters;  // Cov(δ, named parameters): 6 × parameters.size()
};

struct ParameterCovariance {
  std::vector<std::string> parameters;
  Eigen::MatrixXd matrix;
  std::vector<PoseCovariance> poses;

  // Index of a named parameter, or nullopt.
  std::optional<size_t> Find(std::string_view name) const;
  // Index in `poses` of a pose block, or nullopt.
  std::optional<size_t> FindPose(std::string_view pose) const;
  bool empty() const { return parameters.empty() && poses.empty(); }
};

// The rows of ∂y/∂δ of one pose block (rows × 6).
struct PoseJacobian {
  size_t pose = 0;  // index in ParameterCovariance::poses
  Eigen::MatrixXd J;
};

// Cov(y) for y = J · (named parameters) + Σ_k J_k · δ_{pose_k} (J: rows × parameters.size()):
//   J Σ_gg Jᵀ + Σ_k (J Σ_gk J_kᵀ + J_k Σ_kg Jᵀ) + Σ_k J_k Σ_kk J_kᵀ + Σ_{k≠l} J_k Σ_kg Σ_gg⁻ Σ_gl J_lᵀ,
// with Σ_gg⁻ a generalized inverse (Σ_gg may be singular when parameters are tied, e.g.
// fx = sx·fy: any generalized inverse gives the same product because Σ_gl lies in Σ_gg's range).
// Cost: linear in the number of pose Jacobians.
Eigen::MatrixXd PropagateCovariance(const ParameterCovariance& covariance, const Eigen::MatrixXd& J,
                                    std::span<const PoseJacobian> pose_jacobians = {});

}  // namespace vstcal
