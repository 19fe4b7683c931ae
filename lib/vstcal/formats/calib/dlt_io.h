// The "dlt" block calib-dlt adds to its camera@1 output (docs/formats.md#camera).
#pragma once

#include <optional>

#include "vstcal/estimators/decompose.h"
#include "vstcal/calib/dlt.h"
#include "vstcal/json/json_writer.h"

namespace vstcal {

// Solver, singular values of the normalized system, point-cloud extents, conditioning and the
// seed 001 Eq. 13 quantities of the solved P.
OrderedJson DltDiagnosticsToJson(const DltResult& dlt, const std::optional<Eq13Decomposition>& eq13,
                                 const DltOptions& options);

std::string_view DltSolverName(DltOptions::Solver solver);

}  // namespace vstcal
