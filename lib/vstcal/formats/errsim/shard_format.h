// vstcal/err-sim-shard@2 (docs/formats.md#err-sim-shard): the partial state of `err-sim run
// --shard i/N` — the run's description and one mergeable Monte Carlo summary per scenario
// (vstcal/mc-summary@2). Its size grows with the number of outputs and, slowly, the number of
// blocks (log₂ of it), never with the samples themselves.
#pragma once

#include <string_view>

#include "vstcal/errsim/simulation.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

inline constexpr std::string_view kShardFormat = "vstcal/err-sim-shard@2";

OrderedJson ShardToJson(const SimulationResult& result, const RunDescription& run, const Provenance& provenance);
// Reads a shard file; `run` receives its description (checked by the caller against the chain).
// InputError naming the file and field for anything malformed.
SimulationResult ShardFromJson(const JsonDocument& doc, RunDescription* run);

}  // namespace vstcal
