// A volume calibration by DLT, end to end: solve P, decompose it, compute residuals per point, per
// view and at the test points. calib-dlt is a thin main over CalibrateDlt.
#pragma once

#include <optional>

#include "vstcal/calib/calibrated_camera.h"
#include "vstcal/calib/correspondences.h"
#include "vstcal/calib/decompose.h"
#include "vstcal/calib/dlt.h"

namespace vstcal {

struct DltCalibration {
  DltResult dlt;                           // status and message say whether the rest is set
  std::optional<CalibratedCamera> camera;  // method "dlt", K, pose, P, fit; set when dlt.status == kOk
  std::optional<Eq13Decomposition> eq13;   // seed 001 Eq. 13–14 quantities of the same P
};

// `c` must be a volume rig. Statuses other than kOk carry a message naming the offending view and
// point where there is one.
DltCalibration CalibrateDlt(const Correspondences& c, const DltOptions& options = {});

}  // namespace vstcal
