#include "vstcal/sensitivity/mc_summary.h"

#include <cmath>

#include "vstcal/core/error.h"

namespace vstcal::sensitivity {

void SummaryPlan::Validate() const {
  if (output_names.empty()) throw InputError("monte carlo summary: no outputs");
  if (total_samples == 0) throw InputError("monte carlo summary: zero samples; ask for at least one");
  if (block_size == 0) throw InputError("monte carlo summary: block size is zero");
  histogram.Validate();
}

BlockRange ShardBlocks(const SummaryPlan& plan, uint64_t shard, uint64_t shards) {
  if (shards == 0 || shard >= shards) {
    throw InputError("shard " + std::to_string(shard) + "/" + std::to_string(shards) +
                     " is not valid; use i/N with 0 <= i < N");
  }
  const uint64_t blocks = plan.NumBlocks();
  // (blocks·i)/N without overflow: blocks ≤ 2^64 / block_size, shards small.
  auto edge = [&](uint64_t i) {
    return static_cast<uint64_t>((static_cast<long double>(blocks) * i) / shards);
  };
  return {edge(shard), shard + 1 == shards ? blocks : edge(shard + 1)};
}

BlockAccumulator::BlockAccumulator(const SummaryPlan& plan)
    : binner_(&HistogramBinner::For(plan.histogram)), moments_(plan.output_names.size()) {
  bins_.reserve(plan.block_size * moments_.size());
}

void BlockAccumulator::Add(const double* y, size_t stride) {
  for (size_t k = 0; k < moments_.size(); ++k) {
    moments_[k].Add(y[k * stride]);
    bins_.push_back(static_cast<uint32_t>(binner_->BinOf(y[k * stride])));
  }
}

MonteCarloSummary::MonteCarloSummary(SummaryPlan plan) : plan_(std::move(plan)) {
  plan_.Validate();
  folded_.resize(plan_.output_names.size());
  histograms_.assign(plan_.output_names.size(), LogHistogram(plan_.histogram));
}

void MonteCarloSummary::AddBlock(uint64_t block, const BlockAccumulator& accumulator) {
  const uint64_t blocks = plan_.NumBlocks();
  if (block >= blocks) {
    throw InputError("monte carlo summary: block " + std::to_string(block) + " is beyond the plan's " +
                     std::to_string(blocks) + " blocks");
  }
  if (Has(block)) throw InputError("monte carlo summary: block " + std::to_string(block) + " was added twice");
  const uint64_t first = block * plan_.block_size;
  const uint64_t expected = std::min(plan_.block_size, plan_.total_samples - first);
  VSTCAL_CHECK(accumulator.moments_.size() == folded_.size(), "block accumulator of another plan");
  VSTCAL_CHECK(accumulator.moments_[0].count + accumulator.undefined_ == expected,
               "block " + std::to_string(block) + " holds the wrong number of samples");
  const size_t m = folded_.size();
  for (size_t s = 0; s < accumulator.bins_.size(); ++s) histograms_[s % m].AddBin(accumulator.bins_[s]);
  undefined_ += accumulator.undefined_;
  pending_.emplace(block, accumulator.moments_);
  FoldReadyBlocks();
}

void MonteCarloSummary::Merge(const MonteCarloSummary& other) {
  if (!(other.plan_ == plan_)) {
    throw InputError("monte carlo merge: the shards come from different runs (plan or run id differ); "
                     "merge only shards of one run");
  }
  for (uint64_t b = 0; b < other.folded_blocks_; ++b) {
    if (Has(b)) throw InputError("monte carlo merge: block " + std::to_string(b) + " is in two shards");
  }
  for (const auto& [b, moments] : other.pending_) {
    if (Has(b)) throw InputError("monte carlo merge: block " + std::to_string(b) + " is in two shards");
  }
  // other's folded prefix [0, p) can only be adopted when we have none of it, i.e. no prefix yet.
  if (other.folded_blocks_ > 0) {
    VSTCAL_CHECK(folded_blocks_ == 0, "two shards both hold block 0");
    folded_blocks_ = other.folded_blocks_;
    folded_ = other.folded_;
  }
  for (const auto& [b, moments] : other.pending_) pending_.emplace(b, moments);
  for (size_t k = 0; k < histograms_.size(); ++k) histograms_[k].Merge(other.histograms_[k]);
  undefined_ += other.undefined_;
  FoldReadyBlocks();
}

void MonteCarloSummary::FoldReadyBlocks() {
  for (auto it = pending_.begin(); it != pending_.end() && it->first == folded_blocks_; it = pending_.erase(it)) {
    for (size_t k = 0; k < folded_.size(); ++k) folded_[k].Merge(it->second[k]);
    ++folded_blocks_;
  }
}

void MonteCarloSummary::RequireComplete() const {
  if (!complete()) {
    throw InputError("monte carlo summary: block " + std::to_string(folded_blocks_) + " of " +
                     std::to_string(plan_.NumBlocks()) + " is missing; merge every shard first");
  }
}

Percentile MonteCarloSummary::Quantile(size_t output, double p) const {
  RequireComplete();
  const Moments& m = folded_.at(output);
  if (m.count == 0) return {0.0, false};
  return histograms_[output].Quantile(p, m.min, m.max);
}

OutputStatistics MonteCarloSummary::Statistics(size_t output) const {
  RequireComplete();
  const Moments& m = folded_.at(output);
  OutputStatistics s;
  s.name = plan_.output_names[output];
  s.count = m.count;
  if (m.count == 0) return s;
  s.mean = m.mean;
  s.standard_deviation = m.StandardDeviation();
  s.rms = m.Rms();
  s.min = m.min;
  s.max = m.max;
  s.mean_standard_error = s.standard_deviation / std::sqrt(static_cast<double>(m.count));
  s.standard_deviation_standard_error = m.StandardDeviationStandardError();
  s.p50 = Quantile(output, 0.50);
  s.p95 = Quantile(output, 0.95);
  s.p99 = Quantile(output, 0.99);
  return s;
}

std::vector<OutputStatistics> MonteCarloSummary::AllStatistics() const {
  std::vector<OutputStatistics> all;
  for (size_t k = 0; k < folded_.size(); ++k) all.push_back(Statistics(k));
  return all;
}

MonteCarloSummary MonteCarloSummary::FromState(SummaryPlan plan, uint64_t folded_blocks, std::vector<Moments> folded,
                                               std::map<uint64_t, std::vector<Moments>> pending,
                                               std::vector<LogHistogram> histograms, uint64_t undefined) {
  MonteCarloSummary s(std::move(plan));
  const size_t m = s.plan_.output_names.size();
  if (folded_blocks > s.plan_.NumBlocks() || folded.size() != m || histograms.size() != m) {
    throw InputError("monte carlo summary: the saved state does not match its plan");
  }
  for (const auto& [b, moments] : pending) {
    if (b < folded_blocks || b >= s.plan_.NumBlocks() || moments.size() != m) {
      throw InputError("monte carlo summary: saved block " + std::to_string(b) + " does not fit the plan");
    }
  }
  for (const LogHistogram& h : histograms) {
    if (!(h.spec() == s.plan_.histogram)) throw InputError("monte carlo summary: a histogram has another spec");
  }
  for (size_t k = 0; k < m; ++k) {
    uint64_t samples = folded[k].count;
    for (const auto& [b, moments] : pending) samples += moments[k].count;
    if (histograms[k].total() != samples) {
      throw InputError("monte carlo summary: output '" + s.plan_.output_names[k] +
                       "' has histogram counts that disagree with its moments; regenerate the shard file");
    }
  }
  s.folded_blocks_ = folded_blocks;
  s.folded_ = std::move(folded);
  s.pending_ = std::move(pending);
  s.histograms_ = std::move(histograms);
  s.undefined_ = undefined;
  s.FoldReadyBlocks();
  return s;
}

}  // namespace vstcal::sensitivity
