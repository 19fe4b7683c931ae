// Short human summaries of a solved camera for a tool's stderr.
#pragma once

#include <span>
#include <string>

#include "vstcal/estimators/free_intrinsics.h"
#include "vstcal/scene/calibrated_camera.h"

namespace vstcal {

// Several lines: RMS and max residual, K, camera centre, per-view worst, test-point errors.
std::string FitSummaryText(const CalibratedCamera& camera);

// Every lens parameter as Bouguet's toolbox and mrcal show them: the estimate ± 1σ (from the
// camera's covariance) and the 3σ interval; a held parameter with its reason instead; a parameter
// neither estimated with a σ nor held (no covariance) with its value alone. Then the views'
// RMS, the `worst` largest first (with a fit). Empty for a camera with neither fit nor covariance.
std::string ParametersText(const CalibratedCamera& camera, std::span<const HeldIntrinsic> held, size_t worst = 3);

}  // namespace vstcal
