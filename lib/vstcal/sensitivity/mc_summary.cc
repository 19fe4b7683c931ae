#include "vstcal/sensitivity/mc_summary.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

constexpr size_t kLanes = BlockAccumulator::kLanes;
constexpr uint32_t kNoBin = std::numeric_limits<uint32_t>::max();

// The lanes of a 4-bit mask as a SimdMask, for every mask: constant-initialized, so that no
// clone of AccumulateGroup builds a 32-byte vector at run time (a function-local static built by
// a helper faulted under ASan in the baseline clone: an aligned store to a 16-byte-aligned slot).
// (A macro, not a function: a function returning a 32-byte vector changes the ABI without AVX.)
#define VSTCAL_LANE_MASK(b) SimdMask{SimdMask::Bits{(b) & 1 ? -1 : 0, (b) & 2 ? -1 : 0, (b) & 4 ? -1 : 0, (b) & 8 ? -1 : 0}}
alignas(32) constexpr SimdMask kLaneMasks[16] = {
    VSTCAL_LANE_MASK(0),  VSTCAL_LANE_MASK(1),  VSTCAL_LANE_MASK(2),  VSTCAL_LANE_MASK(3),
    VSTCAL_LANE_MASK(4),  VSTCAL_LANE_MASK(5),  VSTCAL_LANE_MASK(6),  VSTCAL_LANE_MASK(7),
    VSTCAL_LANE_MASK(8),  VSTCAL_LANE_MASK(9),  VSTCAL_LANE_MASK(10), VSTCAL_LANE_MASK(11),
    VSTCAL_LANE_MASK(12), VSTCAL_LANE_MASK(13), VSTCAL_LANE_MASK(14), VSTCAL_LANE_MASK(15)};
#undef VSTCAL_LANE_MASK

// First block and one-past-last block a node covers.
std::pair<uint64_t, uint64_t> Span(const MonteCarloSummary::NodeKey& node) {
  const uint64_t first = node.second << node.first;
  return {first, first + (uint64_t{1} << node.first)};
}

}  // namespace

int SummaryPlan::HistogramOf(size_t output) const {
  if (all_percentiles) return static_cast<int>(output);
  const auto it = std::lower_bound(percentile_outputs.begin(), percentile_outputs.end(), output);
  return it != percentile_outputs.end() && *it == output ? static_cast<int>(it - percentile_outputs.begin()) : -1;
}

void SummaryPlan::Validate() const {
  if (output_names.empty()) throw InputError("monte carlo summary: no outputs");
  if (total_samples == 0) throw InputError("monte carlo summary: zero samples; ask for at least one");
  if (block_size == 0 || block_size % kLanes != 0) throw InputError("monte carlo summary: the block size must be a positive multiple of 4");
  for (size_t h = 0; h < percentile_outputs.size(); ++h) {
    if (percentile_outputs[h] >= output_names.size() || (h > 0 && percentile_outputs[h] <= percentile_outputs[h - 1])) {
      throw InputError("monte carlo summary: percentile outputs must be increasing output indices");
    }
  }
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
    : plan_(&plan),
      num_outputs_(plan.output_names.size()),
      shift_(num_outputs_, 0.0),
      has_shift_(num_outputs_, 0),
      count_(num_outputs_, SimdDouble(0.0)),
      s1_(num_outputs_, SimdDouble(0.0)),
      s2_(num_outputs_, SimdDouble(0.0)),
      s3_(num_outputs_, SimdDouble(0.0)),
      s4_(num_outputs_, SimdDouble(0.0)),
      min_(num_outputs_, SimdDouble(std::numeric_limits<double>::infinity())),
      max_(num_outputs_, SimdDouble(-std::numeric_limits<double>::infinity())),
      bins_(plan.NumHistograms(), std::vector<uint32_t>(plan.block_size + kLanes, kNoBin)) {}

namespace {

// A group of four samples for every output: the shift, the sums and the histogram bins, in one
// function cloned for AVX2 (each SimdDouble operation one instruction there).
struct GroupState {
  size_t num_outputs;
  double* shift;
  uint8_t* has_shift;
  SimdDouble *count, *s1, *s2, *s3, *s4, *lo, *hi;
  bool higher_moments;
  const HistogramSpec* spec;
  const SummaryPlan* plan;
  std::vector<uint32_t>* bins;  // per histogram
  size_t sample;                // the group's first sample in the block
};

// Returns whether every lane of every output was defined: those groups are counted once
// (BlockAccumulator::full_groups_) rather than in every output's count.
[[gnu::target_clones("avx2", "default")]] bool AccumulateGroup(const GroupState& a, const double* y, const uint8_t* defined,
                                                               unsigned lanes) {
  // Locals the stores below cannot alias, so that the loop keeps them in registers.
  double* __restrict shift = a.shift;
  uint8_t* __restrict has_shift = a.has_shift;
  SimdDouble* __restrict count = a.count;
  SimdDouble* __restrict s1 = a.s1;
  SimdDouble* __restrict s2 = a.s2;
  SimdDouble* __restrict s3 = a.s3;
  SimdDouble* __restrict s4 = a.s4;
  SimdDouble* __restrict lo = a.lo;
  SimdDouble* __restrict hi = a.hi;
  const size_t n = a.num_outputs;
  const SimdDouble zero(0.0), one(1.0);
  // `full`: every lane of every output defined (nearly every group of a Monte Carlo run). The
  // same sums then go without the masks, which are all ones (Select(m, x, y) is x), and without a
  // count per output (an integer: Finish adds the group's four in any order, exactly).
  auto add = [&](size_t k, unsigned bits, bool higher, bool full) {
    if (!has_shift[k]) {
      shift[k] = y[kLanes * k + std::countr_zero(bits)];
      has_shift[k] = 1;
    }
    const SimdMask m = kLaneMasks[bits];
    const SimdDouble v = SimdDouble::Load(y + kLanes * k);
    const SimdDouble d = full ? v - shift[k] : Select(m, v - shift[k], zero);
    const SimdDouble d2 = d * d;
    if (!full) count[k] += Select(m, one, zero);
    s1[k] += d;
    s2[k] += d2;
    if (higher) {
      s3[k] += d2 * d;
      s4[k] += d2 * d2;
    }
    lo[k] = full ? Select(v < lo[k], v, lo[k]) : Select(m && v < lo[k], v, lo[k]);
    hi[k] = full ? Select(v > hi[k], v, hi[k]) : Select(m && v > hi[k], v, hi[k]);
  };
  bool full = lanes == 0xf;
  for (size_t k = 0; k < n && full; ++k) full = defined[k] == 0xf;
  // A loop per case rather than tests per output: the plan fixes whether M₃, M₄ are kept.
  if (full && a.higher_moments) {
    for (size_t k = 0; k < n; ++k) add(k, 0xf, true, true);
  } else if (full) {
    for (size_t k = 0; k < n; ++k) add(k, 0xf, false, true);
  } else if (a.higher_moments) {
    for (size_t k = 0; k < n; ++k) {
      if (const unsigned bits = defined[k] & lanes) add(k, bits, true, false);
    }
  } else {
    for (size_t k = 0; k < n; ++k) {
      if (const unsigned bits = defined[k] & lanes) add(k, bits, false, false);
    }
  }
  const size_t histograms = a.plan->NumHistograms();
  const HistogramSpec spec = *a.spec;
  for (size_t h = 0; h < histograms; ++h) {
    const size_t k = a.plan->HistogramOutput(h);
    uint32_t* out = a.bins[h].data() + a.sample;
    BinsOf4Inline(spec, y + kLanes * k, out);
    for (int l = 0; l < 4; ++l) out[l] = (defined[k] >> l) & 1 ? out[l] : kNoBin;
  }
  return full;
}

}  // namespace

void BlockAccumulator::AddLanes(const double* y, const uint8_t* defined, size_t count, uint64_t incomplete) {
  VSTCAL_CHECK(samples_ % kLanes == 0 && count >= 1 && count <= kLanes && samples_ + count <= plan_->block_size,
               "lanes out of step with the block");
  const unsigned lanes = (1u << count) - 1;
  const GroupState state{num_outputs_, shift_.data(), has_shift_.data(), count_.data(), s1_.data(), s2_.data(),
                         s3_.data(), s4_.data(), min_.data(), max_.data(), plan_->higher_moments, &plan_->histogram,
                         plan_, bins_.data(), samples_};
  full_groups_ += AccumulateGroup(state, y, defined, lanes);
  samples_ += count;
  incomplete_ += incomplete;
}

void BlockAccumulator::AddOne(size_t k, size_t lane, double value) {
  if (!has_shift_[k]) {
    shift_[k] = value;
    has_shift_[k] = 1;
  }
  const double d = value - shift_[k], d2 = d * d;
  auto add = [lane](SimdDouble& sum, double x) { sum.set_lane(static_cast<int>(lane), sum.lane(static_cast<int>(lane)) + x); };
  add(count_[k], 1.0);
  add(s1_[k], d);
  add(s2_[k], d2);
  if (plan_->higher_moments) {
    add(s3_[k], d2 * d);
    add(s4_[k], d2 * d2);
  }
  if (value < min_[k].lane(static_cast<int>(lane))) min_[k].set_lane(static_cast<int>(lane), value);
  if (value > max_[k].lane(static_cast<int>(lane))) max_[k].set_lane(static_cast<int>(lane), value);
}

void BlockAccumulator::Add(const double* y, size_t stride) {
  VSTCAL_CHECK(samples_ < plan_->block_size, "more samples than a block holds");
  const size_t lane = samples_ % kLanes;
  for (size_t k = 0; k < num_outputs_; ++k) AddOne(k, lane, y[k * stride]);
  for (size_t h = 0; h < bins_.size(); ++h) {
    bins_[h][samples_] = static_cast<uint32_t>(plan_->histogram.BinOf(y[plan_->HistogramOutput(h) * stride]));
  }
  ++samples_;
}

void BlockAccumulator::AddUndefined() {
  VSTCAL_CHECK(samples_ < plan_->block_size, "more samples than a block holds");
  for (auto& b : bins_) b[samples_] = kNoBin;
  ++samples_;
  ++incomplete_;
}

std::vector<Moments> BlockAccumulator::Finish() const {
  std::vector<Moments> out(num_outputs_);
  for (size_t k = 0; k < num_outputs_; ++k) {
    // The lanes' sums in lane order, then the central moments of the block from the power sums
    // about c: with δ = S₁/n, m₂ = S₂ − nδ², m₃ = S₃ − 3δS₂ + 2nδ³, m₄ = S₄ − 4δS₃ + 6δ²S₂ − 3nδ⁴.
    double n = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int l = 0; l < static_cast<int>(kLanes); ++l) {
      n += count_[k].lane(l);
      s1 += s1_[k].lane(l);
      s2 += s2_[k].lane(l);
      s3 += s3_[k].lane(l);
      s4 += s4_[k].lane(l);
      lo = std::min(lo, min_[k].lane(l));
      hi = std::max(hi, max_[k].lane(l));
    }
    n += static_cast<double>(kLanes * full_groups_);
    Moments& m = out[k];
    if (n == 0) continue;
    const double delta = s1 / n, delta2 = delta * delta;
    m.count = static_cast<uint64_t>(n);
    m.mean = shift_[k] + delta;
    m.m2 = std::max(0.0, s2 - n * delta2);
    m.m3 = s3 - 3 * delta * s2 + 2 * n * delta2 * delta;
    m.m4 = std::max(0.0, s4 - 4 * delta * s3 + 6 * delta2 * s2 - 3 * n * delta2 * delta2);
    m.min = lo;
    m.max = hi;
  }
  return out;
}

MonteCarloSummary::MonteCarloSummary(SummaryPlan plan) : plan_(std::move(plan)) {
  plan_.Validate();
  histograms_.assign(plan_.NumHistograms(), LogHistogram(plan_.histogram));
}

uint32_t MonteCarloSummary::RootLevel() const {
  const uint64_t blocks = plan_.NumBlocks();
  return blocks <= 1 ? 0 : static_cast<uint32_t>(std::bit_width(blocks - 1));
}

bool MonteCarloSummary::Overlaps(const NodeKey& node) const {
  const auto [first, last] = Span(node);
  for (const auto& [key, moments] : nodes_) {
    const auto [a, b] = Span(key);
    if (a < last && first < b) return true;
  }
  return false;
}

void MonteCarloSummary::Insert(NodeKey node, std::vector<Moments> moments) {
  const uint32_t root = RootLevel();
  const uint64_t blocks = plan_.NumBlocks();
  while (node.first < root) {
    const NodeKey sibling{node.first, node.second ^ 1};
    const NodeKey parent{node.first + 1, node.second >> 1};
    if ((sibling.second << sibling.first) >= blocks) {  // no right child: the parent is the left one
      node = parent;
      continue;
    }
    const auto it = nodes_.find(sibling);
    if (it == nodes_.end()) break;
    if (node.second % 2 == 0) {
      for (size_t k = 0; k < moments.size(); ++k) moments[k].Merge(it->second[k]);
    } else {
      std::vector<Moments> left = std::move(it->second);
      for (size_t k = 0; k < left.size(); ++k) left[k].Merge(moments[k]);
      moments = std::move(left);
    }
    nodes_.erase(it);
    node = parent;
    // Without the higher moments, a merge's cross terms would make M₃ and M₄ up from nothing.
    if (!plan_.higher_moments) {
      for (Moments& m : moments) m.m3 = m.m4 = 0;
    }
  }
  nodes_.emplace(node, std::move(moments));
}

void MonteCarloSummary::AddBlock(uint64_t block, const BlockAccumulator& accumulator) {
  const uint64_t blocks = plan_.NumBlocks();
  if (block >= blocks) {
    throw InputError("monte carlo summary: block " + std::to_string(block) + " is beyond the plan's " +
                     std::to_string(blocks) + " blocks");
  }
  if (Overlaps({0, block})) throw InputError("monte carlo summary: block " + std::to_string(block) + " was added twice");
  VSTCAL_CHECK(accumulator.plan_ == &plan_ || *accumulator.plan_ == plan_, "block accumulator of another plan");
  const uint64_t first = block * plan_.block_size;
  const uint64_t expected = std::min(plan_.block_size, plan_.total_samples - first);
  VSTCAL_CHECK(accumulator.samples_ == expected, "block " + std::to_string(block) + " holds the wrong number of samples");
  for (size_t h = 0; h < histograms_.size(); ++h) {
    histograms_[h].AddBins(accumulator.bins_[h].data(), accumulator.samples_, kNoBin);
  }
  undefined_ += accumulator.incomplete_;
  Insert({0, block}, accumulator.Finish());
}

void MonteCarloSummary::Merge(const MonteCarloSummary& other) {
  if (!(other.plan_ == plan_)) {
    throw InputError("monte carlo merge: the shards come from different runs (plan or run id differ); "
                     "merge only shards of one run");
  }
  for (const auto& [key, moments] : other.nodes_) {
    if (Overlaps(key)) {
      throw InputError("monte carlo merge: blocks " + std::to_string(Span(key).first) + " onwards are in two shards");
    }
  }
  for (const auto& [key, moments] : other.nodes_) Insert(key, moments);
  for (size_t h = 0; h < histograms_.size(); ++h) histograms_[h].Merge(other.histograms_[h]);
  undefined_ += other.undefined_;
}

bool MonteCarloSummary::complete() const { return nodes_.count({RootLevel(), 0}) > 0; }

void MonteCarloSummary::RequireComplete() const {
  if (complete()) return;
  // The first block no node covers.
  uint64_t missing = 0;
  for (const auto& [key, moments] : nodes_) {
    const auto [first, last] = Span(key);
    if (first == missing) missing = last;
  }
  throw InputError("monte carlo summary: block " + std::to_string(missing) + " of " + std::to_string(plan_.NumBlocks()) +
                   " is missing; merge every shard first");
}

Percentile MonteCarloSummary::Quantile(size_t output, double p) const {
  RequireComplete();
  const int h = plan_.HistogramOf(output);
  VSTCAL_CHECK(h >= 0, "output " + plan_.output_names.at(output) + " has no histogram");
  const Moments& m = nodes_.at({RootLevel(), 0}).at(output);
  if (m.count == 0) return {0.0, false};
  return histograms_[h].Quantile(p, m.min, m.max);
}

OutputStatistics MonteCarloSummary::Statistics(size_t output) const {
  RequireComplete();
  const Moments& m = nodes_.at({RootLevel(), 0}).at(output);
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
  if (plan_.HistogramOf(output) >= 0) {
    s.has_percentiles = true;
    s.p50 = Quantile(output, 0.50);
    s.p95 = Quantile(output, 0.95);
    s.p99 = Quantile(output, 0.99);
  }
  return s;
}

std::vector<OutputStatistics> MonteCarloSummary::AllStatistics() const {
  std::vector<OutputStatistics> all;
  for (size_t k = 0; k < plan_.output_names.size(); ++k) all.push_back(Statistics(k));
  return all;
}

MonteCarloSummary MonteCarloSummary::FromState(SummaryPlan plan, std::map<NodeKey, std::vector<Moments>> nodes,
                                               std::vector<LogHistogram> histograms, uint64_t undefined) {
  MonteCarloSummary s(std::move(plan));
  const size_t m = s.plan_.output_names.size();
  const uint64_t blocks = s.plan_.NumBlocks();
  if (histograms.size() != s.plan_.NumHistograms()) {
    throw InputError("monte carlo summary: the saved histograms do not match the plan");
  }
  for (const LogHistogram& h : histograms) {
    if (!(h.spec() == s.plan_.histogram)) throw InputError("monte carlo summary: a histogram has another spec");
  }
  std::vector<uint64_t> counts(m, 0);
  for (auto& [key, moments] : nodes) {
    if (key.first > s.RootLevel() || (key.second << key.first) >= blocks || (key.second >> (63 - key.first)) != 0 ||
        moments.size() != m) {
      throw InputError("monte carlo summary: saved node (" + std::to_string(key.first) + ", " + std::to_string(key.second) +
                       ") does not fit the plan");
    }
    if (s.Overlaps(key)) throw InputError("monte carlo summary: saved nodes overlap");
    for (size_t k = 0; k < m; ++k) counts[k] += moments[k].count;
    s.nodes_.emplace(key, std::move(moments));
  }
  for (size_t h = 0; h < histograms.size(); ++h) {
    if (histograms[h].total() != counts[s.plan_.HistogramOutput(h)]) {
      throw InputError("monte carlo summary: output '" + s.plan_.output_names[s.plan_.HistogramOutput(h)] +
                       "' has histogram counts that disagree with its moments; regenerate the shard file");
    }
  }
  // Saved nodes are each other's siblings only if the shard was cut mid-way: fold them now.
  std::map<NodeKey, std::vector<Moments>> saved = std::move(s.nodes_);
  s.nodes_.clear();
  for (auto& [key, moments] : saved) s.Insert(key, std::move(moments));
  s.histograms_ = std::move(histograms);
  s.undefined_ = undefined;
  return s;
}

size_t MonteCarloSummary::MemoryBytes() const {
  size_t bytes = sizeof(*this);
  for (const auto& [key, moments] : nodes_) bytes += moments.size() * sizeof(Moments) + 64;
  for (const LogHistogram& h : histograms_) bytes += h.MemoryBytes();
  return bytes;
}

}  // namespace vstcal
