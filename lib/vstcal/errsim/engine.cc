#include "vstcal/errsim/engine.h"

#include <algorithm>
#include <mutex>
#include <vector>

#include "vstcal/errsim/sample_measurer.h"
#include "vstcal/errsim/sampler.h"
#include "vstcal/core/parallel.h"

namespace vstcal {

SummaryPlan ChainPlan(const ChainModel& model, const ChainMonteCarloOptions& options) {
  const ErrorOutputs outputs(model, options.outputs);
  SummaryPlan plan;
  plan.output_names = outputs.names();
  plan.all_percentiles = false;
  plan.higher_moments = false;  // the report gives no standard error of σ
  for (size_t k = 0; k < outputs.size(); ++k) {
    if (outputs.is_headline(k)) plan.percentile_outputs.push_back(k);
  }
  plan.total_samples = options.samples;
  plan.block_size = options.block_size;
  plan.run_id = options.run_id;
  plan.Validate();
  return plan;
}

MonteCarloSummary RunChainMonteCarlo(const ChainModel& model, const ChainMonteCarloOptions& options) {
  const SummaryPlan plan = ChainPlan(model, options);
  const BlockRange range = ShardBlocks(plan, options.shard, options.shards);
  const ChainEvaluator chain(model);
  const ErrorOutputs outputs(model, options.outputs);
  const ThetaSampler sampler(model, options.seed);
  const size_t n = sampler.size(), m = outputs.size();
  constexpr size_t kLanes = SampleMeasurer::kLanes;

  MonteCarloSummary summary(plan);
  std::mutex summary_mutex;
  ParallelFor(range.end - range.begin, options.threads, [&](size_t task) {
    const uint64_t block = range.begin + task;
    const uint64_t first = block * plan.block_size;
    const size_t count = static_cast<size_t>(std::min(plan.block_size, plan.total_samples - first));
    // Samples are measured four at a time; a last partial group computes samples past the block
    // (each a function of its own index) and drops them. θ is drawn a few groups at a time, so
    // that it stays in the cache between the draws and the chain.
    const size_t groups = (count + kLanes - 1) / kLanes;
    constexpr size_t kGroupsPerDraw = 32;
    std::vector<SimdDouble> theta(kGroupsPerDraw * n);
    std::vector<double> y(kLanes * m);
    std::vector<uint8_t> defined(m);
    SampleMeasurer measurer(chain, outputs);
    BlockAccumulator accumulator(plan);
    for (size_t g = 0; g < groups; ++g) {
      if (g % kGroupsPerDraw == 0) sampler.FillLanes(first + kLanes * g, std::min(kGroupsPerDraw, groups - g), theta.data());
      const size_t lanes = std::min(kLanes, count - g * kLanes);
      const int incomplete = measurer.MeasureLanes(&theta[(g % kGroupsPerDraw) * n], y.data(), defined.data());
      // The dropped lanes past the block are not counted as incomplete.
      int counted = incomplete;
      if (lanes < kLanes) {
        counted = 0;
        for (size_t l = 0; l < lanes; ++l) {
          bool all = true;
          for (size_t k = 0; k < m; ++k) all = all && ((defined[k] >> l) & 1);
          counted += !all;
        }
      }
      accumulator.AddLanes(y.data(), defined.data(), lanes, static_cast<uint64_t>(counted));
    }
    const std::lock_guard<std::mutex> lock(summary_mutex);
    summary.AddBlock(block, accumulator);
  });
  return summary;
}

}  // namespace vstcal
