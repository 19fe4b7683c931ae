// P → K, R, t (seed 000 Eq. 8, seed 001 Eq. 12–14). docs/math/dlt.md#decomposition derives both
// routes and shows they agree.
#pragma once

#include <optional>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/scene/parameter_covariance.h"
#include "vstcal/camera/intrinsics.h"

namespace vstcal {

struct ProjectionDecomposition {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();  // upper triangular, fx, fy > 0, K(2,2) = 1, skew kept
  Rigid3d camera_from_world;
};

// RQ decomposition of P's left 3×3 block, signs fixed so that fx, fy > 0 and det R = +1.
// P must be normalized (NormalizeProjectionScale) with det P(:, 0:3) > 0, which SolveDlt
// guarantees; nullopt when the block is singular or mirrored.
std::optional<ProjectionDecomposition> DecomposeProjection(const Matrix34d& P);

// The covariance of the decomposed camera from Cov(vec P) (P row-major, in the gauge
// ‖P(2, 0:3)‖ = 1 that K[R|t] with K(2,2) = 1 satisfies), over fx, fy, cx, cy, s and
// camera_from_world's tangent (rx, ry, rz, tx, ty, tz; docs/conventions.md#poses-in-optimisation).
// P(θ) = K[R|t] maps the 11 parameters onto the 11-dimensional gauge surface, so the
// decomposition's Jacobian is the pseudo-inverse of ∂vec P/∂θ: Σ_θ = J⁺ Σ_P J⁺ᵀ
// (docs/math/dlt.md#covariance). `P_covariance` must lie in the surface's tangent space, as
// EstimateDltUncertainty's does.
ParameterCovariance DecompositionCovariance(const ProjectionDecomposition& d,
                                            const Eigen::Matrix<double, 12, 12>& P_covariance);

// Cov(C) of the camera centre C = −Rᵀt in world coordinates from a covariance over
// camera_from_world's tangent: a left perturbation (ω, ρ) moves C by −Rᵀρ.
Eigen::Matrix3d CameraCentreCovariance(const ParameterCovariance& covariance, const Rigid3d& camera_from_world);

// Seed 001 Eq. 13–14 (Forsyth & Ponce) written out literally, as an independent route to the
// same numbers: with P = [A b] and rows a₁, a₂, a₃ of A,
//   ρ = ±1/‖a₃‖, u₀ = ρ²(a₁·a₃), v₀ = ρ²(a₂·a₃),
//   cos θ = −(a₁×a₃)·(a₂×a₃) / (‖a₁×a₃‖ ‖a₂×a₃‖),
//   fu = ρ²‖a₁×a₃‖ sin θ, fv = ρ²‖a₂×a₃‖ sin θ,
//   r₁ = (a₂×a₃)/‖a₂×a₃‖, r₃ = ρa₃, r₂ = r₃×r₁, t = ρK⁻¹b,
// with the sign of ρ chosen so that P's depth row is positive in front (ρ > 0 for a normalized P).
struct Eq13Decomposition {
  SkewForm intrinsics;
  double rho = 0;
  Rigid3d camera_from_world;
};
Eq13Decomposition DecomposeProjectionEq13(const Matrix34d& P);

}  // namespace vstcal
