#include "vstcal/formats/errsim/mc_summary_json.h"

#include <cmath>

#include "vstcal/core/error.h"
#include "vstcal/json/format_check.h"

namespace vstcal {
namespace {

constexpr const char* kRegenerate = "regenerate the shard file (it was changed or truncated)";

// [count, mean, m2, m3, m4, min, max], or [count, mean, m2, min, max] without the higher moments.
OrderedJson MomentsToJson(const Moments& m, bool higher) {
  if (m.count == 0) return OrderedJson::array({0});
  if (!higher) return OrderedJson::array({m.count, m.mean, m.m2, m.min, m.max});
  return OrderedJson::array({m.count, m.mean, m.m2, m.m3, m.m4, m.min, m.max});
}

uint64_t Count(const JsonNode& node) {
  if (!node.json().is_number_unsigned()) node.Fail("expected a non-negative integer, got " + node.json().dump(), kRegenerate);
  return node.json().get<uint64_t>();
}

Moments MomentsFromJson(const JsonNode& node, bool higher) {
  const size_t n = node.ArraySize();
  Moments m;
  m.count = Count(node.at(size_t{0}));
  if (m.count == 0) {
    if (n != 1) node.Fail("an empty moment set has one number, [0]", kRegenerate);
    return m;
  }
  node.ArraySize(higher ? 7 : 5);
  m.mean = node.at(1).Number();
  m.m2 = node.at(2).NonNegativeNumber();
  const size_t extremes = higher ? 5 : 3;
  if (higher) {
    m.m3 = node.at(3).Number();
    m.m4 = node.at(4).NonNegativeNumber();
  }
  m.min = node.at(extremes).Number();
  m.max = node.at(extremes + 1).Number();
  if (m.min > m.max) node.Fail("min exceeds max", kRegenerate);
  if (m.mean < m.min || m.mean > m.max) node.Fail("the mean lies outside [min, max]", kRegenerate);
  return m;
}

}  // namespace

OrderedJson SummaryToJson(const MonteCarloSummary& summary) {
  const SummaryPlan& plan = summary.plan();
  OrderedJson j;
  j["format"] = kSummaryFormat;
  j["run_id"] = plan.run_id;
  j["total_samples"] = plan.total_samples;
  j["block_size"] = plan.block_size;
  j["histogram"] = {{"min_exponent", plan.histogram.min_exponent},
                    {"max_exponent", plan.histogram.max_exponent},
                    {"sub_bins_log2", plan.histogram.sub_bins_log2}};
  j["outputs"] = plan.output_names;
  j["percentile_outputs"] = plan.all_percentiles ? OrderedJson("all") : OrderedJson(plan.percentile_outputs);
  j["higher_moments"] = plan.higher_moments;
  j["undefined_samples"] = summary.undefined_samples();
  OrderedJson nodes = OrderedJson::array();
  for (const auto& [key, moments] : summary.nodes()) {
    OrderedJson list = OrderedJson::array();
    for (const Moments& m : moments) list.push_back(MomentsToJson(m, plan.higher_moments));
    nodes.push_back({key.first, key.second, std::move(list)});
  }
  j["nodes"] = std::move(nodes);
  OrderedJson histograms = OrderedJson::array();
  for (const LogHistogram& h : summary.histograms()) {
    OrderedJson runs = OrderedJson::array();
    size_t next = 0;
    h.ForEachBin([&](size_t bin, uint64_t count) {
      if (runs.empty() || bin != next) runs.push_back(OrderedJson::array({bin}));
      runs.back().push_back(count);
      next = bin + 1;
    });
    histograms.push_back(std::move(runs));
  }
  j["histograms"] = std::move(histograms);
  return j;
}

MonteCarloSummary SummaryFromJson(const JsonNode& root) {
  root.ExpectObject();
  CheckFormat(root, kSummaryFormat);
  SummaryPlan plan;
  plan.run_id = root.at("run_id").String();
  plan.total_samples = Count(root.at("total_samples"));
  plan.block_size = Count(root.at("block_size"));
  const JsonNode histogram = root.at("histogram");
  plan.histogram.min_exponent = histogram.at("min_exponent").Integer();
  plan.histogram.max_exponent = histogram.at("max_exponent").Integer();
  plan.histogram.sub_bins_log2 = histogram.at("sub_bins_log2").Integer();
  const JsonNode outputs = root.at("outputs");
  const size_t m = outputs.ArraySize();
  for (size_t k = 0; k < m; ++k) plan.output_names.push_back(outputs.at(k).String());
  const JsonNode percentiles = root.at("percentile_outputs");
  if (percentiles.json().is_string()) {
    if (percentiles.String() != "all") percentiles.Fail("expected \"all\" or a list of output indices", kRegenerate);
  } else {
    plan.all_percentiles = false;
    for (size_t i = 0; i < percentiles.ArraySize(); ++i) plan.percentile_outputs.push_back(Count(percentiles.at(i)));
  }
  plan.higher_moments = root.at("higher_moments").Boolean();
  try {
    plan.Validate();
  } catch (const InputError& e) {
    root.Fail(e.what(), kRegenerate);
  }

  std::map<MonteCarloSummary::NodeKey, std::vector<Moments>> nodes;
  const JsonNode nodes_node = root.at("nodes");
  for (size_t i = 0; i < nodes_node.ArraySize(); ++i) {
    const JsonNode entry = nodes_node.at(i);
    entry.ArraySize(3);
    const uint64_t level = Count(entry.at(size_t{0}));
    if (level > 64) entry.at(size_t{0}).Fail("a tree level above 64", kRegenerate);
    const MonteCarloSummary::NodeKey key{static_cast<uint32_t>(level), Count(entry.at(1))};
    const JsonNode list = entry.at(2);
    list.ArraySize(m);
    std::vector<Moments> moments;
    for (size_t k = 0; k < m; ++k) moments.push_back(MomentsFromJson(list.at(k), plan.higher_moments));
    if (!nodes.emplace(key, std::move(moments)).second) entry.Fail("repeats a node", kRegenerate);
  }
  std::vector<LogHistogram> histograms(plan.NumHistograms(), LogHistogram(plan.histogram));
  const JsonNode hist_node = root.at("histograms");
  hist_node.ArraySize(histograms.size());
  const size_t num_bins = plan.histogram.NumBins();
  for (size_t h = 0; h < histograms.size(); ++h) {
    const JsonNode runs = hist_node.at(h);
    for (size_t i = 0; i < runs.ArraySize(); ++i) {
      const JsonNode run = runs.at(i);
      const size_t length = run.ArraySize();
      if (length < 2) run.Fail("a run of bins needs its first bin and at least one count", kRegenerate);
      const uint64_t first = Count(run.at(size_t{0}));
      if (first >= num_bins || length - 1 > num_bins - first) run.Fail("names a bin beyond the histogram", kRegenerate);
      for (size_t b = 1; b < length; ++b) {
        const uint64_t count = Count(run.at(b));
        if (count > plan.total_samples) run.at(b).Fail("counts more samples than the run has", kRegenerate);
        histograms[h].AddBin(first + b - 1, count);
      }
    }
  }
  try {
    return MonteCarloSummary::FromState(std::move(plan), std::move(nodes), std::move(histograms),
                                        Count(root.at("undefined_samples")));
  } catch (const InputError& e) {
    root.Fail(e.what(), kRegenerate);
  }
}

}  // namespace vstcal
