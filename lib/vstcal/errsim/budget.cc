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
    image += ms(outputs.at(k, ErrorMeasure::kImagePixel, 0)) + ms(outputs.at(k, ErrorMeasure::kImagePixel, 1));
    misregistration += ms(outputs.at(k, ErrorMeasure::kMisregistrationLinear));
    misperception += ms(outputs.at(k, ErrorMeasure::kMisperceptionLinear));
    if (outputs.has_surface(k)) {
      for (int e = 0; e < kNumEyes; ++e) {
        const auto s = summary.Statistics(outputs.at(k, ErrorMeasure::kWrongOcclusion, e));
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
  for (int s = 0; s < kNumSources; ++s) {
    const Source source = static_cast<Source>(s);
    const std::string key(SourceKey(source));
    if (!HasScenario(result, "alone:" + key)) continue;
    BudgetEntry e{source, Totals(model, ScenarioSummary(result, "alone:" + key), OutputSet::kTotals),
                  Totals(model, ScenarioSummary(result, "halved:" + key), OutputSet::kTotals), {}};
    const std::vector<TermGroup> terms = ActiveTerms(model, source);
    std::vector<Term> all_terms;
    for (const TermGroup& t : terms) {
      e.terms.push_back({t.name, terms.size() == 1 ? e.alone
                                                   : Totals(model, ScenarioSummary(result, "term:" + t.name), OutputSet::kTotals)});
      e.terms.back().origins = OriginsOf(model, t.terms);
      all_terms.insert(all_terms.end(), t.terms.begin(), t.terms.end());
    }
    e.origins = OriginsOf(model, all_terms);
    budget.entries.push_back(std::move(e));
  }
  const ScenarioTotals all = Totals(model, ScenarioSummary(result, "all"), OutputSet::kFull);
  // What "zero to rounding" means for each measure: 1e-9 of the image's size (px), of the test
  // points' RMS distance from the head (length unit); a mean square below its square is rounding.
  const ChainGeometry& g = model.geometry;
  double image_scale = 0, length_scale = 0;
  for (const Camera& c : g.cameras) image_scale = std::max<double>({image_scale, 1.0 * c.image_size.width, 1.0 * c.image_size.height});
  const Rigid3d hmd_from_world = g.hmd_from_tracker * g.tracker_from_world;
  for (const ChainTestPoint& tp : g.test_points) length_scale += (hmd_from_world * tp.point_in_world).squaredNorm();
  length_scale = std::sqrt(length_scale / std::max<size_t>(1, g.test_points.size()));
  auto whole = [&](double ScenarioTotals::*total, double BudgetEntry::*share, double TermPart::*term_share, double scale) {
    WholeOfMeasure w;
    w.mean_square = all.*total * (all.*total);
    for (const BudgetEntry& e : budget.entries) w.parts_mean_square += e.alone.*total * (e.alone.*total);
    w.remainder_mean_square = w.mean_square - w.parts_mean_square;
    w.none = std::isfinite(w.mean_square) && w.mean_square <= std::pow(1e-9 * scale, 2);
    // The remainder's share is 1 − Σ shares, so that the rows add to 1 to the last bit.
    double sum = 0;
    for (BudgetEntry& e : budget.entries) {
      e.*share = w.none ? kNaN : Share(e.alone.*total * (e.alone.*total), w.mean_square);
      sum += e.*share;
      for (TermPart& t : e.terms) t.*term_share = w.none ? kNaN : Share(t.alone.*total * (t.alone.*total), w.mean_square);
    }
    w.remainder_share = w.none || !std::isfinite(sum) || !(w.mean_square > 0) ? kNaN : 1.0 - sum;
    return w;
  };
  budget.image = whole(&ScenarioTotals::image_rms_px, &BudgetEntry::share_of_image_ms, &TermPart::share_of_image_ms, image_scale);
  budget.misregistration = whole(&ScenarioTotals::misregistration_rms, &BudgetEntry::share_of_misregistration_ms,
                                 &TermPart::share_of_misregistration_ms, length_scale);
  budget.misperception = whole(&ScenarioTotals::misperception_rms, &BudgetEntry::share_of_misperception_ms,
                               &TermPart::share_of_misperception_ms, length_scale);
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
  budget.by_image = rank([](const BudgetEntry& e) { return e.share_of_image_ms; },
                         [](const BudgetEntry& e) { return e.share_of_misregistration_ms; });
  return budget;
}

size_t DominantTerm(const BudgetEntry& e, double TermPart::*share) {
  size_t best = 0;
  for (size_t i = 1; i < e.terms.size(); ++i) {
    const double x = e.terms[i].*share, y = e.terms[best].*share;
    if (std::isfinite(x) && (!std::isfinite(y) || x > y)) best = i;
  }
  return best;
}

}  // namespace vstcal
