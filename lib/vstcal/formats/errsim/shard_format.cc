#include "vstcal/formats/errsim/shard_format.h"

#include "vstcal/json/format_check.h"
#include "vstcal/formats/errsim/mc_summary_json.h"

namespace vstcal {
namespace {

constexpr const char* kShardRegenerate = "regenerate the shard file (it was changed or truncated)";

uint64_t ShardCount(const JsonNode& n) {
  if (!n.json().is_number_unsigned()) n.Fail("expected a non-negative integer, got " + n.json().dump(), kShardRegenerate);
  return n.json().get<uint64_t>();
}

}  // namespace

OrderedJson ShardToJson(const SimulationResult& result, const RunDescription& run, const Provenance& provenance) {
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
    scenarios.push_back({{"name", result.scenarios[i]}, {"summary", SummaryToJson(result.summaries[i])}});
  }
  j["scenarios"] = std::move(scenarios);
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

SimulationResult ShardFromJson(const JsonDocument& doc, RunDescription* run) {
  const JsonNode root = doc.root();
  root.ExpectObject();
  CheckFormat(root, kShardFormat);
  run->chain_path = root.at("chain").String();
  run->digest = root.at("chain_digest").String();
  run->options.samples = ShardCount(root.at("samples"));
  run->options.budget_samples = ShardCount(root.at("budget_samples"));
  run->options.seed = ShardCount(root.at("seed"));
  run->options.budget = root.at("budget").Boolean();
  run->options.block_size = ShardCount(root.at("block_size"));
  for (const char* key : {"only", "without"}) {
    const JsonNode list = root.at(key);
    std::vector<std::string>& out = std::string(key) == "only" ? run->only : run->without;
    for (size_t i = 0; i < list.ArraySize(); ++i) {
      out.push_back(list.at(i).String());
      if (!SourceFromKey(out.back())) list.at(i).Fail("unknown error source \"" + out.back() + "\"", kShardRegenerate);
    }
  }
  const JsonNode shard = root.at("shard");
  shard.ArraySize(2);
  run->options.shard = ShardCount(shard.at(size_t{0}));
  run->options.shards = ShardCount(shard.at(1));
  if (run->options.shards == 0 || run->options.shard >= run->options.shards) {
    shard.Fail("is not i/N with 0 ≤ i < N", kShardRegenerate);
  }
  SimulationResult result;
  const JsonNode scenarios = root.at("scenarios");
  for (size_t i = 0; i < scenarios.ArraySize(); ++i) {
    result.scenarios.push_back(scenarios.at(i).at("name").String());
    result.summaries.push_back(SummaryFromJson(scenarios.at(i).at("summary")));
  }
  return result;
}

}  // namespace vstcal
