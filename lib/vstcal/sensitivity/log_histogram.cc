#include "vstcal/sensitivity/log_histogram.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>

#include "vstcal/core/error.h"

namespace vstcal::sensitivity {
namespace {

// Layout: [0] y ≤ −max, [1, K] negative bins from the largest magnitude down, [K + 1] central,
// [K + 2, 2K + 1] positive bins from the smallest magnitude up, [2K + 2] y ≥ max.
size_t BinsPerSide(const HistogramSpec& spec) {
  return static_cast<size_t>(std::ceil(std::log10(spec.max_magnitude / spec.min_magnitude) * spec.bins_per_decade));
}

}  // namespace

void HistogramSpec::Validate() const {
  if (!(std::isfinite(min_magnitude) && std::isfinite(max_magnitude) && min_magnitude > 0 &&
        max_magnitude > min_magnitude)) {
    throw InputError("histogram: need 0 < min_magnitude < max_magnitude, both finite");
  }
  if (bins_per_decade < 1 || bins_per_decade > 10000) {
    throw InputError("histogram: bins_per_decade must be in [1, 10000]");
  }
}

size_t HistogramSpec::NumBins() const { return 2 * BinsPerSide(*this) + 3; }

size_t HistogramSpec::BinOf(double y) const {
  const size_t k = BinsPerSide(*this);
  const double magnitude = std::abs(y);
  if (magnitude < min_magnitude) return k + 1;
  if (magnitude >= max_magnitude) return y > 0 ? 2 * k + 2 : 0;
  // Rounding of log10 near an edge can only move a value to the neighbouring bin.
  const size_t b = std::min(k - 1, static_cast<size_t>(std::log10(magnitude / min_magnitude) * bins_per_decade));
  return y > 0 ? k + 2 + b : k - b;
}

HistogramBinner::HistogramBinner(const HistogramSpec& spec) : spec_(spec) {
  spec_.Validate();
  bins_per_side_ = BinsPerSide(spec_);
  log2_min_ = std::log2(spec_.min_magnitude);
  for (size_t j = 0; j < log2_centre_.size(); ++j) {
    const double centre = 1 + (static_cast<double>(j) + 0.5) / 64;
    log2_centre_[j] = std::log2(centre);
    inverse_centre_[j] = 1 / centre;
  }
  bins_per_octave_ = spec_.bins_per_decade * std::log10(2.0);
  // lower_[b] is where BinOf's positive index reaches b: start at the exact edge min·10^(b/d) and
  // step by ulps (BinOf's logarithm is off by at most a few).
  const size_t first_positive = bins_per_side_ + 2;
  auto index = [&](double m) { return spec_.BinOf(m) - first_positive; };
  lower_.resize(bins_per_side_);
  lower_[0] = spec_.min_magnitude;
  for (size_t b = 1; b < bins_per_side_; ++b) {
    const double edge = spec_.min_magnitude * std::pow(10.0, static_cast<double>(b) / spec_.bins_per_decade);
    double m = std::max(lower_[b - 1], edge);
    while (m > lower_[b - 1] && index(std::nextafter(m, 0.0)) >= b) m = std::nextafter(m, 0.0);
    while (index(m) < b) m = std::nextafter(m, HUGE_VAL);
    lower_[b] = m;
  }
}

const HistogramBinner& HistogramBinner::For(const HistogramSpec& spec) {
  static std::mutex mutex;
  static std::map<std::tuple<double, double, int>, std::unique_ptr<const HistogramBinner>> binners;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& binner = binners[{spec.min_magnitude, spec.max_magnitude, spec.bins_per_decade}];
  if (!binner) binner = std::make_unique<const HistogramBinner>(spec);
  return *binner;
}

size_t HistogramBinner::BinOf(double y) const {
  const size_t k = bins_per_side_;
  const double magnitude = std::abs(y);
  if (magnitude < spec_.min_magnitude) return k + 1;
  if (magnitude >= spec_.max_magnitude) return y > 0 ? 2 * k + 2 : 0;
  // log2 of the magnitude: its exponent, plus log2 f for its mantissa f in [1, 2) from a table at
  // the 64 centres c_j = 1 + (j + ½)/64 and ln(1 + r) through r⁴ for r = f/c_j − 1, |r| < 1/128:
  // error below 1e-11, so the estimate of BinOf's log10(|y|/min)·d is within 1e-7 of a bin (d ≤
  // 10000), and BinOf's own rounding is far smaller. Unless the estimate is that close to a bin
  // edge its floor is BinOf's bin; near an edge the stored edges decide. (A subnormal magnitude
  // gets a poor estimate; the edges correct that too.)
  const uint64_t bits = std::bit_cast<uint64_t>(magnitude);
  const double exponent = static_cast<double>(static_cast<int>(bits >> 52) - 1023);
  const double f = std::bit_cast<double>((bits & 0x000fffffffffffffu) | 0x3ff0000000000000u);
  const size_t j = (bits >> 46) & 63;
  const double r = f * inverse_centre_[j] - 1;
  const double ln_1_plus_r = r * (1 - r * (0.5 - r * (1.0 / 3 - r * 0.25)));
  const double estimate =
      (exponent + log2_centre_[j] + ln_1_plus_r * (1 / std::numbers::ln2) - log2_min_) * bins_per_octave_;
  if (!(estimate > 0)) return BinOnSide(y, EdgeSearch(magnitude, 0));
  if (!(estimate < static_cast<double>(k - 1))) return BinOnSide(y, EdgeSearch(magnitude, k - 1));
  const size_t b = static_cast<size_t>(estimate);  // the floor, estimate being positive
  const double fraction = estimate - static_cast<double>(b);
  return BinOnSide(y, fraction > 1e-6 && fraction < 1 - 1e-6 ? b : EdgeSearch(magnitude, b));
}

size_t HistogramBinner::EdgeSearch(double magnitude, size_t b) const {
  const size_t k = bins_per_side_;
  while (b + 1 < k && magnitude >= lower_[b + 1]) ++b;
  while (b > 0 && magnitude < lower_[b]) --b;
  return b;
}

size_t HistogramBinner::BinOnSide(double y, size_t b) const {
  // Without a branch: for signed outputs the side is a coin toss.
  const size_t positive = bins_per_side_ + 2 + b, negative = bins_per_side_ - b;
  return y > 0 ? positive : negative;
}

double HistogramSpec::RelativeResolution() const { return std::pow(10.0, 0.5 / bins_per_decade) - 1.0; }

LogHistogram::LogHistogram(const HistogramSpec& spec) : spec_(spec) {
  spec_.Validate();
  bins_per_side_ = BinsPerSide(spec_);
  counts_.assign(spec_.NumBins(), 0);
}

void LogHistogram::AddBin(size_t bin, uint64_t count) {
  VSTCAL_CHECK(bin < counts_.size(), "histogram bin out of range");
  counts_[bin] += count;
  total_ += count;
}

void LogHistogram::Merge(const LogHistogram& other) {
  VSTCAL_CHECK(other.spec_ == spec_, "merging histograms of different specs");
  for (size_t b = 0; b < counts_.size(); ++b) counts_[b] += other.counts_[b];
  total_ += other.total_;
}

double LogHistogram::BinCentre(size_t bin) const {
  const size_t k = bins_per_side_;
  if (bin == k + 1) return 0.0;
  const bool positive = bin > k + 1;
  const size_t b = positive ? bin - (k + 2) : k - bin;
  const double centre = spec_.min_magnitude * std::pow(10.0, (static_cast<double>(b) + 0.5) / spec_.bins_per_decade);
  return positive ? centre : -centre;
}

Percentile LogHistogram::Quantile(double p, double observed_min, double observed_max) const {
  VSTCAL_CHECK(total_ > 0 && p > 0 && p < 1, "quantile of an empty histogram or p outside (0, 1)");
  const uint64_t rank = std::max<uint64_t>(1, static_cast<uint64_t>(std::ceil(p * static_cast<double>(total_))));
  uint64_t cumulative = 0;
  size_t bin = 0;
  for (; bin < counts_.size(); ++bin) {
    cumulative += counts_[bin];
    if (cumulative >= rank) break;
  }
  Percentile out;
  if (bin == 0 || bin == counts_.size() - 1) {
    out.in_range = false;
    out.value = bin == 0 ? observed_min : observed_max;
    return out;
  }
  out.value = std::clamp(BinCentre(bin), observed_min, observed_max);
  return out;
}

}  // namespace vstcal::sensitivity
