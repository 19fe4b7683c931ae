// Residual statistics (scene/fit.h) as JSON: the one writer every format uses. Formats spell the
// keys differently (stereo@1 "rms_px"… "n_points"; registration@1 "rms"+unit… "n"), so the unit
// suffix and the count's key are the caller's.
#pragma once

#include <string_view>

#include "vstcal/json/json_writer.h"
#include "vstcal/scene/fit.h"

namespace vstcal {

OrderedJson ResidualStatsToJson(const ResidualStats& s, std::string_view unit_suffix = "_px",
                                std::string_view count_key = "n_points");

}  // namespace vstcal
