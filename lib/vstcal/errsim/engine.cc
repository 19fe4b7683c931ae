#include "vstcal/errsim/engine.h"

#include <algorithm>
#include <mutex>
#include <vector>

#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/holloway.h"
#include "vstcal/errsim/sampler.h"
#include "vstcal/sensitivity/parallel.h"

namespace vstcal::errsim {

sensitivity::SummaryPlan ChainPlan(const ChainModel& model, const ChainMonteCarloOptions& options) {
  sensitivity::SummaryPlan plan;
  plan.output_names = ErrorOutputs(model).names();
  plan.total_samples = options.samples;
  plan.block_size = options.block_size;
  plan.run_id = options.run_id;
  plan.Validate();
  return plan;
}

sensitivity::MonteCarloSummary RunChainMonteCarlo(const ChainModel& model, const ChainMonteCarloOptions& options) {
  const sensitivity::SummaryPlan plan = ChainPlan(model, options);
  const sensitivity::BlockRange range = sensitivity::ShardBlocks(plan, options.shard, options.shards);
  const ChainEvaluator chain(model);
  const ErrorOutputs outputs(model);
  const ThetaSampler sampler(model, options.seed);
  const size_t n = sampler.size(), m = outputs.size();

  sensitivity::MonteCarloSummary summary(plan);
  std::mutex summary_mutex;
  sensitivity::ParallelFor(range.end - range.begin, options.threads, [&](size_t task) {
    const uint64_t block = range.begin + task;
    const uint64_t first = block * plan.block_size;
    const size_t count = static_cast<size_t>(std::min(plan.block_size, plan.total_samples - first));
    std::vector<double> theta(count * n), y(m);
    ChainSample<double> sample(chain.num_points());
    sampler.Fill(first, count, theta.data());
    sensitivity::BlockAccumulator accumulator(plan);
    for (size_t s = 0; s < count; ++s) {
      const double* row = &theta[s * n];
      chain.Evaluate(row, &sample);
      if (outputs.Measure(chain, sample, row, y.data())) {
        accumulator.Add(y.data());
      } else {
        accumulator.AddUndefined();
      }
    }
    const std::lock_guard<std::mutex> lock(summary_mutex);
    summary.AddBlock(block, accumulator);
  });
  return summary;
}

}  // namespace vstcal::errsim
