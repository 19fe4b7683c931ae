// Plain Monte Carlo of a model: draw θ from the parameter space, evaluate, summarise. The result is
// a MonteCarloSummary (mc_summary.h): bit-identical for any thread count and any shard split.
#pragma once

#include <cstdint>
#include <string>

#include "vstcal/sensitivity/mc_summary.h"
#include "vstcal/sensitivity/model.h"
#include "vstcal/sensitivity/parameter_space.h"
#include "vstcal/sensitivity/unit_points.h"

namespace vstcal {

struct MonteCarloOptions {
  uint64_t samples = 100000;
  uint64_t block_size = 1024;  // part of the plan: changing it changes the last bits
  SamplingOptions sampling;
  HistogramSpec histogram;
  std::string run_id;  // identifies the run in shard files; see SummaryPlan
  unsigned threads = 0;  // 0 → all cores; the result does not depend on it
  uint64_t shard = 0;   // run blocks ShardBlocks(plan, shard, shards) only
  uint64_t shards = 1;
};

// The plan a run with these options produces (its outputs named after the model's).
SummaryPlan MakePlan(const Model& model, const MonteCarloOptions& options);

// Sample i uses point i of the unit cube (unit_points.h): θ = Q(u). Undefined evaluations are
// counted in undefined_samples() and left out of every statistic.
MonteCarloSummary RunMonteCarlo(const ParameterSpace& space, const Model& model, const MonteCarloOptions& options);

}  // namespace vstcal
