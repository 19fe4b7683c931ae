#include "vstcal/formats/camera/residual_stats_json.h"

#include <string>

namespace vstcal {

OrderedJson ResidualStatsToJson(const ResidualStats& s, std::string_view unit_suffix, std::string_view count_key) {
  const std::string unit(unit_suffix);
  return {{"rms" + unit, s.rms_px}, {"max" + unit, s.max_px}, {std::string(count_key), s.n_points}};
}

}  // namespace vstcal
