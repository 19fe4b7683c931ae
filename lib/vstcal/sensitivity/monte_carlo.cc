#include "vstcal/sensitivity/monte_carlo.h"

#include <mutex>
#include <vector>

#include "vstcal/core/parallel.h"

namespace vstcal {

SummaryPlan MakePlan(const Model& model, const MonteCarloOptions& options) {
  SummaryPlan plan;
  plan.output_names = model.output_names();
  plan.total_samples = options.samples;
  plan.block_size = options.block_size;
  plan.histogram = options.histogram;
  plan.run_id = options.run_id;
  plan.Validate();
  return plan;
}

MonteCarloSummary RunMonteCarlo(const ParameterSpace& space, const Model& model, const MonteCarloOptions& options) {
  RequireCompatible(space, model);
  const SummaryPlan plan = MakePlan(model, options);
  const BlockRange range = ShardBlocks(plan, options.shard, options.shards);
  const UnitPoints points(options.sampling, space.size());
  const size_t n = space.size(), m = model.num_outputs();

  MonteCarloSummary summary(plan);
  std::mutex summary_mutex;
  // Blocks are combined in a fixed tree by the summary itself, so the order they finish in is free.
  ParallelFor(range.end - range.begin, options.threads, [&](size_t task) {
    const uint64_t block = range.begin + task;
    const uint64_t first = block * plan.block_size;
    const size_t count = static_cast<size_t>(std::min(plan.block_size, plan.total_samples - first));
    std::vector<double> u(count * n), theta(n), y(m);
    points.Fill(first, count, u.data());
    BlockAccumulator accumulator(plan);
    for (size_t s = 0; s < count; ++s) {
      space.ToParameters(&u[s * n], theta.data());
      if (model.Evaluate(theta.data(), y.data())) {
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

}  // namespace vstcal
