#include "vstcal/errsim/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "vstcal/core/error.h"
#include "vstcal/errsim/holloway.h"
#include "vstcal/json/format_check.h"
#include "vstcal/sensitivity/mc_summary_json.h"

namespace vstcal::errsim {
namespace {

using io::OrderedJson;
using sensitivity::OutputStatistics;

const double kNaN = std::numeric_limits<double>::quiet_NaN();

OrderedJson NumberOrNull(double v) { return std::isfinite(v) ? OrderedJson(v) : OrderedJson(nullptr); }

OrderedJson StatsToJson(const OutputStatistics& s) {
  if (s.count == 0) return nullptr;
  OrderedJson j;
  j["mean"] = s.mean;
  j["rms"] = s.rms;
  j["p50"] = s.p50.value;
  j["p95"] = s.p95.value;
  j["p99"] = s.p99.value;
  j["max"] = s.max;
  j["standard_deviation"] = s.standard_deviation;
  j["mean_standard_error"] = s.mean_standard_error;
  if (!s.p50.in_range || !s.p95.in_range || !s.p99.in_range) j["percentiles_out_of_range"] = true;
  return j;
}

OrderedJson RateToJson(const OutputStatistics& s) {
  if (s.count == 0) return nullptr;
  // A rate p from N decisions: standard error √(p(1 − p)/N).
  return {{"wrong_rate", s.mean}, {"standard_error", std::sqrt(s.mean * (1 - s.mean) / static_cast<double>(s.count))}};
}

OrderedJson TotalsToJson(const ScenarioTotals& t) {
  return {{"image_rms_px", t.image_rms_px}, {"perceived_rms", t.perceived_rms},
          {"wrong_occlusion_rate", NumberOrNull(t.wrong_occlusion_rate)}};
}

const sensitivity::MonteCarloSummary& ScenarioSummary(const SimulationResult& result, const std::string& name) {
  for (size_t i = 0; i < result.scenarios.size(); ++i) {
    if (result.scenarios[i] == name) return result.summaries[i];
  }
  throw InternalError("no scenario " + name);
}

bool HasScenario(const SimulationResult& result, const std::string& name) {
  return std::find(result.scenarios.begin(), result.scenarios.end(), name) != result.scenarios.end();
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

}  // namespace

ScenarioTotals Totals(const ChainModel& model, const sensitivity::MonteCarloSummary& summary) {
  const ErrorOutputs outputs(model);
  ScenarioTotals t;
  double image = 0, perceived = 0, wrong = 0;
  int n_wrong = 0;
  const size_t points = model.geometry.test_points.size();
  for (size_t k = 0; k < points; ++k) {
    const size_t o = outputs.offset(k);
    for (const size_t eye_output : {o + 0, o + 2}) image += std::pow(summary.Statistics(eye_output).rms, 2);
    perceived += std::pow(summary.Statistics(o + 4).rms, 2);
    if (outputs.has_occlusion(k)) {
      wrong += summary.Statistics(o + 9).mean + summary.Statistics(o + 10).mean;
      n_wrong += 2;
    }
  }
  t.image_rms_px = std::sqrt(image / (2.0 * points));
  t.perceived_rms = std::sqrt(perceived / points);
  t.wrong_occlusion_rate = n_wrong > 0 ? wrong / n_wrong : kNaN;
  return t;
}

std::vector<BudgetEntry> Budget(const ChainModel& model, const SimulationResult& result) {
  std::vector<BudgetEntry> entries;
  double image_sum = 0, perceived_sum = 0;
  for (int s = 0; s < kNumSources; ++s) {
    const Source source = static_cast<Source>(s);
    const std::string key(SourceKey(source));
    if (!HasScenario(result, "alone:" + key)) continue;
    BudgetEntry e{source, Totals(model, ScenarioSummary(result, "alone:" + key)),
                  Totals(model, ScenarioSummary(result, "halved:" + key))};
    image_sum += e.alone.image_rms_px * e.alone.image_rms_px;
    perceived_sum += e.alone.perceived_rms * e.alone.perceived_rms;
    entries.push_back(e);
  }
  for (BudgetEntry& e : entries) {
    e.share_of_image_ms = image_sum > 0 ? e.alone.image_rms_px * e.alone.image_rms_px / image_sum : 0;
    e.share_of_perceived_ms = perceived_sum > 0 ? e.alone.perceived_rms * e.alone.perceived_rms / perceived_sum : 0;
  }
  std::stable_sort(entries.begin(), entries.end(), [](const BudgetEntry& a, const BudgetEntry& b) {
    if (a.share_of_perceived_ms != b.share_of_perceived_ms) return a.share_of_perceived_ms > b.share_of_perceived_ms;
    return a.share_of_image_ms > b.share_of_image_ms;
  });
  return entries;
}

OrderedJson ReportToJson(const ChainModel& model, const SimulationResult& result, const RunDescription& run,
                         const io::Provenance& provenance) {
  VSTCAL_CHECK(result.complete(), "the report needs every block of every scenario");
  const sensitivity::MonteCarloSummary& all = ScenarioSummary(result, "all");
  const ErrorOutputs outputs(model);
  const auto stats = all.AllStatistics();
  OrderedJson j;
  j["format"] = kReportFormat;
  j["chain"] = run.chain_path;
  j["chain_digest"] = run.digest;
  j["length_unit"] = LengthUnitName(model.geometry.length_unit);
  j["samples"] = run.options.samples;
  j["budget_samples"] = run.options.budget ? OrderedJson(run.options.budget_samples) : OrderedJson(nullptr);
  j["seed"] = run.options.seed;
  OrderedJson active = OrderedJson::array();
  for (int s = 0; s < kNumSources; ++s) {
    if (model.SourceActive(static_cast<Source>(s))) active.push_back(kSourceKeys[s]);
  }
  j["sources"] = {{"active", active}, {"only", run.only}, {"without", run.without}};
  j["undefined_samples"] = all.undefined_samples();

  OrderedJson points = OrderedJson::array();
  for (size_t k = 0; k < model.geometry.test_points.size(); ++k) {
    const TestPoint& tp = model.geometry.test_points[k];
    const size_t o = outputs.offset(k);
    OrderedJson p;
    p["name"] = tp.name;
    p["world"] = io::MatrixToJson(tp.point_in_world);
    p["image"] = {{"left", {{"pixel_px", StatsToJson(stats[o + 0])}}}, {"right", {{"pixel_px", StatsToJson(stats[o + 2])}}}};
    OrderedJson perceived;
    perceived["left"] = {{"angular_deg", StatsToJson(stats[o + 1])}};
    perceived["right"] = {{"angular_deg", StatsToJson(stats[o + 3])}};
    perceived["linear"] = StatsToJson(stats[o + 4]);
    perceived["lateral"] = StatsToJson(stats[o + 5]);
    perceived["depth"] = StatsToJson(stats[o + 6]);
    perceived["depth_abs"] = StatsToJson(stats[o + 7]);
    perceived["angular_deg"] = StatsToJson(stats[o + 8]);
    p["perceived"] = std::move(perceived);
    p["occlusion"] = outputs.has_occlusion(k)
                         ? OrderedJson{{"surface_behind", *tp.surface_behind},
                                       {"left", RateToJson(stats[o + 9])},
                                       {"right", RateToJson(stats[o + 10])}}
                         : OrderedJson(nullptr);
    points.push_back(std::move(p));
  }
  j["test_points"] = std::move(points);
  j["totals"] = TotalsToJson(Totals(model, all));

  if (run.options.budget) {
    OrderedJson budget = OrderedJson::array();
    int rank = 1;
    for (const BudgetEntry& e : Budget(model, result)) {
      OrderedJson b;
      b["rank"] = rank++;
      b["source"] = SourceKey(e.source);
      b["share_of_perceived_ms"] = e.share_of_perceived_ms;
      b["share_of_image_ms"] = e.share_of_image_ms;
      b["alone"] = TotalsToJson(e.alone);
      b["halved"] = TotalsToJson(e.halved);
      b["correction"] = SourceCorrection(e.source);
      budget.push_back(std::move(b));
    }
    j["budget"] = {{"ranked_by", "share_of_perceived_ms"}, {"entries", std::move(budget)}};
  } else {
    j["budget"] = nullptr;
  }
  j["provenance"] = io::ProvenanceToJson(provenance);
  return j;
}

std::string ReportText(const ChainModel& model, const SimulationResult& result, const RunDescription& run) {
  const sensitivity::MonteCarloSummary& all = ScenarioSummary(result, "all");
  const ErrorOutputs outputs(model);
  const auto stats = all.AllStatistics();
  const std::string unit(LengthUnitName(model.geometry.length_unit));
  std::ostringstream out;
  out << "err-sim: " << run.chain_path << ": " << run.options.samples << " samples, seed " << run.options.seed;
  if (all.undefined_samples() > 0) out << ", " << all.undefined_samples() << " undefined (a point behind a virtual camera)";
  out << "\n  image misregistration (px, virtual − real in the video frame):\n";
  out << "    " << Pad("test point", 16) << Pad("eye", 7) << Pad("mean", 9) << Pad("rms", 9) << Pad("p95", 9) << Pad("p99", 9) << "max\n";
  for (size_t k = 0; k < model.geometry.test_points.size(); ++k) {
    for (int e = 0; e < kNumEyes; ++e) {
      const OutputStatistics& s = stats[outputs.offset(k) + 2 * e];
      out << "    " << Pad(model.geometry.test_points[k].name, 16) << Pad(std::string(kEyeNames[e]), 7) << Pad(Fixed(s.mean, 2), 9)
          << Pad(Fixed(s.rms, 2), 9) << Pad(Fixed(s.p95.value, 2), 9) << Pad(Fixed(s.p99.value, 2), 9) << Fixed(s.max, 2) << "\n";
    }
  }
  out << "  perceived space (Holloway; " << unit << ", angles in degrees at the cyclopean eye):\n";
  out << "    " << Pad("test point", 16) << Pad("linear rms", 12) << Pad("p95", 9) << Pad("lateral rms", 13) << Pad("depth mean", 12)
      << Pad("depth rms", 11) << Pad("angular rms", 13) << "wrong occlusion\n";
  for (size_t k = 0; k < model.geometry.test_points.size(); ++k) {
    const size_t o = outputs.offset(k);
    std::string occlusion = "—";
    if (outputs.has_occlusion(k)) occlusion = Fixed(100 * 0.5 * (stats[o + 9].mean + stats[o + 10].mean), 2) + " %";
    out << "    " << Pad(model.geometry.test_points[k].name, 16) << Pad(Fixed(stats[o + 4].rms, 2), 12)
        << Pad(Fixed(stats[o + 4].p95.value, 2), 9) << Pad(Fixed(stats[o + 5].rms, 2), 13) << Pad(Fixed(stats[o + 6].mean, 2), 12)
        << Pad(Fixed(stats[o + 6].rms, 2), 11) << Pad(Fixed(stats[o + 8].rms, 3), 13) << occlusion << "\n";
  }
  const ScenarioTotals t = Totals(model, all);
  out << "  totals: image " << Fixed(t.image_rms_px, 2) << " px rms, perceived " << Fixed(t.perceived_rms, 2) << " " << unit
      << " rms";
  if (std::isfinite(t.wrong_occlusion_rate)) out << ", wrong occlusion " << Fixed(100 * t.wrong_occlusion_rate, 2) << " %";
  out << "\n";
  if (run.options.budget) {
    out << "  error budget (" << run.options.budget_samples << " samples per scenario), ranked by share of perceived mean square:\n";
    out << "    " << Pad("#", 3) << Pad("source", 26) << Pad("perceived", 11) << Pad("image", 9) << Pad("alone", 20)
        << Pad("all, this halved", 20) << "\n";
    int rank = 1;
    for (const BudgetEntry& e : Budget(model, result)) {
      out << "    " << Pad(std::to_string(rank++), 3) << Pad(std::string(SourceKey(e.source)), 26)
          << Pad(Fixed(100 * e.share_of_perceived_ms, 1) + " %", 11) << Pad(Fixed(100 * e.share_of_image_ms, 1) + " %", 9)
          << Pad(Fixed(e.alone.perceived_rms, 2) + " " + unit + " " + Fixed(e.alone.image_rms_px, 2) + " px", 20)
          << Fixed(e.halved.perceived_rms, 2) + " " + unit + " " + Fixed(e.halved.image_rms_px, 2) + " px" << "\n";
      out << "       → " << SourceCorrection(e.source) << "\n";
    }
  }
  return out.str();
}

OrderedJson ShardToJson(const SimulationResult& result, const RunDescription& run, const io::Provenance& provenance) {
  OrderedJson j;
  j["format"] = kShardFormat;
  j["chain"] = run.chain_path;
  j["chain_digest"] = run.digest;
  j["samples"] = run.options.samples;
  j["budget_samples"] = run.options.budget_samples;
  j["seed"] = run.options.seed;
  j["budget"] = run.options.budget;
  j["block_size"] = run.options.block_size;
  j["only"] = run.only;
  j["without"] = run.without;
  j["shard"] = {run.options.shard, run.options.shards};
  OrderedJson scenarios = OrderedJson::array();
  for (size_t i = 0; i < result.scenarios.size(); ++i) {
    scenarios.push_back({{"name", result.scenarios[i]}, {"summary", sensitivity::SummaryToJson(result.summaries[i])}});
  }
  j["scenarios"] = std::move(scenarios);
  j["provenance"] = io::ProvenanceToJson(provenance);
  return j;
}

SimulationResult ShardFromJson(const io::JsonDocument& doc, RunDescription* run) {
  const io::JsonNode root = doc.root();
  root.ExpectObject();
  io::CheckFormat(root, kShardFormat);
  run->chain_path = root.at("chain").String();
  run->digest = root.at("chain_digest").String();
  auto count = [](const io::JsonNode& n) {
    if (!n.json().is_number_unsigned()) n.Fail("expected a non-negative integer", "regenerate the shard file");
    return n.json().get<uint64_t>();
  };
  run->options.samples = count(root.at("samples"));
  run->options.budget_samples = count(root.at("budget_samples"));
  run->options.seed = count(root.at("seed"));
  run->options.budget = root.at("budget").Boolean();
  run->options.block_size = count(root.at("block_size"));
  for (const char* key : {"only", "without"}) {
    const io::JsonNode list = root.at(key);
    std::vector<std::string>& out = std::string(key) == "only" ? run->only : run->without;
    for (size_t i = 0; i < list.ArraySize(); ++i) out.push_back(list.at(i).String());
  }
  const io::JsonNode shard = root.at("shard");
  shard.ArraySize(2);
  run->options.shard = count(shard.at(size_t{0}));
  run->options.shards = count(shard.at(1));
  SimulationResult result;
  const io::JsonNode scenarios = root.at("scenarios");
  for (size_t i = 0; i < scenarios.ArraySize(); ++i) {
    result.scenarios.push_back(scenarios.at(i).at("name").String());
    result.summaries.push_back(sensitivity::SummaryFromJson(scenarios.at(i).at("summary")));
  }
  return result;
}

}  // namespace vstcal::errsim
