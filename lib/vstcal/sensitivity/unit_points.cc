#include "vstcal/sensitivity/unit_points.h"

#include <boost/random/sobol.hpp>

#include "vstcal/core/error.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

// Lane of the Philox blocks that hold the Sobol digital shifts: far above any lane a sample uses
// (j / 2 for j < 3667), so the shifts are independent of the pseudo-random draws of the same seed.
constexpr uint32_t kShiftLane = 0xFFFF0000u;
constexpr size_t kMaxSobolDimensions = 3667;  // boost::random::default_sobol_table::max_dimension

uint64_t Word(const PhiloxCounter& b, int half) {
  return (uint64_t{b[2 * half]} << 32) | b[2 * half + 1];
}

}  // namespace

std::string SamplingMethodName(SamplingMethod method) {
  return std::string(NameOf(kSamplingMethodNames, method));
}

SamplingMethod ParseSamplingMethod(const std::string& name) {
  if (const auto method = FromName(kSamplingMethodNames, name)) return *method;
  throw InputError("sampling: unknown method '" + name + "'; use " + JoinedNames(kSamplingMethodNames));
}

UnitPoints::UnitPoints(const SamplingOptions& options, size_t dimensions)
    : options_(options), dimensions_(dimensions) {
  if (dimensions == 0) throw InputError("sampling: zero dimensions; the parameter space is empty");
  if (options.method == SamplingMethod::kSobol) {
    if (dimensions > kMaxSobolDimensions) {
      throw InputError("sampling: " + std::to_string(dimensions) + " dimensions exceed the Sobol table's " +
                       std::to_string(kMaxSobolDimensions) + "; use pseudo-random sampling");
    }
    const CounterRng rng(options.seed, options.stream);
    shifts_.resize(dimensions);
    for (size_t j = 0; j < dimensions; ++j) shifts_[j] = Word(rng.Bits(j / 2, kShiftLane), static_cast<int>(j % 2));
  }
}

void UnitPoints::Fill(uint64_t first, size_t count, double* out) const {
  if (count == 0) return;
  if (options_.method == SamplingMethod::kSobol) {
    FillSobol(first, count, out);
  } else {
    FillPhilox(first, count, out);
  }
}

void UnitPoints::FillPhilox(uint64_t first, size_t count, double* out) const {
  const CounterRng rng(options_.seed, options_.stream);
  for (size_t s = 0; s < count; ++s) {
    for (size_t j = 0; j < dimensions_; j += 2) {
      const auto u = rng.Uniform2(first + s, static_cast<uint32_t>(j / 2));
      out[s * dimensions_ + j] = u[0];
      if (j + 1 < dimensions_) out[s * dimensions_ + j + 1] = u[1];
    }
  }
}

void UnitPoints::FillSobol(uint64_t first, size_t count, double* out) const {
  size_t s = 0;
  if (first == 0) {  // the all-zero point 0, which Boost's sequence skips
    for (size_t j = 0; j < dimensions_; ++j) out[j] = ToOpenUnit(shifts_[j]);
    s = 1;
  }
  if (s == count) return;
  boost::random::sobol engine(dimensions_);
  engine.seed(first + s - 1);  // Boost's point k is the sequence's point k + 1
  for (; s < count; ++s) {
    for (size_t j = 0; j < dimensions_; ++j) out[s * dimensions_ + j] = ToOpenUnit(engine() ^ shifts_[j]);
  }
}

}  // namespace vstcal
