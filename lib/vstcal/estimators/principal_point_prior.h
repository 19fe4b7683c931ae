// One plane cannot determine a pinhole's principal point besides its focal length (Zhang 2000,
// §3.1): the homography fixes 8 numbers, the pose takes 6. calib-tsai's default estimates it under
// a Gaussian prior, and calib-capture plan predicts that same solve, so both take it from here
// (docs/math/uncertainty.md#one-plane).
#pragma once

#include <string>

#include <Eigen/Core>

#include "vstcal/core/image_size.h"
#include "vstcal/estimators/refine_options.h"

namespace vstcal {

// The prior's σ per coordinate, as a fraction of the image diagonal.
inline constexpr double kPlanePrincipalPointPriorSigma = 0.05;

// σ in px of a prior of `sigma_fraction` of the diagonal of `size`.
double PrincipalPointPriorSigmaPx(const ImageSize& size, double sigma_fraction);

// Appends the priors on cx and cy at `at`, σ PrincipalPointPriorSigmaPx each, with `because`.
void AddPrincipalPointPrior(const Eigen::Vector2d& at, double sigma_px, const std::string& because, RefineOptions* options);

// Whether `options` already place the principal point, by a prior on cx or cy or by holding it:
// the caller's choice then stands, and no rule adds one of its own.
bool PlacesPrincipalPoint(const RefineOptions& options);

}  // namespace vstcal
