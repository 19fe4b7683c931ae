// The "dlt" block calib-dlt adds to its camera@1 output (docs/formats.md#camera).
#pragma once

#include <optional>

#include "vstcal/estimators/decompose.h"
#include "vstcal/estimators/dlt.h"
#include "vstcal/json/json_writer.h"

namespace vstcal {

// Solver, singular values of the normalized system, point-cloud extents, conditioning and the
// seed 001 Eq. 13 quantities of the solved P.
OrderedJson DltDiagnosticsToJson(const DltResult& dlt, const std::optional<Eq13Decomposition>& eq13,
                                 const DltOptions& options);

// The DLT's first-order uncertainty (docs/formats.md#camera-dlt-uncertainty): σ̂ and its degrees of
// freedom, Cov(vec P) in its gauge, and the σ's of the decomposed K, rotation and camera centre
// (`covariance` over fx … camera_from_world.tz, at `camera_from_world`).
OrderedJson DltUncertaintyToJson(const DltUncertainty& u, const ParameterCovariance& covariance,
                                 const Rigid3d& camera_from_world);

std::string_view DltSolverName(DltOptions::Solver solver);

}  // namespace vstcal
