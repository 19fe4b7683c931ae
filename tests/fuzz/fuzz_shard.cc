// vstcal/err-sim-shard@2: the reader (`err-sim merge`) and the writer's fixed point
// (docs/formats.md#err-sim-shard).
#include "harness.h"
#include "vstcal/formats/errsim/shard_format.h"

namespace {

std::string ShardPass(const std::string& text) {
  using namespace vstcal;
  RunDescription run;
  const SimulationResult result = ShardFromJson(JsonDocument::Parse(text, "fuzz.json"), &run);
  return DumpJson(ShardToJson(result, run, fuzz::kProvenance));
}

}  // namespace

VSTCAL_FUZZ_TARGET(shard, text) {
  ShardPass(text);
  vstcal::fuzz::RequireFixedPoint(text, ShardPass);
}
