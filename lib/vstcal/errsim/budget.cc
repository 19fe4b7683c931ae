#include "vstcal/errsim/budget.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const MonteCarloSummary& ScenarioSummary(const SimulationResult& result, const std::string& name) {
  for (size_t i = 0; i < result.scenarios.size(); ++i) {
    if (result.scenarios[i] == name) return result.summaries[i];
  }
  throw InternalError("no scenario " + name);
}

bool HasScenario(const SimulationResult& result, const std::string& name) {
  return std::find(result.scenarios.begin(), result.scenarios.end(), name) != result.scenarios.end();
}

// a / b, NaN unless both are finite and b > 0 (0 when b is 0: no source contributes).
double Share(double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b)) return kNaN;
  return b > 0 ? a / b : 0.0;
}

}  // namespace

ScenarioTotals Totals(const ChainModel& model, const MonteCarloSummary& summary, OutputSet set) {
  const ErrorOutputs outputs(model, set);
  double image = 0, misregistration = 0, misperception = 0, wrong = 0;
  int n_wrong = 0;
  const size_t points = outputs.num_points();
  // Mean squares of the magnitudes: RMS² of each output; NaN when a point has no defined sample.
  auto ms = [&](size_t k) {
    const auto s = summary.Statistics(k);
    return s.count > 0 ? s.rms * s.rms : kNaN;
  };
  for (size_t k = 0; k < points; ++k) {
    const size_t o = outputs.offset(k);
    image += ms(o + ErrorOutputs::kPixel) + ms(o + ErrorOutputs::kPixel + 1);
    misregistration += ms(o + outputs.misregistration() + ErrorOutputs::kLinear);
    misperception += ms(o + outputs.misperception() + ErrorOutputs::kLinear);
    if (outputs.has_occlusion(k)) {
      for (int e = 0; e < kNumEyes; ++e) {
        const auto s = summary.Statistics(o + outputs.occlusion() + e);
        wrong += s.count > 0 ? s.mean : kNaN;
        ++n_wrong;
      }
    }
  }
  return {std::sqrt(image / (2.0 * points)), std::sqrt(misregistration / points), std::sqrt(misperception / points),
          n_wrong > 0 ? wrong / n_wrong : kNaN};
}

double SystematicMisperceptionRms(const ChainEvaluator& chain) {
  double ms = 0;
  for (size_t k = 0; k < chain.num_points(); ++k) ms += std::pow(chain.systematic(k).error.linear, 2);
  return std::sqrt(ms / static_cast<double>(chain.num_points()));
}

ErrorBudget Budget(const ChainModel& model, const SimulationResult& result) {
  ErrorBudget budget;
  double image = 0, misregistration = 0, misperception = 0;
  for (int s = 0; s < kNumSources; ++s) {
    const Source source = static_cast<Source>(s);
    const std::string key(SourceKey(source));
    if (!HasScenario(result, "alone:" + key)) continue;
    BudgetEntry e{source, Totals(model, ScenarioSummary(result, "alone:" + key), OutputSet::kTotals),
                  Totals(model, ScenarioSummary(result, "halved:" + key), OutputSet::kTotals)};
    image += e.alone.image_rms_px * e.alone.image_rms_px;
    misregistration += e.alone.misregistration_rms * e.alone.misregistration_rms;
    misperception += e.alone.misperception_rms * e.alone.misperception_rms;
    budget.entries.push_back(e);
  }
  for (BudgetEntry& e : budget.entries) {
    e.share_of_image_ms = Share(e.alone.image_rms_px * e.alone.image_rms_px, image);
    e.share_of_misregistration_ms = Share(e.alone.misregistration_rms * e.alone.misregistration_rms, misregistration);
    e.share_of_misperception_ms = Share(e.alone.misperception_rms * e.alone.misperception_rms, misperception);
  }
  // NaN shares (undefined totals) rank last.
  auto rank = [&](auto share, auto tie) {
    std::vector<size_t> order(budget.entries.size());
    std::iota(order.begin(), order.end(), size_t{0});
    auto key = [&](double v) { return std::isfinite(v) ? v : -1.0; };
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      const BudgetEntry &x = budget.entries[a], &y = budget.entries[b];
      if (key(share(x)) != key(share(y))) return key(share(x)) > key(share(y));
      return key(tie(x)) > key(tie(y));
    });
    return order;
  };
  budget.by_misregistration = rank([](const BudgetEntry& e) { return e.share_of_misregistration_ms; },
                                   [](const BudgetEntry& e) { return e.share_of_image_ms; });
  budget.by_misperception = rank([](const BudgetEntry& e) { return e.share_of_misperception_ms; },
                                 [](const BudgetEntry& e) { return e.share_of_misregistration_ms; });
  return budget;
}

}  // namespace vstcal
