// err-sim's outputs (docs/formats.md#err-sim-report): the report of a complete run — per test point
// and eye the statistics of image misregistration and of perceived-space (Holloway) errors, the
// occlusion decisions, each source's contribution, and the ranked error budget with seed 001's
// corrections — as JSON and as a text summary; and the shard file of a partial run.
#pragma once

#include <string>
#include <vector>

#include "vstcal/errsim/simulation.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal::errsim {

inline constexpr std::string_view kReportFormat = "vstcal/err-sim-report@1";
inline constexpr std::string_view kShardFormat = "vstcal/err-sim-shard@1";

// Aggregates of one scenario: RMS over test points and eyes of the pixel error, RMS over test
// points of Holloway's linear error, and the mean rate of wrong occlusion decisions (NaN without
// occlusion points).
struct ScenarioTotals {
  double image_rms_px = 0;
  double perceived_rms = 0;
  double wrong_occlusion_rate = 0;
};
ScenarioTotals Totals(const ChainModel& model, const sensitivity::MonteCarloSummary& summary);

struct BudgetEntry {
  Source source;
  ScenarioTotals alone, halved;
  double share_of_image_ms = 0;      // alone image MS / Σ over sources
  double share_of_perceived_ms = 0;  // alone perceived MS / Σ over sources
};
// Entries ranked by share of the perceived-space mean square (ties by image share).
std::vector<BudgetEntry> Budget(const ChainModel& model, const SimulationResult& result);

struct RunDescription {
  std::string chain_path;  // as given on the command line
  std::string digest;
  std::vector<std::string> only, without;
  SimulationOptions options;
};

io::OrderedJson ReportToJson(const ChainModel& model, const SimulationResult& result, const RunDescription& run,
                             const io::Provenance& provenance);
std::string ReportText(const ChainModel& model, const SimulationResult& result, const RunDescription& run);

io::OrderedJson ShardToJson(const SimulationResult& result, const RunDescription& run, const io::Provenance& provenance);
// Reads a shard file; `run` receives its description (checked by the caller against the chain).
SimulationResult ShardFromJson(const io::JsonDocument& doc, RunDescription* run);

}  // namespace vstcal::errsim
