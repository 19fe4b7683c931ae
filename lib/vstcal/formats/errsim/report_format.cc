#include "vstcal/formats/errsim/report_format.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <cstdio>
#include <sstream>

#include "vstcal/core/error.h"
#include "vstcal/errsim/budget.h"
#include "vstcal/errsim/measures.h"
#include "vstcal/formats/errsim/report_keys.h"

namespace vstcal {
namespace {


constexpr double kDeg = 180.0 / kPi;

OrderedJson StatsToJson(const OutputStatistics& s) {
  if (s.count == 0) return nullptr;
  OrderedJson j;
  j[errsim_key::kMean] = NumberOrNull(s.mean);
  j[errsim_key::kRms] = NumberOrNull(s.rms);
  j[errsim_key::kStandardDeviation] = NumberOrNull(s.standard_deviation);
  j[errsim_key::kMeanStandardError] = NumberOrNull(s.mean_standard_error);
  j[errsim_key::kMax] = NumberOrNull(s.max);
  if (s.has_percentiles) {
    j[errsim_key::kP50] = NumberOrNull(s.p50.value);
    j[errsim_key::kP95] = NumberOrNull(s.p95.value);
    j[errsim_key::kP99] = NumberOrNull(s.p99.value);
    if (!s.p50.in_range || !s.p95.in_range || !s.p99.in_range) j[errsim_key::kPercentilesOutOfRange] = true;
  }
  return j;
}

OrderedJson RateToJson(ErrorMeasure m, const OutputStatistics& s) {
  if (s.count == 0) return nullptr;
  // A rate p from N decisions: standard error √(p(1 − p)/N).
  return {{RateKey(m), s.mean}, {errsim_key::kStandardError, std::sqrt(s.mean * (1 - s.mean) / static_cast<double>(s.count))}};
}

OrderedJson TotalsToJson(const ScenarioTotals& t) {
  return {{TotalKey(Total::kImage), NumberOrNull(t.image_rms_px)},
          {TotalKey(Total::kMisregistration), NumberOrNull(t.misregistration_rms)},
          {TotalKey(Total::kMisperception), NumberOrNull(t.misperception_rms)},
          {TotalKey(Total::kWrongOcclusion), NumberOrNull(t.wrong_occlusion_rate)}};
}

// Test point k's measures, in kMeasures' order, at their MeasurePointer under `point`. A group
// starts with what `start` puts first (the misperception's systematic part, the occlusion's
// surface); a group that needs a surface the point lacks is null.
template <typename Start>
void MeasuresToJson(const ErrorOutputs& outputs, const std::vector<OutputStatistics>& stats, size_t k, const Start& start,
                    OrderedJson* point) {
  for (const MeasureDecl& d : kMeasures) {
    const std::string group(d.group);
    if (d.needs_surface && !outputs.has_surface(k)) {
      if (!point->contains(group)) (*point)[group] = nullptr;
      continue;
    }
    if (!point->contains(group)) (*point)[group] = start(d.measure);
    for (int e = 0; e < SlotsOf(d.scope); ++e) {
      const OutputStatistics& s = stats[outputs.at(k, d.measure, e)];
      (*point)[OrderedJson::json_pointer(std::string("/").append(MeasurePointer(d.measure, e)))] =
          d.unit == OutputUnit::kDecision ? RateToJson(d.measure, s) : StatsToJson(s);
    }
  }
}

// Holloway's terms of a 3-D measure, as the text summary's columns show them.
struct HollowayColumns {
  ErrorMeasure linear, lateral, depth, angular;
};
constexpr HollowayColumns kMisregistrationColumns{ErrorMeasure::kMisregistrationLinear, ErrorMeasure::kMisregistrationLateral,
                                                  ErrorMeasure::kMisregistrationDepth, ErrorMeasure::kMisregistrationAngular};
constexpr HollowayColumns kMisperceptionColumns{ErrorMeasure::kMisperceptionLinear, ErrorMeasure::kMisperceptionLateral,
                                                ErrorMeasure::kMisperceptionDepth, ErrorMeasure::kMisperceptionAngular};

const MonteCarloSummary& AllScenario(const SimulationResult& result) {
  VSTCAL_CHECK(!result.scenarios.empty() && result.scenarios[0] == "all", "the first scenario is \"all\"");
  return result.summaries[0];
}

std::string Fixed(double v, int digits) {
  if (!std::isfinite(v)) return "—";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string Pad(const std::string& s, size_t width) {
  // Count UTF-8 code points, not bytes, for alignment.
  size_t n = 0;
  for (const unsigned char c : s) n += (c & 0xc0) != 0x80;
  return s + std::string(width > n ? width - n : 0, ' ');
}


// Shares that add to 1, printed to 0.1 % so that the printed values add to 100.0 % too: each is
// the difference of the rounded running sums (a share's rounding is carried to the next row).
// The rows in `order`; NaN shares print as "—" and carry nothing.
std::vector<std::string> PercentsAddingUp(const std::vector<double>& shares) {
  std::vector<std::string> out;
  double running = 0;
  long long printed = 0;
  for (const double share : shares) {
    if (!std::isfinite(share)) {
      out.push_back(Fixed(share, 1));
      continue;
    }
    running += share;
    const long long next = std::llround(1000 * running);
    out.push_back(Fixed((next - printed) / 10.0, 1) + " %");
    printed = next;
  }
  return out;
}

OrderedJson WholeToJson(const WholeOfMeasure& w) {
  return {{errsim_key::kMeanSquare, NumberOrNull(w.mean_square)},
          {errsim_key::kPartsMeanSquare, NumberOrNull(w.parts_mean_square)},
          {errsim_key::kRemainderMeanSquare, NumberOrNull(w.remainder_mean_square)},
          {errsim_key::kRemainderShare, NumberOrNull(w.remainder_share)},
          {errsim_key::kNone, w.none}};
}

// [{"kind": "measured", "file", "format"} | {"kind": "assumed"}, …] (docs/formats.md#err-sim-report).
OrderedJson OriginsToJson(const std::vector<DistributionOrigin>& origins) {
  OrderedJson list = OrderedJson::array();
  for (const DistributionOrigin& o : origins) {
    if (o.measured()) {
      list.push_back({{errsim_key::kKind, errsim_key::kMeasured}, {errsim_key::kFile, o.file}, {errsim_key::kOriginFormat, o.format}});
    } else {
      list.push_back({{errsim_key::kKind, errsim_key::kAssumed}});
    }
  }
  return list;
}

// "measured (rig.json)", "assumed", or both joined by " + ".
std::string OriginsText(const std::vector<DistributionOrigin>& origins) {
  std::string out;
  for (const DistributionOrigin& o : origins) {
    if (!out.empty()) out.append(" + ");
    out.append(o.measured() ? std::string("measured (").append(o.file).append(")") : std::string("assumed"));
  }
  return out;
}

}  // namespace

OrderedJson ReportToJson(const ChainEvaluator& chain, const SimulationResult& result, const RunDescription& run,
                         const Provenance& provenance) {
  VSTCAL_CHECK(result.complete(), "the report needs every block of every scenario");
  const ChainModel& model = chain.model();
  const MonteCarloSummary& all = AllScenario(result);
  const ErrorOutputs outputs(model);
  const auto stats = all.AllStatistics();
  OrderedJson j;
  j[errsim_key::kFormat] = kReportFormat;
  j[errsim_key::kChain] = run.chain_path;
  j[errsim_key::kChainDigest] = run.digest;
  j[errsim_key::kLengthUnit] = LengthUnitName(model.geometry.length_unit);
  j[errsim_key::kSamples] = run.options.samples;
  j[errsim_key::kBudgetSamples] = run.options.budget ? OrderedJson(run.options.budget_samples) : OrderedJson(nullptr);
  j[errsim_key::kSeed] = run.options.seed;
  OrderedJson active = OrderedJson::array();
  for (int s = 0; s < kNumSources; ++s) {
    if (model.SourceActive(static_cast<Source>(s))) active.push_back(kSourceKeys[s]);
  }
  j[errsim_key::kSources] = {{errsim_key::kActive, active}, {errsim_key::kOnly, run.only}, {errsim_key::kWithout, run.without}};
  j[errsim_key::kUndefinedSamples] = all.undefined_samples();

  OrderedJson points = OrderedJson::array();
  for (size_t k = 0; k < outputs.num_points(); ++k) {
    const ChainTestPoint& tp = model.geometry.test_points[k];
    const uint64_t defined = stats[outputs.offset(k)].count;
    OrderedJson p;
    p[errsim_key::kName] = tp.name;
    p[errsim_key::kWorld] = MatrixToJson(tp.point_in_world);
    p[errsim_key::kUndefined] = {{errsim_key::kSamples, run.options.samples - defined},
                      {errsim_key::kRate, static_cast<double>(run.options.samples - defined) / static_cast<double>(run.options.samples)}};
    // The misperception's group starts with the error-free chain's systematic part, named as the
    // sampled terms; the occlusion's with the surface behind the point.
    auto start = [&](ErrorMeasure m) {
      OrderedJson group = OrderedJson::object();
      const auto name = [](ErrorMeasure term) { return std::string(Declaration(term).name); };
      if (Declaration(m).group == Declaration(ErrorMeasure::kMisperceptionLinear).group) {
        const Systematic& systematic = chain.systematic(k);
        group[errsim_key::kSystematic] = {{errsim_key::kOffset, MatrixToJson(systematic.offset)},
                               {name(ErrorMeasure::kMisperceptionLinear), systematic.error.linear},
                               {name(ErrorMeasure::kMisperceptionLateral), systematic.error.lateral},
                               {name(ErrorMeasure::kMisperceptionDepth), systematic.error.depth},
                               {name(ErrorMeasure::kMisperceptionAngular), kDeg * systematic.error.angular}};
      }
      if (Declaration(m).needs_surface) group[errsim_key::kSurfaceBehind] = *tp.surface_behind;
      return group;
    };
    MeasuresToJson(outputs, stats, k, start, &p);
    points.push_back(std::move(p));
  }
  j[errsim_key::kTestPoints] = std::move(points);
  OrderedJson totals = TotalsToJson(Totals(model, all, OutputSet::kFull));
  totals[std::string(kSystematicMisperceptionKey)] = SystematicMisperceptionRms(chain);
  j[errsim_key::kTotals] = std::move(totals);

  if (run.options.budget) {
    const ErrorBudget budget = Budget(model, result);
    OrderedJson entries = OrderedJson::array();
    for (const BudgetEntry& e : budget.entries) {
      OrderedJson b;
      b[errsim_key::kSource] = SourceKey(e.source);
      b[ShareKey(Total::kMisregistration)] = NumberOrNull(e.share_of_misregistration_ms);
      b[ShareKey(Total::kImage)] = NumberOrNull(e.share_of_image_ms);
      b[ShareKey(Total::kMisperception)] = NumberOrNull(e.share_of_misperception_ms);
      b[errsim_key::kAlone] = TotalsToJson(e.alone);
      b[errsim_key::kHalved] = TotalsToJson(e.halved);
      b[errsim_key::kCorrection] = SourceCorrection(e.source);
      OrderedJson terms = OrderedJson::array();
      for (const TermPart& t : e.terms) {
        terms.push_back({{errsim_key::kTerm, t.name},
                         {ShareKey(Total::kMisregistration), NumberOrNull(t.share_of_misregistration_ms)},
                         {ShareKey(Total::kImage), NumberOrNull(t.share_of_image_ms)},
                         {ShareKey(Total::kMisperception), NumberOrNull(t.share_of_misperception_ms)},
                         {errsim_key::kAlone, TotalsToJson(t.alone)},
                         {errsim_key::kOrigin, OriginsToJson(t.origins)}});
      }
      b[errsim_key::kTerms] = std::move(terms);
      b[errsim_key::kDominantTerm] = {{BudgetMeasureKey(Total::kImage), e.terms[DominantTerm(e, &TermPart::share_of_image_ms)].name},
                            {BudgetMeasureKey(Total::kMisregistration), e.terms[DominantTerm(e, &TermPart::share_of_misregistration_ms)].name},
                            {BudgetMeasureKey(Total::kMisperception), e.terms[DominantTerm(e, &TermPart::share_of_misperception_ms)].name}};
      b[errsim_key::kOrigin] = OriginsToJson(e.origins);
      entries.push_back(std::move(b));
    }
    auto ranking = [&](const std::vector<size_t>& order) {
      OrderedJson list = OrderedJson::array();
      for (const size_t i : order) list.push_back(SourceKey(budget.entries[i].source));
      return list;
    };
    j[errsim_key::kBudget] = {{errsim_key::kSamples, run.options.budget_samples},
                   {errsim_key::kWhole, {{BudgetMeasureKey(Total::kImage), WholeToJson(budget.image)},
                              {BudgetMeasureKey(Total::kMisregistration), WholeToJson(budget.misregistration)},
                              {BudgetMeasureKey(Total::kMisperception), WholeToJson(budget.misperception)}}},
                   // The default ranking is by what the user sees (issue 21 item 3); the others beside it.
                   {errsim_key::kRankedBy, BudgetMeasureKey(Total::kImage)},
                   {errsim_key::kRanking, {{BudgetMeasureKey(Total::kImage), ranking(budget.by_image)},
                                {BudgetMeasureKey(Total::kMisregistration), ranking(budget.by_misregistration)},
                                {BudgetMeasureKey(Total::kMisperception), ranking(budget.by_misperception)}}},
                   {errsim_key::kEntries, std::move(entries)}};
  } else {
    j[errsim_key::kBudget] = nullptr;
  }
  j[errsim_key::kProvenance] = ProvenanceToJson(provenance);
  return j;
}

std::string ReportText(const ChainEvaluator& chain, const SimulationResult& result, const RunDescription& run) {
  const ChainModel& model = chain.model();
  const MonteCarloSummary& all = AllScenario(result);
  const ErrorOutputs outputs(model);
  const auto stats = all.AllStatistics();
  const std::string unit(LengthUnitName(model.geometry.length_unit));
  // The test point column as wide as the longest name (names are never cut, and the columns stay aligned).
  size_t point_width = 16;
  for (const ChainTestPoint& tp : model.geometry.test_points) point_width = std::max(point_width, tp.name.size() + 2);
  std::ostringstream out;
  out << "err-sim: " << run.chain_path << ": " << run.options.samples << " samples, seed " << run.options.seed;
  if (all.undefined_samples() > 0) out << ", " << all.undefined_samples() << " with some test point undefined";
  out << "\n  image misregistration (px, overlay − video in each eye's frame):\n";
  out << "    " << Pad("test point", point_width) << Pad("eye", 7) << Pad("mean", 9) << Pad("rms", 9) << Pad("p95", 9) << Pad("p99", 9)
      << Pad("max", 9) << "undefined\n";
  for (size_t k = 0; k < outputs.num_points(); ++k) {
    for (int e = 0; e < kNumEyes; ++e) {
      const OutputStatistics& s = stats[outputs.at(k, ErrorMeasure::kImagePixel, e)];
      const double undefined = 1 - static_cast<double>(s.count) / static_cast<double>(run.options.samples);
      out << "    " << Pad(model.geometry.test_points[k].name, point_width) << Pad(std::string(kEyeNames[e]), 7)
          << Pad(Fixed(s.count ? s.mean : NAN, 2), 9) << Pad(Fixed(s.count ? s.rms : NAN, 2), 9)
          << Pad(Fixed(s.count ? s.p95.value : NAN, 2), 9) << Pad(Fixed(s.count ? s.p99.value : NAN, 2), 9)
          << Pad(Fixed(s.count ? s.max : NAN, 2), 9) << Fixed(100 * undefined, 2) << " %\n";
    }
  }
  auto measure_table = [&](const char* title, const HollowayColumns& c, bool systematic) {
    out << "  " << title << " (" << unit << "; Holloway's terms seen from the cyclopean eye, degrees):\n";
    out << "    " << Pad("test point", point_width);
    // The systematic offset's size and the visual angle it subtends from the cyclopean eye: the
    // size is the camera–eye offset at every depth, the angle is what shrinks with distance.
    if (systematic) out << Pad("systematic", 12) << Pad("its angle", 11);
    out << Pad("linear rms", 12) << Pad("p95", 9) << Pad("lateral rms", 13) << Pad("depth mean", 12) << Pad("depth rms", 11)
        << "angular rms\n";
    for (size_t k = 0; k < outputs.num_points(); ++k) {
      auto v = [&](ErrorMeasure m, double OutputStatistics::*field) {
        const OutputStatistics& s = stats[outputs.at(k, m)];
        return s.count ? s.*field : NAN;
      };
      const OutputStatistics& linear = stats[outputs.at(k, c.linear)];
      out << "    " << Pad(model.geometry.test_points[k].name, point_width);
      if (systematic) {
        out << Pad(Fixed(chain.systematic(k).error.linear, 2), 12) << Pad(Fixed(kDeg * chain.systematic(k).error.angular, 3), 11);
      }
      out << Pad(Fixed(v(c.linear, &OutputStatistics::rms), 2), 12)
          << Pad(Fixed(linear.count ? linear.p95.value : NAN, 2), 9)
          << Pad(Fixed(v(c.lateral, &OutputStatistics::rms), 2), 13)
          << Pad(Fixed(v(c.depth, &OutputStatistics::mean), 2), 12)
          << Pad(Fixed(v(c.depth, &OutputStatistics::rms), 2), 11)
          << Fixed(v(c.angular, &OutputStatistics::rms), 3) << "\n";
    }
  };
  measure_table("misregistration, the overlay against the video image of the point as the eyes see both",
                kMisregistrationColumns, false);
  measure_table("misperception, where the eyes see the point against where it is: systematic, then from the errors",
                kMisperceptionColumns, true);
  const ScenarioTotals t = Totals(model, all, OutputSet::kFull);
  out << "  totals: image " << Fixed(t.image_rms_px, 2) << " px rms, misregistration " << Fixed(t.misregistration_rms, 2)
      << " " << unit << " rms, misperception " << Fixed(t.misperception_rms, 2) << " " << unit << " rms (systematic "
      << Fixed(SystematicMisperceptionRms(chain), 2) << " " << unit << ")";
  if (std::isfinite(t.wrong_occlusion_rate)) out << ", wrong occlusion " << Fixed(100 * t.wrong_occlusion_rate, 2) << " %";
  out << "\n";
  // A display with its own field of view magnifies the video: nominal, so in the systematic part
  // (docs/math/vst-chain.md#display-fov).
  if (model.geometry.display.focal_px[0] || model.geometry.display.focal_px[1]) {
    out << "  display: its own field of view magnifies the video";
    for (int e = 0; e < kNumEyes; ++e) {
      const std::vector<double>& p = model.geometry.cameras[e].params;
      const Eigen::Vector2d focal = model.geometry.display.focal_px[e].value_or(Eigen::Vector2d(p[intrinsic::kFx], p[intrinsic::kFy]));
      out << (e ? ", " : " ") << kEyeNames[e] << " ×" << Fixed(p[intrinsic::kFx] / focal.x(), 3) << " × " << Fixed(p[intrinsic::kFy] / focal.y(), 3);
    }
    out << " (horizontal × vertical, against the camera's); part of the systematic misperception\n";
  }
  if (run.options.budget) {
    const ErrorBudget budget = Budget(model, result);
    // Each source's share of the whole chain's mean square, then what the parts leave out and the
    // whole: the rows add to 100 % (docs/math/sensitivity.md#shares-of-the-whole). Ranked by the
    // table's measure; a second measure may stand beside it (its share and its own rank).
    struct Measure {
      std::string name;    // "image misregistration"
      std::string column;  // the short column head: "image", "3-D"
      double BudgetEntry::*share;
      double TermPart::*term_share;
      double ScenarioTotals::*total;
      const WholeOfMeasure* whole;
      std::string unit;
      const std::vector<size_t>* order;
    };
    const Measure image{"image misregistration", "image", &BudgetEntry::share_of_image_ms, &TermPart::share_of_image_ms, &ScenarioTotals::image_rms_px,
                        &budget.image, "px", &budget.by_image};
    const Measure misregistration{"3-D misregistration", "3-D", &BudgetEntry::share_of_misregistration_ms, &TermPart::share_of_misregistration_ms,
                                  &ScenarioTotals::misregistration_rms, &budget.misregistration, unit, &budget.by_misregistration};
    const Measure misperception{"misperception", "share", &BudgetEntry::share_of_misperception_ms, &TermPart::share_of_misperception_ms,
                                &ScenarioTotals::misperception_rms, &budget.misperception, unit, &budget.by_misperception};
    auto table = [&](const std::string& what, const Measure& m, const Measure* beside) {
      out << "  error budget of " << what << " (" << run.options.budget_samples
          << " samples per scenario), ranked by each source's share of the whole chain's mean square of the " << m.name;
      if (beside) out << "; the " << beside->name << "'s share and rank beside it";
      if (m.whole->none) out << " (none: the whole chain's is 0 to rounding)";
      out << ":\n";
      size_t name_width = std::string("interactions and means in common").size() + 2;
      for (const BudgetEntry& e : budget.entries) {
        for (const TermPart& term : e.terms) name_width = std::max(name_width, term.name.size() + 4);
      }
      out << "    " << Pad("#", 3) << Pad("source", name_width) << Pad(m.column, 9);
      if (beside) out << Pad(beside->column, 9) << Pad(beside->column + " #", 6);
      out << Pad("alone", 22) << "all, this halved\n";
      std::vector<const BudgetEntry*> shown;
      int silent = 0;
      for (const size_t i : *m.order) {
        const BudgetEntry& e = budget.entries[i];
        if (!beside && e.alone.*m.total == 0) {  // the misperception table: sources that do not touch what the eyes see
          ++silent;
          continue;
        }
        shown.push_back(&e);
      }
      std::vector<double> shares, beside_shares;
      for (const BudgetEntry* e : shown) shares.push_back(e->*m.share), beside_shares.push_back(beside ? e->*beside->share : 0.0);
      shares.push_back(m.whole->remainder_share);
      beside_shares.push_back(beside ? beside->whole->remainder_share : 0.0);
      const std::vector<std::string> percents = PercentsAddingUp(shares), beside_percents = PercentsAddingUp(beside_shares);
      auto cell = [](bool none, const std::string& percent) { return none ? std::string("none") : percent; };
      // Built by appending: GCC 12's -Wrestrict misfires on "literal" + std::string.
      auto rms = [&](const ScenarioTotals& totals) {
        std::string text = Fixed(totals.*m.total, 2).append(" ").append(m.unit);
        if (beside) text.append(" ").append(Fixed(totals.*beside->total, 2)).append(" ").append(beside->unit);
        return text;
      };
      int rank = 1;
      for (size_t r = 0; r < shown.size(); ++r) {
        const BudgetEntry& e = *shown[r];
        out << "    " << Pad(std::to_string(rank++), 3) << Pad(std::string(SourceKey(e.source)), name_width)
            << Pad(cell(m.whole->none, percents[r]), 9);
        if (beside) {
          const auto at = std::find(beside->order->begin(), beside->order->end(), static_cast<size_t>(&e - budget.entries.data()));
          out << Pad(cell(beside->whole->none, beside_percents[r]), 9) << Pad(std::to_string(at - beside->order->begin() + 1), 6);
        }
        out << Pad(rms(e.alone), 22) << rms(e.halved) << "\n";
        // Its terms alone, largest share first, when it has several: the tree source → term.
        std::vector<size_t> terms(e.terms.size());
        std::iota(terms.begin(), terms.end(), size_t{0});
        auto key = [&](size_t i) { return std::isfinite(e.terms[i].*m.term_share) ? e.terms[i].*m.term_share : -1.0; };
        std::stable_sort(terms.begin(), terms.end(), [&](size_t a, size_t b) { return key(a) > key(b); });
        size_t small = 0;
        for (const size_t i : terms) {
          if (e.terms.size() < 2) break;
          const TermPart& term = e.terms[i];
          // Terms below what the column shows (0.0 %) are counted, not listed.
          if (!m.whole->none && !(term.*m.term_share >= 0.0005)) {
            ++small;
            continue;
          }
          out << "    " << Pad("", 3) << Pad("  " + term.name, name_width)
              << Pad(m.whole->none ? std::string("none") : Fixed(100 * (term.*m.term_share), 1) + " %", 9);
          if (beside) {
            out << Pad(beside->whole->none ? std::string("none") : Fixed(100 * (term.*beside->term_share), 1) + " %", 9) << Pad("", 6);
          }
          out << rms(term.alone) << "\n";
        }
        if (small > 0 && small < e.terms.size()) {
          out << "    " << Pad("", 3) << "  (" << small << " more term" << (small > 1 ? "s" : "") << " below 0.05 %)\n";
        }
        // No advice against a share of nothing; the advice is the source's, aimed at its dominant term.
        if (rank <= 4 && !m.whole->none) {
          out << "       → ";
          if (e.terms.size() > 1) out << "mostly " << e.terms[DominantTerm(e, m.term_share)].name << ": ";
          out << SourceCorrection(e.source) << "\n";
        }
      }
      out << "    " << Pad("", 3) << Pad("interactions and means in common", name_width)
          << (beside ? Pad(cell(m.whole->none, percents.back()), 9) + cell(beside->whole->none, beside_percents.back())
                     : cell(m.whole->none, percents.back()));
      out << "\n    " << Pad("", 3) << Pad("whole chain", name_width) << Pad(m.whole->none ? "none" : "100.0 %", 9);
      if (beside) out << Pad(beside->whole->none ? "none" : "100.0 %", 9) << Pad("", 6);
      out << rms(t) << "\n";
      if (silent > 0) {
        out << "    (" << silent << " other source" << (silent > 1 ? "s do" : " does")
            << " not move what the eyes see of the physical world: 0 here)\n";
      }
    };
    // The default ranking is by what the user sees: the overlay's error in each eye's image
    // (issue 21 item 3), the 3-D misregistration's rank beside it; the misperception's below.
    table("what the user sees", image, &misregistration);
    table("the misperception (from the errors, beside the systematic part)", misperception, nullptr);
    // Where each source's σ's come from, beside what it does alone (in the image, then in 3-D): a
    // budget built from measurements reads differently from one built from guesses. In the default
    // ranking's order, as the first table.
    out << "  where the distributions come from (measured: a calibration's file; assumed: typed into the chain), "
           "each source alone, in the order of what the user sees:\n";
    for (const size_t i : budget.by_image) {
      const BudgetEntry& e = budget.entries[i];
      const std::string key(SourceKey(e.source));
      const std::string alone =
          Fixed(e.alone.image_rms_px, 2) + " px " + Fixed(e.alone.misregistration_rms, 2) + " " + std::string(unit);
      out << "    " << key << ": ";
      const bool uniform = std::all_of(e.terms.begin(), e.terms.end(), [&](const TermPart& p) { return p.origins == e.origins; });
      if (uniform) {
        out << OriginsText(e.origins) << ", " << alone << "\n";
        continue;
      }
      out << alone;
      for (const TermPart& p : e.terms) {
        out << "; " << p.name.substr(key.size() + 1) << ": " << OriginsText(p.origins);
      }
      out << "\n";
    }
  }
  return out.str();
}

}  // namespace vstcal
