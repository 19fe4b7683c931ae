// The refinement's robust loss as a Ceres loss function (docs/math/uncertainty.md#robust): the
// solve minimises Σ ρ(‖r̃‖²) over weighted residuals r̃ = √w r, and the information weighs each
// point's rows by ρ′(‖r̃‖²).
#pragma once

#include <memory>

#include <ceres/loss_function.h>

#include "vstcal/estimators/refine_options.h"

namespace vstcal {

// Huber or Cauchy at options.loss_scale_px; nullptr for least squares.
std::unique_ptr<ceres::LossFunction> MakeLoss(const RefineOptions& options);

}  // namespace vstcal
