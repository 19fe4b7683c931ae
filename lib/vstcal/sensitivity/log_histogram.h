// A fixed-bin histogram over the real line with log-spaced bins, for percentiles that merge
// exactly: bin counts are integers, so shards add up to the same counts in any order.
//
// Bins (docs/math/sensitivity.md#histogram): for |y| in [min_magnitude, max_magnitude), bin edges
// at min_magnitude·r^k with r = 10^(1/bins_per_decade), mirrored for negative y; one central bin
// for |y| < min_magnitude; one overflow bin on each side for |y| ≥ max_magnitude.
//
// Resolution: a percentile is reported at the geometric centre of its bin (clamped to the observed
// min and max), so its relative error is at most √r − 1 (0.58 % with the default 200 bins a
// decade), its absolute error at most min_magnitude in the central bin; in an overflow bin it is
// flagged as out of range.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vstcal::sensitivity {

struct HistogramSpec {
  double min_magnitude = 1e-9;
  double max_magnitude = 1e9;
  int bins_per_decade = 200;

  // InputError unless 0 < min < max (finite) and 1 ≤ bins_per_decade ≤ 10000.
  void Validate() const;
  size_t NumBins() const;
  size_t BinOf(double y) const;
  // Worst relative error of a percentile inside the log-spaced range: √r − 1.
  double RelativeResolution() const;
  bool operator==(const HistogramSpec&) const = default;
};

// HistogramSpec::BinOf without a logarithm per value (Monte Carlo blocks bin every output of every
// sample): the smallest magnitude of each log-spaced bin is found once, from BinOf itself, and a
// value's bin is a cheap estimate of its logarithm corrected against those edges — so the two
// agree on every double. Building costs a few log10 per bin; For() builds each spec once.
class HistogramBinner {
 public:
  explicit HistogramBinner(const HistogramSpec& spec);
  // The binner of `spec`, built on first use and kept for the process (thread-safe).
  static const HistogramBinner& For(const HistogramSpec& spec);

  size_t BinOf(double y) const;

 private:
  size_t EdgeSearch(double magnitude, size_t estimate) const;  // the positive index by the edges
  size_t BinOnSide(double y, size_t b) const;                   // positive index b on y's side

  HistogramSpec spec_;
  size_t bins_per_side_;
  double log2_min_;         // log2(min_magnitude)
  double bins_per_octave_;  // bins_per_decade · log10(2)
  std::array<double, 64> log2_centre_, inverse_centre_;  // mantissa table (BinOf)
  std::vector<double> lower_;  // lower_[b]: the smallest magnitude in positive bin b (lower_[0] = min)
};

struct Percentile {
  double value = 0;
  bool in_range = true;  // false when the percentile fell in an overflow bin (value is then min or max)
};

class LogHistogram {
 public:
  explicit LogHistogram(const HistogramSpec& spec);

  const HistogramSpec& spec() const { return spec_; }
  void AddBin(size_t bin, uint64_t count = 1);
  void Add(double y) { AddBin(spec_.BinOf(y)); }
  void Merge(const LogHistogram& other);  // InternalError unless same spec
  uint64_t total() const { return total_; }
  const std::vector<uint64_t>& counts() const { return counts_; }

  // The p-quantile (0 < p < 1): the smallest bin whose cumulative count reaches ⌈p·total⌉,
  // reported at its geometric centre, clamped to [observed_min, observed_max]. Requires total > 0.
  Percentile Quantile(double p, double observed_min, double observed_max) const;

 private:
  double BinCentre(size_t bin) const;

  HistogramSpec spec_;
  size_t bins_per_side_;  // log-spaced bins on each side
  std::vector<uint64_t> counts_;
  uint64_t total_ = 0;
};

}  // namespace vstcal::sensitivity
