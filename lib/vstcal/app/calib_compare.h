// calib-compare as a library call (docs/tools/calib-compare.md): two cameras compared in
// parameters, pose and pixels, optionally at a correspondences file's test points, and optionally
// checked against thresholds for a user's CI — a pixel bound and a bound in σ of the two
// calibrations' own projection uncertainties — with the verdicts as JUnit XML.
#pragma once

#include <optional>
#include <string>

#include "vstcal/app/outcome.h"

namespace vstcal::app {

struct CompareRequest {
  std::string reference, other;    // camera@1 files
  std::optional<double> depth;     // of the comparison grid (length unit)
  std::string test_points;         // correspondences@1 file; empty: none
  std::optional<double> max_px;    // fail when any disagreement exceeds it (px)
  std::optional<double> max_sigma;  // fail when any disagreement exceeds it in σ (both cameras need a covariance)
  // Cross-validation of two calibrations of one camera from disjoint data (CrossValidate): a table
  // of the image's regions and a check that fails when they disagree beyond their uncertainty.
  bool cross_validate = false;
  std::string junit;               // JUnit XML of the checks; empty: none
};

// The comparison (and the checks' verdicts) in `stdout_text`; the JUnit file in `files`;
// `check_failed` when a threshold is exceeded. InputError for a bad file, a threshold that is not
// a positive finite number, --max-sigma with a camera without covariance, --junit without a check.
Outcome Compare(const CompareRequest& request);

}  // namespace vstcal::app
