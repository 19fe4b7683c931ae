// Cramér–Rao bound for a pinhole camera with skew and one pose, under isotropic Gaussian pixel
// noise σ: Cov(θ) ≥ σ² (JᵀJ)⁻¹ with J = ∂(projections)/∂θ, θ = (fx, fy, cx, cy, s, r, t), r the
// rotation vector of a left perturbation of camera_from_world. J comes from ceres::Jet through
// the library's templated projection. Used to derive test tolerances independently of any solver.
#pragma once

#include <span>

#include <Eigen/Core>

#include "vstcal/scene/correspondences.h"
#include "vstcal/camera/camera.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal::testing {

using Matrix11d = Eigen::Matrix<double, 11, 11>;

Matrix11d PinholeCrb(const Camera& camera, const Rigid3d& camera_from_world, std::span<const Observation> observations,
                     double sigma_px);

}  // namespace vstcal::testing
