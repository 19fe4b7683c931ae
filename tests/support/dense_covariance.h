// The dense covariance path the refinement used before poses were eliminated by the Schur
// complement, kept here as the test oracle (never in lib/): the whole information matrix JᵀWJ over
// the free intrinsics β and 6 tangents per pose, (g + 6P)², accumulated point by point through the
// same cost function, and inverted whole — cubic in the views. The inverse is taken in long double
// after Jacobi scaling, so that the oracle is exact to far below the 1e-9 it is compared at; the
// old code's verdict (unscaled eigenvalue ratio > 1e-13) is reported beside it.
// Optionally one σ per view (rows divided by it), so that weights can be checked against "a
// view's σ divided by √k" independently of the weight code.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "vstcal/scene/correspondences.h"
#include "vstcal/estimators/free_intrinsics.h"
#include "vstcal/estimators/refine_options.h"
#include "vstcal/camera/camera.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal::testing {

struct DenseCovariance {
  FreeIntrinsics free;
  Eigen::MatrixXd information;  // JᵀWJ / σ², (g + 6P)², columns β then 6 per pose
  Eigen::MatrixXd covariance;   // its inverse; empty when LDLT finds it singular
  // The old verdict: smallest eigenvalue of the unscaled information over its largest.
  double unscaled_eigenvalue_ratio = 0;
};

// `sigma_per_view`: the pixel σ of each view's weight-1 points; default σ for all.
DenseCovariance DenseCovarianceAt(const Correspondences& c, const Camera& camera, const std::vector<Rigid3d>& poses,
                                  const RefineOptions& options, double sigma_px,
                                  const std::optional<std::vector<double>>& sigma_per_view = std::nullopt);

}  // namespace vstcal::testing
