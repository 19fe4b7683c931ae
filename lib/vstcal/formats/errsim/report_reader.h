// What err-sim check reads of a vstcal/err-sim-report@3 (or @2) (docs/formats.md#err-sim-report): the run
// it describes and the metrics that carry a Monte Carlo standard error (errsim/report_check.h).
// The rest of the report (percentiles, totals, budget) is not read, nor checked.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vstcal/errsim/report_check.h"
#include "vstcal/json/json_reader.h"

namespace vstcal {

struct ReportForCheck {
  std::string chain;         // as the run was given it
  std::string chain_digest;
  std::string length_unit;
  uint64_t samples = 0, seed = 0;
  std::vector<std::string> only, without;  // source keys
  std::vector<MonteCarloMetric> metrics;   // per test point in order, measures in kCheckedMeasures' order;
                                           // a statistic of no defined sample (null) is left out
};

// InputError "<file>: <field>: …; …" for another format, a missing field or a bad value.
ReportForCheck ReadReportForCheck(const JsonDocument& document);

}  // namespace vstcal
