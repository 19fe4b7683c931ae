#include "vstcal/sensitivity/mc_summary_json.h"

#include <cmath>

#include "vstcal/core/error.h"

namespace vstcal::sensitivity {
namespace {

io::OrderedJson MomentsToJson(const Moments& m) {
  if (m.count == 0) return io::OrderedJson::array({0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  return io::OrderedJson::array({m.count, m.mean, m.m2, m.m3, m.m4, m.min, m.max});
}

io::OrderedJson MomentsListToJson(const std::vector<Moments>& list) {
  io::OrderedJson out = io::OrderedJson::array();
  for (const Moments& m : list) out.push_back(MomentsToJson(m));
  return out;
}

uint64_t Count(const io::JsonNode& node) {
  if (!node.json().is_number_unsigned()) node.Fail("expected a non-negative integer", "write a count");
  return node.json().get<uint64_t>();
}

Moments MomentsFromJson(const io::JsonNode& node) {
  node.ArraySize(7);
  Moments m;
  m.count = Count(node.at(size_t{0}));
  if (m.count == 0) return m;
  m.mean = node.at(1).Number();
  m.m2 = node.at(2).NonNegativeNumber();
  m.m3 = node.at(3).Number();
  m.m4 = node.at(4).NonNegativeNumber();
  m.min = node.at(5).Number();
  m.max = node.at(6).Number();
  if (m.min > m.max) node.Fail("min exceeds max", "regenerate the shard file");
  return m;
}

std::vector<Moments> MomentsListFromJson(const io::JsonNode& node, size_t m) {
  node.ArraySize(m);
  std::vector<Moments> list;
  for (size_t k = 0; k < m; ++k) list.push_back(MomentsFromJson(node.at(k)));
  return list;
}

}  // namespace

io::OrderedJson SummaryToJson(const MonteCarloSummary& summary) {
  const SummaryPlan& plan = summary.plan();
  io::OrderedJson j;
  j["format"] = kSummaryFormat;
  j["run_id"] = plan.run_id;
  j["total_samples"] = plan.total_samples;
  j["block_size"] = plan.block_size;
  j["histogram"] = {{"min_magnitude", plan.histogram.min_magnitude},
                    {"max_magnitude", plan.histogram.max_magnitude},
                    {"bins_per_decade", plan.histogram.bins_per_decade}};
  j["outputs"] = plan.output_names;
  j["undefined_samples"] = summary.undefined_samples();
  j["folded_blocks"] = summary.folded_blocks();
  j["folded"] = MomentsListToJson(summary.folded());
  io::OrderedJson pending = io::OrderedJson::array();
  for (const auto& [block, moments] : summary.pending()) {
    pending.push_back({{"block", block}, {"moments", MomentsListToJson(moments)}});
  }
  j["pending"] = std::move(pending);
  io::OrderedJson histograms = io::OrderedJson::array();
  for (const LogHistogram& h : summary.histograms()) {
    io::OrderedJson bins = io::OrderedJson::array();
    for (size_t b = 0; b < h.counts().size(); ++b) {
      if (h.counts()[b] > 0) bins.push_back({b, h.counts()[b]});
    }
    histograms.push_back(std::move(bins));
  }
  j["histograms"] = std::move(histograms);
  return j;
}

MonteCarloSummary SummaryFromJson(const io::JsonNode& root) {
  root.ExpectObject();
  const io::JsonNode format = root.at("format");
  if (format.String() != kSummaryFormat) {
    format.Fail("is '" + format.String() + "'", std::string("expected '") + kSummaryFormat + "'");
  }
  SummaryPlan plan;
  plan.run_id = root.at("run_id").String();
  plan.total_samples = Count(root.at("total_samples"));
  plan.block_size = Count(root.at("block_size"));
  const io::JsonNode histogram = root.at("histogram");
  plan.histogram.min_magnitude = histogram.at("min_magnitude").PositiveNumber();
  plan.histogram.max_magnitude = histogram.at("max_magnitude").PositiveNumber();
  plan.histogram.bins_per_decade = histogram.at("bins_per_decade").PositiveInteger();
  const io::JsonNode outputs = root.at("outputs");
  const size_t m = outputs.ArraySize();
  for (size_t k = 0; k < m; ++k) plan.output_names.push_back(outputs.at(k).String());
  plan.Validate();

  std::map<uint64_t, std::vector<Moments>> pending;
  const io::JsonNode pending_node = root.at("pending");
  for (size_t i = 0; i < pending_node.ArraySize(); ++i) {
    const io::JsonNode entry = pending_node.at(i);
    const uint64_t block = Count(entry.at("block"));
    if (!pending.emplace(block, MomentsListFromJson(entry.at("moments"), m)).second) {
      entry.at("block").Fail("repeats a block", "regenerate the shard file");
    }
  }
  std::vector<LogHistogram> histograms(m, LogHistogram(plan.histogram));
  const io::JsonNode hist_node = root.at("histograms");
  hist_node.ArraySize(m);
  for (size_t k = 0; k < m; ++k) {
    const io::JsonNode bins = hist_node.at(k);
    for (size_t i = 0; i < bins.ArraySize(); ++i) {
      const io::JsonNode pair = bins.at(i);
      pair.ArraySize(2);
      const uint64_t bin = Count(pair.at(size_t{0}));
      if (bin >= plan.histogram.NumBins()) pair.Fail("names a bin beyond the histogram", "regenerate the shard file");
      histograms[k].AddBin(bin, Count(pair.at(1)));
    }
  }
  return MonteCarloSummary::FromState(std::move(plan), Count(root.at("folded_blocks")),
                                      MomentsListFromJson(root.at("folded"), m), std::move(pending),
                                      std::move(histograms), Count(root.at("undefined_samples")));
}

}  // namespace vstcal::sensitivity
