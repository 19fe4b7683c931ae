// Solving a stereo rig from the same target poses seen by both cameras (docs/math/stereo.md#solve,
// docs/tools/calib-stereo.md#solve): each camera calibrated alone by the shared pipeline
// (calib/pipeline.h), right_from_left started from the geodesic L1 mean of the per-view relative
// rotations and the mean of the translations, then one joint maximum-likelihood refinement of both
// cameras' intrinsics, right_from_left and one board pose per view (poses eliminated by the Schur
// complement), and the covariance of right_from_left from the square-root information of that same
// problem (estimators/arrow_information.h).
//
// Views are matched by name. A view seen by one camera only still serves that camera's intrinsics
// (and, through the shared pose, nothing else); it is reported. Volume rigs have one pose (the
// world frame) seen by both cameras; planar-views rigs one pose per view name.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vstcal/scene/correspondences.h"
#include "vstcal/scene/view_keys.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/core/error.h"
#include "vstcal/scene/stereo_rig.h"

namespace vstcal {

struct StereoSolveOptions {
  // Each camera's own start, the lens terms estimated and the iteration limit of every solve. The
  // joint problem is least squares: a robust loss is refused (InputError).
  CalibrationOptions calibration;
  // Intrinsics of an earlier calibration: the start of that camera (its own calibration is
  // skipped) and, when held, its value throughout.
  std::optional<Camera> left_camera, right_camera;
  bool hold_left = false, hold_right = false;  // intrinsics held fixed (at the given camera, else at its own calibration)
  // Views match when their keys are equal: the name itself, or, given this regular expression
  // (ECMAScript), the first group of its match in the name — "([0-9]+)$" pairs left01.jpg's view
  // "left01" with "right01". A name it does not match is bad input.
  std::string view_key_pattern;
  size_t min_common_views = 3;  // planar views seen by both cameras; fewer: exit code 3
};

struct StereoSolveResult {
  ExitCode exit_code = ExitCode::kOk;
  std::string message;             // why, when exit_code != kOk
  std::vector<std::string> notes;  // views seen by one camera only, weak parameters, …
  StereoRig rig;                   // method "stereo-solve"; fit and covariance filled
  std::vector<std::string> common_views, left_only_views, right_only_views;
  Eigen::Matrix3d initial_rotation = Eigen::Matrix3d::Identity();  // the rotation average, before refinement
  double sigma_px = 0;  // σ̂ of a weight-1 point over both cameras' residuals
  int dof = 0;
  int iterations = 0;
  double rms_left_px = 0, rms_right_px = 0;  // reprojection RMS of each camera at the optimum
};

// `left_file`, `right_file` name the inputs in messages. Throws InputError for inputs that cannot
// be solved together (differing length units or rigs, a view key twice in one file, a name the
// view key pattern does not match, a given
// camera whose image size differs from its correspondences', a robust loss); geometric failures come back in
// exit_code (kDegenerate) and message, nothing else filled.
StereoSolveResult SolveStereo(Correspondences left, Correspondences right, const StereoSolveOptions& options,
                              const std::string& left_file = "LEFT", const std::string& right_file = "RIGHT");

}  // namespace vstcal
