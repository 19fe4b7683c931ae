// Monte Carlo summary statistics that merge EXACTLY across shards: one machine and any split into
// shards give bit-identical numbers (docs/math/sensitivity.md#mergeable).
//
// The N samples are cut into fixed blocks of `block_size` (block b holds samples
// [b·B, min((b + 1)·B, N))). A block's moments are power sums about one of its own values, four
// running sums (one per lane of four consecutive samples) combined in lane order: a function of the
// block's samples alone. Blocks are then combined in a fixed binary tree over the block indices
// (node (ℓ, i) covers blocks [i·2^ℓ, (i + 1)·2^ℓ); its moments are its left child's merged with its
// right child's, or its left child's when the right one lies beyond the last block), whoever
// computed them and in whatever order they arrive. So every bit is fixed by (N, B) and the samples,
// and a summary holds at most a few nodes per tree level: its memory grows with log N, not N.
// Percentiles come from fixed-bin histograms (log_histogram.h) whose integer counts add in any
// order, kept only for the outputs that ask for them.
//
// err-sim's `--shard i/N` runs its block range (ShardBlocks) and writes SummaryToJson; `merge`
// reads the shard files (SummaryFromJson) and Merges them in any order.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "vstcal/core/simd_double.h"
#include "vstcal/sensitivity/log_histogram.h"
#include "vstcal/sensitivity/moments.h"

namespace vstcal {

// What fixes the bits: shards merge only when their plans are equal.
struct SummaryPlan {
  std::vector<std::string> output_names;
  // The outputs that get percentiles (a histogram), in increasing order; every output when
  // `all_percentiles` (the default).
  bool all_percentiles = true;
  std::vector<size_t> percentile_outputs;
  // Whether to keep M₃ and M₄ (for the standard error of σ, which err-sim's reports do not give):
  // without them the sums cost a quarter less and M₃ = M₄ = 0.
  bool higher_moments = true;
  uint64_t total_samples = 0;
  uint64_t block_size = 1024;
  HistogramSpec histogram;
  // Identifies the run (err-sim: the chain file's digest, seed, sampling method). Shards of
  // different runs are refused at merge time even when their sizes match.
  std::string run_id;

  uint64_t NumBlocks() const { return (total_samples + block_size - 1) / block_size; }
  // The histogram index of output k, or −1 when it has none.
  int HistogramOf(size_t output) const;
  size_t NumHistograms() const { return all_percentiles ? output_names.size() : percentile_outputs.size(); }
  size_t HistogramOutput(size_t h) const { return all_percentiles ? h : percentile_outputs[h]; }
  void Validate() const;  // InputError: no outputs, N = 0, block_size = 0 or not a multiple of 4, bad indices
  bool operator==(const SummaryPlan&) const = default;
};

// The blocks [begin, end) that shard i of `shards` runs: contiguous and balanced.
struct BlockRange {
  uint64_t begin = 0;
  uint64_t end = 0;
};
BlockRange ShardBlocks(const SummaryPlan& plan, uint64_t shard, uint64_t shards);  // InputError unless shard < shards

// One block's samples, accumulated in sample order. Sample j of the block goes to lane j mod 4.
class BlockAccumulator {
 public:
  static constexpr size_t kLanes = SimdDouble::kLanes;

  explicit BlockAccumulator(const SummaryPlan& plan);
  // Four consecutive samples of the block (the block's sample count so far a multiple of 4):
  // output k of lane l at y[kLanes·k + l], defined where bit l of defined[k] is set. Only the
  // first `count` lanes are samples (the block's last group may be partial). `incomplete` of them
  // have some output undefined.
  void AddLanes(const double* y, const uint8_t* defined, size_t count, uint64_t incomplete);
  // One sample with every output defined: output k at y[k·stride].
  void Add(const double* y, size_t stride = 1);
  // One sample with no output defined.
  void AddUndefined();

  uint64_t samples() const { return samples_; }  // at most the plan's block size

 private:
  friend class MonteCarloSummary;
  void AddOne(size_t output, size_t lane, double value);
  std::vector<Moments> Finish() const;  // per output

  const SummaryPlan* plan_;
  size_t num_outputs_;
  // Per output: the shift c (the output's first defined value in the block) and, per lane, the
  // count and the sums of (y − c)^k, k = 1…4, min and max. Groups of four with every output
  // defined are counted in full_groups_ instead of count_ (the loop's common case, one store less
  // an output).
  std::vector<double> shift_;
  std::vector<uint8_t> has_shift_;
  std::vector<SimdDouble> count_, s1_, s2_, s3_, s4_, min_, max_;
  uint64_t full_groups_ = 0;
  std::vector<std::vector<uint32_t>> bins_;  // per histogram and sample, the value's bin (undefined: a marker)
  uint64_t samples_ = 0;
  uint64_t incomplete_ = 0;
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
  double standard_deviation_standard_error = 0;  // moments.h; 0 without the plan's higher moments
  bool has_percentiles = false;
  Percentile p50, p95, p99;  // when has_percentiles
};

class MonteCarloSummary {
 public:
  explicit MonteCarloSummary(SummaryPlan plan);

  const SummaryPlan& plan() const { return plan_; }
  // Adds block b (InputError if b is outside the plan or already present).
  void AddBlock(uint64_t block, const BlockAccumulator& accumulator);
  // Adds every block of `other` (InputError for a different plan or a block present in both).
  void Merge(const MonteCarloSummary& other);

  bool complete() const;
  // Samples in which some output was undefined (counted, left out of that output's statistics).
  uint64_t undefined_samples() const { return undefined_; }
  // Statistics of output k; InputError naming the first missing block unless complete().
  OutputStatistics Statistics(size_t output) const;
  std::vector<OutputStatistics> AllStatistics() const;
  // The p-quantile of output k from its histogram (complete() and a histogram required), 0 < p < 1.
  Percentile Quantile(size_t output, double p) const;

  // Raw state, for serialization (mc_summary_json.h): the tree's nodes, keyed (level, index).
  using NodeKey = std::pair<uint32_t, uint64_t>;
  const std::map<NodeKey, std::vector<Moments>>& nodes() const { return nodes_; }
  const std::vector<LogHistogram>& histograms() const { return histograms_; }  // per NumHistograms()
  // Rebuilds a summary from serialized state; checks it is consistent (InputError otherwise).
  static MonteCarloSummary FromState(SummaryPlan plan, std::map<NodeKey, std::vector<Moments>> nodes,
                                     std::vector<LogHistogram> histograms, uint64_t undefined);
  size_t MemoryBytes() const;

 private:
  uint32_t RootLevel() const;
  bool Overlaps(const NodeKey& node) const;
  void Insert(NodeKey node, std::vector<Moments> moments);
  void RequireComplete() const;

  SummaryPlan plan_;
  std::map<NodeKey, std::vector<Moments>> nodes_;
  std::vector<LogHistogram> histograms_;
  uint64_t undefined_ = 0;
};

}  // namespace vstcal
