// Monte Carlo summary statistics that merge EXACTLY across shards: one machine and any split into
// shards give bit-identical numbers (docs/math/sensitivity.md#mergeable).
//
// The N samples are cut into fixed blocks of `block_size` (block b holds samples
// [b·B, min((b + 1)·B, N))). A block's moments (moments.h) are accumulated in sample order; blocks
// are folded into the total strictly in block order, whoever computed them and whenever they
// arrive: a block that arrives early waits (pending) until all blocks before it are folded. So the
// sequence of floating-point operations — hence every bit — is fixed by (N, B) alone.
// Percentiles come from fixed-bin histograms (log_histogram.h) whose integer counts add in any order.
//
// err-sim's `--shard i/N` runs its block range (ShardBlocks) and writes ToJson; `merge` reads the
// shard files (FromJson) and Merges them in any order.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "vstcal/sensitivity/log_histogram.h"
#include "vstcal/sensitivity/moments.h"

namespace vstcal::sensitivity {

// What fixes the bits: shards merge only when their plans are equal.
struct SummaryPlan {
  std::vector<std::string> output_names;
  uint64_t total_samples = 0;
  uint64_t block_size = 1024;
  HistogramSpec histogram;
  // Identifies the run (err-sim: the chain file's digest, seed, sampling method). Shards of
  // different runs are refused at merge time even when their sizes match.
  std::string run_id;

  uint64_t NumBlocks() const { return (total_samples + block_size - 1) / block_size; }
  void Validate() const;  // InputError: no outputs, N = 0 or block_size = 0
  bool operator==(const SummaryPlan&) const = default;
};

// The blocks [begin, end) that shard i of `shards` runs: contiguous and balanced.
struct BlockRange {
  uint64_t begin = 0;
  uint64_t end = 0;
};
BlockRange ShardBlocks(const SummaryPlan& plan, uint64_t shard, uint64_t shards);  // InputError unless shard < shards

// One block's samples, accumulated in sample order.
class BlockAccumulator {
 public:
  explicit BlockAccumulator(const SummaryPlan& plan);
  // One defined sample: output k at y[k·stride] (stride > 1 for samples evaluated lane-interleaved).
  void Add(const double* y, size_t stride = 1);
  void AddUndefined() { ++undefined_; }

 private:
  friend class MonteCarloSummary;
  const HistogramBinner* binner_;
  std::vector<Moments> moments_;          // per output
  std::vector<uint32_t> bins_;            // histogram bin per (sample, output)
  uint64_t undefined_ = 0;
};

struct OutputStatistics {
  std::string name;
  uint64_t count = 0;  // defined samples
  double mean = 0;
  double standard_deviation = 0;  // unbiased
  double rms = 0;
  double min = 0;
  double max = 0;
  double mean_standard_error = 0;                // σ / √N
  double standard_deviation_standard_error = 0;  // moments.h
  Percentile p50, p95, p99;
};

class MonteCarloSummary {
 public:
  explicit MonteCarloSummary(SummaryPlan plan);

  const SummaryPlan& plan() const { return plan_; }
  // Adds block b (InputError if b is outside the plan or already present).
  void AddBlock(uint64_t block, const BlockAccumulator& accumulator);
  // Adds every block of `other` (InputError for a different plan or a block present in both).
  void Merge(const MonteCarloSummary& other);

  bool complete() const { return folded_blocks_ == plan_.NumBlocks(); }
  uint64_t undefined_samples() const { return undefined_; }
  // Statistics of output k; InputError naming the first missing block unless complete().
  OutputStatistics Statistics(size_t output) const;
  std::vector<OutputStatistics> AllStatistics() const;
  // The p-quantile of output k from its histogram (complete() required), 0 < p < 1.
  Percentile Quantile(size_t output, double p) const;

  // Raw state, for serialization (mc_summary_json.h).
  uint64_t folded_blocks() const { return folded_blocks_; }
  const std::vector<Moments>& folded() const { return folded_; }
  const std::map<uint64_t, std::vector<Moments>>& pending() const { return pending_; }
  const std::vector<LogHistogram>& histograms() const { return histograms_; }
  // Rebuilds a summary from serialized state; checks it is consistent (InputError otherwise).
  static MonteCarloSummary FromState(SummaryPlan plan, uint64_t folded_blocks, std::vector<Moments> folded,
                                     std::map<uint64_t, std::vector<Moments>> pending,
                                     std::vector<LogHistogram> histograms, uint64_t undefined);

 private:
  bool Has(uint64_t block) const { return block < folded_blocks_ || pending_.count(block) > 0; }
  void FoldReadyBlocks();
  void RequireComplete() const;

  SummaryPlan plan_;
  uint64_t folded_blocks_ = 0;                        // blocks [0, folded_blocks_) are in folded_
  std::vector<Moments> folded_;                       // per output
  std::map<uint64_t, std::vector<Moments>> pending_;  // blocks waiting for their predecessors
  std::vector<LogHistogram> histograms_;              // per output
  uint64_t undefined_ = 0;
};

}  // namespace vstcal::sensitivity
