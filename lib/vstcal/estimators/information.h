// The Fisher information of a calibration and its covariance at GIVEN parameters, without solving:
// what Refine reports at its optimum (with the noise σ̂ it estimates) and what a capture plan
// predicts before any image is taken (with a stated pixel noise). One code path for both.
//
// The information is JᵀWJ over the free intrinsics β (FreeIntrinsics) and one pose tangent per
// pose (volume: camera_from_world; planar views: each view's camera_from_board), assembled view by
// view in block-arrow form, weighted by the points' weights and, under a robust loss, by ρ′ at the
// given parameters (the IRLS information). Poses are eliminated by the Schur complement and the
// observability verdict is taken on the Jacobi-scaled matrix, so neither the cost nor the verdict
// grows beyond linear in the views, and neither depends on the length unit
// (docs/math/uncertainty.md#schur, #observability).
#pragma once

#include <string>
#include <vector>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/scene/correspondences.h"
#include "vstcal/estimators/free_intrinsics.h"
#include "vstcal/estimators/refine_options.h"

namespace vstcal {

struct CalibrationCovariance {
  bool observable = false;
  // When not observable: "the information matrix is singular: " + `weakest`. One line.
  std::string message;
  double smallest_scaled_eigenvalue = 0;
  // The parameters (or the view) along the weakest direction of the scaled information and what
  // to hold or add ("k3 is not determined by these points (…); …"), when not observable or when
  // the smallest scaled eigenvalue is below kWeaklyDetermined ("barely determined"); else empty.
  std::string weakest;

  AnyLensModel model;   // the refined model (options may promote the camera's)
  FreeIntrinsics free;  // the coordinates β of `free_covariance`
  Eigen::MatrixXd free_covariance;  // σ² × the β block of the inverse information
  // Over the lens parameters β moves and the poses, as camera files carry it: volume rigs name
  // camera_from_world's tangents beside the intrinsics; planar views keep one PoseCovariance per
  // view. Empty when not observable.
  ParameterCovariance covariance;
  size_t n_behind = 0;  // observations behind the camera at these parameters, left out
};

// A scaled eigenvalue below this leaves a parameter's σ over 1000 times what it would be were it
// the only one free (variance inflation > 10⁶): determined, but barely.
inline constexpr double kWeaklyDetermined = 1e-6;

// `poses`: camera_from_world (volume: one) or camera_from_board (planar views: one per view), in
// the file's length unit. `sigma_px`: the pixel noise of a weight-1 point. Throws InputError for
// options naming unknown distortion terms.
CalibrationCovariance CovarianceAt(const Correspondences& c, const Camera& camera, const std::vector<Rigid3d>& poses,
                                   const RefineOptions& options, double sigma_px);

// The name of pose i in covariances: "camera_from_world" (volume) or "views[i].camera_from_board".
std::string PoseName(const Correspondences& c, size_t pose);

}  // namespace vstcal
