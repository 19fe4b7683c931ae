// err-sim check (docs/tools/err-sim.md#check): each Monte Carlo metric of an accepted report
// against the same metric of a new one — a metric may rise by at most an allowance, judged with the
// two reports' standard errors (sensitivity/rise_check.h) so that sampling noise fails no build.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vstcal/core/check.h"
#include "vstcal/errsim/outputs.h"
#include "vstcal/sensitivity/rise_check.h"

namespace vstcal {

// The measures checked at every test point, in kMeasures' order (its `checked` column): those of
// vstcal/err-sim-report@3 (@2 alike) that carry a standard error and for which a rise is worse —
// each stats object's mean (with mean_standard_error) and each eye's wrong-occlusion rate (with
// standard_error). Left out: the signed depth means (a bias of either sign; depth_abs is checked),
// and RMS, percentiles, maxima and the totals, which the report gives without one.
struct CheckedMeasure {
  ErrorMeasure measure;
  int eye = 0;       // of a per-eye measure
  std::string name;  // SummaryName: "image.left.pixel_px", "occlusion.left.wrong_rate"
};
const std::vector<CheckedMeasure>& CheckedMeasures();

// One metric of a report: a test point's measure, the estimate and its Monte Carlo standard error.
struct MonteCarloMetric {
  std::string point;
  std::string measure;  // a CheckedMeasures() name
  double value = 0;
  double standard_error = 0;
  std::string name() const { return point + "." + measure; }
};

// An allowance for one metric ("<point>.<measure>") or one measure at every test point.
struct RiseRule {
  std::string name;
  RiseAllowance allowance;
};

struct MetricCheck {
  std::string name;
  double accepted = 0, accepted_standard_error = 0;
  double fresh = 0, fresh_standard_error = 0;  // meaningful when `present`
  bool present = true;                          // the new report has the metric
  RiseJudgement judgement;                      // verdict kFail when not present
  CheckResult result;                           // the verdict and its numbers, one line
};

// One check per metric of `accepted`, in its order. The allowance of a metric is the rule naming it,
// else the rule naming its measure, else `by_default`. A metric the new report lacks (a test point
// renamed or removed, a statistic with no defined sample) fails. InputError for a rule naming no
// metric of `accepted` and no measure (with a did-you-mean), or one name given twice.
std::vector<MetricCheck> CheckMetrics(std::span<const MonteCarloMetric> accepted, std::span<const MonteCarloMetric> fresh,
                                      const RiseAllowance& by_default, std::span<const RiseRule> rules, double z);

}  // namespace vstcal
