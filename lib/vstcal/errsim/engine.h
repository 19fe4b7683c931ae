// The Monte Carlo loop of err-sim run: θ from the fast sampler (sampler.h), the chain and its error
// measures four samples at a time (sample_measurer.h), accumulated four lanes at a time into the
// sensitivity module's mergeable summary in fixed blocks — so the numbers depend only on (samples,
// block size, seed), never on the thread count or the shard split. Equivalent to
// RunMonteCarlo over ErrorModel, without a std::function call and a buffer lookup per
// sample, and with the faster sampler. Memory: one block's buffers per thread and the summary's
// (mc_summary.h), independent of the number of samples.
#pragma once

#include <cstdint>
#include <string>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/errsim/measures.h"
#include "vstcal/sensitivity/mc_summary.h"

namespace vstcal {

struct ChainMonteCarloOptions {
  uint64_t samples = 0;
  uint64_t seed = 0;
  uint64_t block_size = 1024;
  unsigned threads = 0;  // 0: all cores
  uint64_t shard = 0, shards = 1;
  std::string run_id;
  OutputSet outputs = OutputSet::kFull;
};

// The summary's plan: the outputs of `options.outputs`, percentiles for those that want them.
SummaryPlan ChainPlan(const ChainModel& model, const ChainMonteCarloOptions& options);

// Runs the blocks of shard `shard` of `shards`.
MonteCarloSummary RunChainMonteCarlo(const ChainModel& model, const ChainMonteCarloOptions& options);

}  // namespace vstcal
