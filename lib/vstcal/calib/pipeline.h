// Calibration end to end: a closed-form start (DLT or Tsai for a volume, Zhang for planar views),
// then, unless switched off, the shared maximum-likelihood refinement with its covariance.
// calib-dlt and calib-tsai are thin mains over Calibrate().
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vstcal/calib/calibrated_camera.h"
#include "vstcal/calib/correspondences.h"
#include "vstcal/calib/decompose.h"
#include "vstcal/calib/dlt.h"
#include "vstcal/calib/refine.h"
#include "vstcal/calib/tsai.h"
#include "vstcal/calib/zhang.h"
#include "vstcal/core/error.h"

namespace vstcal {

struct CalibrationOptions {
  enum class Start { kDlt, kTsai };
  Start start = Start::kTsai;  // for volume rigs; planar views always start from Zhang's method
  DltOptions dlt;
  TsaiOptions tsai;
  bool refine = true;
  RefineOptions refinement;
};

struct CalibrationResult {
  ExitCode exit_code = ExitCode::kOk;
  std::string message;                // why, when exit_code != kOk
  std::vector<std::string> warnings;  // skipped views, thin volumes, outliers, …

  CalibratedCamera camera;  // method "dlt", "tsai", "zhang", with "+refine" when refined
  Correspondences used;     // the correspondences the result refers to (sparse views dropped)

  std::optional<DltResult> dlt;
  std::optional<Eq13Decomposition> eq13;
  std::optional<TsaiResult> tsai;
  std::optional<Refinement> refinement;
};

// Never throws on bad geometry: exit_code and message say what went wrong. Throws InputError for
// options that cannot apply (e.g. an unknown distortion term).
CalibrationResult Calibrate(Correspondences correspondences, const CalibrationOptions& options);

}  // namespace vstcal
