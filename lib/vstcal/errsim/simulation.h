// err-sim's Monte Carlo run: the chain with the chosen sources, and for the error budget each
// active source alone and each halved, all on common random numbers (sample i draws the same
// value of a parameter in every scenario). Statistics are the sensitivity module's mergeable
// summaries, so a run split into shards (--shard i/N, on any machines) and merged gives the same
// bits as one run, whatever the thread count (docs/math/vst-chain.md#monte-carlo).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/sensitivity/mc_summary.h"

namespace vstcal {

struct Scenario {
  std::string name;  // "all", "alone:<source>", "halved:<source>"
  ChainModel model;
};

// One error term of a source as the budget's tree ranks it: a row of kTerms, both eyes together
// ("display.screen_shift", "tracking.latency", "camera_extrinsic.rig.rotation",
// "camera_intrinsic.lens"). With a rig covariance the right camera's rotation and translation are
// one correlated draw, so camera_extrinsic's rotation and translation are one term, "pose".
struct TermGroup {
  std::string name;
  std::vector<Term> terms;
};
// The terms of `source` with some random or non-zero parameter, in kTerms order.
std::vector<TermGroup> ActiveTerms(const ChainModel& model, Source source);
// Where the distributions of `terms` came from: the distinct origins of their active parameters, in
// θ order of first appearance (issue 21 item 4).
std::vector<DistributionOrigin> OriginsOf(const ChainModel& model, const std::vector<Term>& terms);
// The chain with only the parameters of `group`'s terms.
ChainModel WithTermsOnly(const ChainModel& model, const TermGroup& group);

// "all" (model as given), then for every active source, when `budget` is set, "alone:<s>" and
// "halved:<s>" (every draw of s multiplied by ½), then for every active source with more than one
// active term "term:<term>" for each of them (that term alone).
std::vector<Scenario> MakeScenarios(const ChainModel& model, bool budget);

// The chain with only the sources in `only` (all when empty), minus those in `without`.
ChainModel SelectSources(const ChainModel& model, const std::vector<Source>& only, const std::vector<Source>& without);

// A digest of everything that determines the run's numbers (geometry, cameras, every parameter's
// distribution): shards of different chains are never merged. 16 hex digits (FNV-1a 64).
std::string ChainDigest(const ChainModel& model);

struct SimulationOptions {
  uint64_t samples = 0;         // "all" scenario
  uint64_t budget_samples = 0;  // each budget scenario
  uint64_t seed = 0;
  bool budget = true;
  unsigned threads = 0;  // 0: all cores; the result does not depend on it
  uint64_t shard = 0, shards = 1;
  uint64_t block_size = 1024;
};

// How a run was asked for: what its report and shard files record.
struct RunDescription {
  std::string chain_path;  // as given on the command line
  std::string digest;
  std::vector<std::string> only, without;
  SimulationOptions options;
};

struct SimulationResult {
  std::vector<std::string> scenarios;
  std::vector<MonteCarloSummary> summaries;  // one per scenario
  bool complete() const;
};

// Called with the fraction done (0…1) as the run goes.
using Progress = std::function<void(double fraction)>;

SimulationResult RunSimulation(const std::vector<Scenario>& scenarios, const SimulationOptions& options,
                               const std::string& digest, const Progress& progress = {});

// The scenarios' summaries before any sample, with the plans RunSimulation gives them: what
// `merge` checks shard files against and merges them into.
SimulationResult EmptySimulation(const std::vector<Scenario>& scenarios, const SimulationOptions& options,
                                 const std::string& digest);

// Adds `other`'s blocks (InputError for shards of a different run or overlapping blocks).
void MergeSimulation(SimulationResult* into, const SimulationResult& other);

}  // namespace vstcal
