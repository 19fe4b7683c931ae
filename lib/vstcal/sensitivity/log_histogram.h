// A fixed-bin histogram over the real line for percentiles that merge exactly: bin counts are
// integers, so shards add up to the same counts in any order (docs/math/sensitivity.md#histogram).
//
// Bins are log-linear (the layout of HdrHistogram): each octave [2^e, 2^(e+1)) of magnitudes is cut
// into 2^s equal bins, for min_exponent ≤ e < max_exponent. A value's bin is read off its bits —
// the biased exponent and the top s bits of the mantissa — so binning is one shift and one
// subtraction, exact for every double, and cheap four values at a time. Negative values mirror
// the positive bins; one central bin holds |y| < 2^min_exponent, one overflow bin on each side
// |y| ≥ 2^max_exponent.
//
// Resolution: a percentile is reported at the midpoint of its bin [a, b) (clamped to the observed
// min and max); the bin's width b − a is at most a/2^s, so the relative error is at most 2^−(s+1)
// (0.78 % with the default s = 6), the absolute error at most 2^min_exponent in the central bin;
// in an overflow bin the percentile is flagged as out of range.
//
// Storage is paged: 256 bins a page, allocated when first used, so a histogram costs memory only
// for the octaves its values occupy (a few KB), not for the whole range.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdint>
#include <memory>
#include <vector>

namespace vstcal {

struct HistogramSpec {
  int min_exponent = -30;  // 2^−30 ≈ 9.3e-10
  int max_exponent = 30;   // 2^30 ≈ 1.07e9
  int sub_bins_log2 = 6;   // 64 bins an octave

  // InputError unless −1000 ≤ min < max ≤ 1000, 0 ≤ sub_bins_log2 ≤ 12 and at most 2^20 bins a side.
  void Validate() const;
  size_t BinsPerSide() const { return static_cast<size_t>(max_exponent - min_exponent) << sub_bins_log2; }
  size_t NumBins() const { return 2 * BinsPerSide() + 3; }
  // Layout: [0] y ≤ −2^max, [1, K] negative bins from the largest magnitude down, [K + 1] central,
  // [K + 2, 2K + 1] positive bins from the smallest magnitude up, [2K + 2] y ≥ 2^max. NaN: central.
  size_t BinOf(double y) const;
  // BinOf of four values (lane by lane; the same bins).
  void BinsOf4(const double* y, uint32_t* bins) const;
  // [lo, hi) of a bin's magnitudes (positive or negative side); the central bin is [0, 2^min).
  double BinLow(size_t bin) const;
  double BinHigh(size_t bin) const;
  // Worst relative error of a percentile inside the log-linear range: 2^−(s+1).
  double RelativeResolution() const;
  bool operator==(const HistogramSpec&) const = default;
};

// BinsOf4's arithmetic, inlined into callers compiled for AVX2 (mc_summary.cc bins a group of four
// samples in the same function as its sums): BinOf on four lanes with GCC vector extensions, one
// instruction each where the CPU has AVX2; NaN and the edges as BinOf.
[[gnu::always_inline]] inline void BinsOf4Inline(const HistogramSpec& spec, const double* y, uint32_t* bins) {
  using V = int64_t __attribute__((vector_size(32)));
  V bits;
  static_assert(sizeof bits == 4 * sizeof(double));
  __builtin_memcpy(&bits, y, sizeof bits);
  const int64_t k = static_cast<int64_t>(spec.BinsPerSide());
  const int64_t low = static_cast<int64_t>(1023 + spec.min_exponent) << 52;
  const int64_t high = static_cast<int64_t>(1023 + spec.max_exponent) << 52;
  const V magnitude = bits & INT64_MAX;
  const V negative = bits < 0;
  const V b = (magnitude - low) >> (52 - spec.sub_bins_log2);
  const V inside = ((k - b) & negative) | ((k + 2 + b) & ~negative);
  const V overflow = negative ? V{} : V{} + (2 * k + 2);
  const V central = (magnitude < low) | (magnitude > 0x7ff0000000000000ll);
  const V over = magnitude >= high;
  const V bin = central ? V{} + (k + 1) : (over ? overflow : inside);
  for (int l = 0; l < 4; ++l) bins[l] = static_cast<uint32_t>(bin[l]);
}

struct Percentile {
  double value = 0;
  bool in_range = true;  // false when the percentile fell in an overflow bin (value is then min or max)
};

class LogHistogram {
 public:
  explicit LogHistogram(const HistogramSpec& spec);
  LogHistogram(const LogHistogram& other);
  LogHistogram& operator=(const LogHistogram& other);
  LogHistogram(LogHistogram&&) = default;
  LogHistogram& operator=(LogHistogram&&) = default;

  const HistogramSpec& spec() const { return spec_; }
  void AddBin(size_t bin, uint64_t count = 1);
  // One count for each of n bins, skipping the value `skip` (a block's undefined samples).
  void AddBins(const uint32_t* bins, size_t n, uint32_t skip);
  void Add(double y) { AddBin(spec_.BinOf(y)); }
  void Merge(const LogHistogram& other);  // InternalError unless same spec
  uint64_t total() const { return total_; }
  uint64_t count(size_t bin) const;
  // f(bin, count) for every non-empty bin, in bin order.
  template <typename F>
  void ForEachBin(F&& f) const {
    for (size_t p = 0; p < pages_.size(); ++p) {
      if (!pages_[p]) continue;
      for (size_t i = 0; i < kPageSize; ++i) {
        if ((*pages_[p])[i] != 0) f(p * kPageSize + i, (*pages_[p])[i]);
      }
    }
  }
  // Bytes held by the pages in use.
  size_t MemoryBytes() const;

  // The p-quantile (0 < p < 1): the smallest bin whose cumulative count reaches ⌈p·total⌉,
  // reported at its midpoint, clamped to [observed_min, observed_max]. Requires total > 0.
  Percentile Quantile(double p, double observed_min, double observed_max) const;

 private:
  static constexpr size_t kPageSize = 256;
  using Page = std::array<uint64_t, kPageSize>;

  HistogramSpec spec_;
  std::vector<std::unique_ptr<Page>> pages_;
  uint64_t total_ = 0;
};

}  // namespace vstcal
