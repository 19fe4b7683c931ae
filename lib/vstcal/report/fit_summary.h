// Short human summaries of a solved camera for a tool's stderr.
#pragma once

#include <string>

#include "vstcal/scene/calibrated_camera.h"

namespace vstcal {

// Several lines: RMS and max residual, K, camera centre, per-view worst, test-point errors.
std::string FitSummaryText(const CalibratedCamera& camera);

}  // namespace vstcal
