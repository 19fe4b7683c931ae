#include "vstcal/sensitivity/log_histogram.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

constexpr uint64_t kMagnitude = 0x7fffffffffffffffull;
constexpr uint64_t kSign = 0x8000000000000000ull;

uint64_t ExponentBits(int exponent) { return static_cast<uint64_t>(1023 + exponent) << 52; }

}  // namespace

void HistogramSpec::Validate() const {
  if (!(-1000 <= min_exponent && min_exponent < max_exponent && max_exponent <= 1000)) {
    throw InputError("histogram: need -1000 <= min_exponent < max_exponent <= 1000");
  }
  if (sub_bins_log2 < 0 || sub_bins_log2 > 12) throw InputError("histogram: sub_bins_log2 must be in [0, 12]");
  if (BinsPerSide() > (size_t{1} << 20)) throw InputError("histogram: more than 2^20 bins a side; narrow the exponent range");
}

size_t HistogramSpec::BinOf(double y) const {
  const size_t k = BinsPerSide();
  const uint64_t bits = std::bit_cast<uint64_t>(y);
  const uint64_t magnitude = bits & kMagnitude;
  const uint64_t low = ExponentBits(min_exponent), high = ExponentBits(max_exponent);
  if (magnitude < low || magnitude > 0x7ff0000000000000ull) return k + 1;  // tiny, or NaN
  if (magnitude >= high) return (bits & kSign) ? 0 : 2 * k + 2;
  const size_t b = static_cast<size_t>((magnitude - low) >> (52 - sub_bins_log2));
  return (bits & kSign) ? k - b : k + 2 + b;
}

// Dispatched by hand rather than with target_clones: clang 14 emits a target_clones member
// function's ifunc without its plain name, so callers in other units do not link.
namespace {
[[gnu::target("avx2")]] void BinsOf4Avx2(const HistogramSpec& spec, const double* y, uint32_t* bins) { BinsOf4Inline(spec, y, bins); }
void BinsOf4Default(const HistogramSpec& spec, const double* y, uint32_t* bins) { BinsOf4Inline(spec, y, bins); }
}  // namespace

void HistogramSpec::BinsOf4(const double* y, uint32_t* bins) const {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  (avx2 ? BinsOf4Avx2 : BinsOf4Default)(*this, y, bins);
}

double HistogramSpec::BinLow(size_t bin) const {
  const size_t k = BinsPerSide();
  if (bin == k + 1) return 0.0;
  if (bin == 0 || bin == 2 * k + 2) return std::ldexp(1.0, max_exponent);
  const size_t b = bin > k + 1 ? bin - (k + 2) : k - bin;
  return std::bit_cast<double>(ExponentBits(min_exponent) + (static_cast<uint64_t>(b) << (52 - sub_bins_log2)));
}

double HistogramSpec::BinHigh(size_t bin) const {
  const size_t k = BinsPerSide();
  if (bin == k + 1) return std::ldexp(1.0, min_exponent);
  if (bin == 0 || bin == 2 * k + 2) return HUGE_VAL;
  const size_t b = bin > k + 1 ? bin - (k + 2) : k - bin;
  return std::bit_cast<double>(ExponentBits(min_exponent) + (static_cast<uint64_t>(b + 1) << (52 - sub_bins_log2)));
}

double HistogramSpec::RelativeResolution() const { return std::ldexp(1.0, -(sub_bins_log2 + 1)); }

LogHistogram::LogHistogram(const HistogramSpec& spec) : spec_(spec) { spec_.Validate(); }

LogHistogram::LogHistogram(const LogHistogram& other) : spec_(other.spec_), total_(other.total_) {
  pages_.resize(other.pages_.size());
  for (size_t p = 0; p < pages_.size(); ++p) {
    if (other.pages_[p]) pages_[p] = std::make_unique<Page>(*other.pages_[p]);
  }
}

LogHistogram& LogHistogram::operator=(const LogHistogram& other) {
  if (this != &other) *this = LogHistogram(other);
  return *this;
}

void LogHistogram::AddBin(size_t bin, uint64_t count) {
  VSTCAL_CHECK(bin < spec_.NumBins(), "histogram bin out of range");
  if (bin / kPageSize >= pages_.size()) pages_.resize(bin / kPageSize + 1);
  std::unique_ptr<Page>& page = pages_[bin / kPageSize];
  if (!page) page = std::make_unique<Page>(Page{});
  (*page)[bin % kPageSize] += count;
  total_ += count;
}

void LogHistogram::AddBins(const uint32_t* bins, size_t n, uint32_t skip) {
  const size_t num_bins = spec_.NumBins();
  uint64_t added = 0;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t bin = bins[i];
    if (bin == skip) continue;
    VSTCAL_CHECK(bin < num_bins, "histogram bin out of range");
    const size_t p = bin / kPageSize;
    if (p >= pages_.size()) pages_.resize(p + 1);
    if (!pages_[p]) pages_[p] = std::make_unique<Page>(Page{});
    ++(*pages_[p])[bin % kPageSize];
    ++added;
  }
  total_ += added;
}

uint64_t LogHistogram::count(size_t bin) const {
  if (bin / kPageSize >= pages_.size()) return 0;
  const std::unique_ptr<Page>& page = pages_[bin / kPageSize];
  return page ? (*page)[bin % kPageSize] : 0;
}

void LogHistogram::Merge(const LogHistogram& other) {
  VSTCAL_CHECK(other.spec_ == spec_, "merging histograms of different specs");
  if (other.pages_.size() > pages_.size()) pages_.resize(other.pages_.size());
  for (size_t p = 0; p < other.pages_.size(); ++p) {
    if (!other.pages_[p]) continue;
    if (!pages_[p]) pages_[p] = std::make_unique<Page>(Page{});
    for (size_t i = 0; i < kPageSize; ++i) (*pages_[p])[i] += (*other.pages_[p])[i];
  }
  total_ += other.total_;
}

size_t LogHistogram::MemoryBytes() const {
  size_t pages = 0;
  for (const auto& page : pages_) pages += page != nullptr;
  return pages * sizeof(Page) + pages_.size() * sizeof(pages_[0]);
}

Percentile LogHistogram::Quantile(double p, double observed_min, double observed_max) const {
  VSTCAL_CHECK(total_ > 0 && p > 0 && p < 1, "quantile of an empty histogram or p outside (0, 1)");
  const uint64_t rank = std::max<uint64_t>(1, static_cast<uint64_t>(std::ceil(p * static_cast<double>(total_))));
  uint64_t cumulative = 0;
  size_t bin = spec_.NumBins() - 1;
  for (size_t page = 0; page < pages_.size() && cumulative < rank; ++page) {
    if (!pages_[page]) continue;
    for (size_t i = 0; i < kPageSize; ++i) {
      cumulative += (*pages_[page])[i];
      if (cumulative >= rank) {
        bin = page * kPageSize + i;
        break;
      }
    }
  }
  Percentile out;
  const size_t k = spec_.BinsPerSide();
  if (bin == 0 || bin == 2 * k + 2) {
    out.in_range = false;
    out.value = bin == 0 ? observed_min : observed_max;
    return out;
  }
  const double midpoint = bin == k + 1 ? 0.0 : 0.5 * (spec_.BinLow(bin) + spec_.BinHigh(bin));
  out.value = std::clamp(bin < k + 1 ? -midpoint : midpoint, observed_min, observed_max);
  return out;
}

}  // namespace vstcal
