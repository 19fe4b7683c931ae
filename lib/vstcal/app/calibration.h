// What calib-dlt and calib-tsai do once the solver has run (docs/tools/calib-dlt.md,
// calib-tsai.md): the camera file with its solver blocks and projection uncertainty, the optional
// residuals file, the warnings and the summary — or, for a failed result, the documented error.
#pragma once

#include <string>

#include "vstcal/app/outcome.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/formats/calib/calibration_io.h"
#include "vstcal/json/provenance.h"

namespace vstcal::app {

struct CalibrationFiles {
  std::string tool;       // names the warnings' lines ("calib-tsai: warning: …")
  std::string input;      // the correspondences file, named in the summary and in a failure
  std::string output;     // camera@1
  std::string residuals;  // residuals@1; empty: none
  UncertaintyRequest uncertainty;
  // Check images: each view's image (views[].image, as given or beside the input) resampled
  // undistorted through the camera (image/undistort.h), as FOLDER/<view>.undistorted.png; empty: none.
  std::string undistort_folder;
};

// Throws Error with the result's exit code and "<input>: <message>" for a failed result.
Outcome CalibrationOutcome(const CalibrationResult& result, const CalibrationOptions& options,
                           const CalibrationFiles& files, const Provenance& provenance);

// calib-tsai --split-halves (docs/tools/calib-tsai.md#cross-validation): the views split into two
// halves — the 1st, 3rd, 5th … and the 2nd, 4th, 6th … in file order — each calibrated as the whole
// was, their cameras written beside files.output as <stem>.half-a.json and <stem>.half-b.json for
// calib-compare --cross-validate. InputError naming the flag when there are fewer than 2 views, and
// the half's failure (with its exit code) when a half cannot be calibrated.
Outcome CalibrateHalves(const Correspondences& corners, const CalibrationOptions& options, const CalibrationFiles& files,
                        const Provenance& provenance);

// The two kinds of projection uncertainty, each labelled, at the image centre at the calibration
// points' median depth and at each requested pixel; empty without a covariance.
std::string UncertaintySummary(const CalibrationResult& result, const UncertaintyRequest& request);

}  // namespace vstcal::app
