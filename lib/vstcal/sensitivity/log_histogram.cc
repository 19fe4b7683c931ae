#include "vstcal/sensitivity/log_histogram.h"

#include <algorithm>
#include <cmath>

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
