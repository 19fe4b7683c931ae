#include "vstcal/errsim/sample_measurer.h"

#include <algorithm>
#include <bit>

namespace vstcal {
namespace {

// The whole group in one function body (flatten inlines the chain, the measures and Eigen's
// expression templates into it), cloned for AVX-512 machines, AVX2 and the x86-64 baseline: each
// SimdDouble operation is then one 256-bit instruction or two 128-bit ones, with the same results.
// The AVX-512 clone still works in 256 bits but has 32 vector registers instead of 16, and the body
// spills far less: 12–16 % less time a chain sample (docs/performance.md#err-sim). y moves out here
// too, so that its stores have the width of the arithmetic.
[[gnu::target_clones("arch=x86-64-v4", "avx2", "default"), VSTCAL_FLATTEN_LANES]] void EvaluateLanes(
    const ChainEvaluator& chain, const ErrorOutputs& outputs, const SimdDouble* theta, double* y, bool* defined,
    ChainSample<SimdDouble>* sample, SimdDouble* y_lanes) {
  chain.Evaluate(theta, sample);
  outputs.Measure(chain, *sample, theta, y_lanes, defined);
  for (size_t k = 0; k < outputs.size(); ++k) y_lanes[k].Store(y + SimdDouble::kLanes * k);
}

}  // namespace

SampleMeasurer::SampleMeasurer(const ChainEvaluator& chain, const ErrorOutputs& outputs)
    : chain_(chain),
      outputs_(outputs),
      sample_(chain.num_points()),
      lanes_sample_(chain.num_points()),
      y_lanes_(outputs.size()),
      row_(chain.model().parameters.size()),
      y_row_(outputs.size()),
      point_defined_(chain.num_points()),
      row_defined_(new bool[chain.num_points() + 1]) {}

int SampleMeasurer::MeasureLanes(const SimdDouble* theta, double* y, uint8_t* defined) {
  const size_t points = chain_.num_points(), m = y_row_.size();
  SimdDivergence::Clear();
  EvaluateLanes(chain_, outputs_, theta, y, row_defined_.get(), &lanes_sample_, y_lanes_.data());
  if (!SimdDivergence::Occurred()) {
    // Every lane took the same path: a point is defined in all four or in none.
    for (size_t p = 0; p < points; ++p) point_defined_[p] = row_defined_[p] ? 0xf : 0;
  } else {
    ++divergent_groups_;
    std::fill(point_defined_.begin(), point_defined_.end(), 0);
    for (size_t l = 0; l < kLanes; ++l) {
      for (size_t j = 0; j < row_.size(); ++j) row_[j] = theta[j].lane(static_cast<int>(l));
      MeasureOne(row_.data(), y_row_.data(), row_defined_.get());
      for (size_t p = 0; p < points; ++p) point_defined_[p] |= row_defined_[p] << l;
      for (size_t k = 0; k < m; ++k) y[kLanes * k + l] = y_row_[k];
    }
  }
  uint8_t all = 0xf;
  for (size_t p = 0; p < points; ++p) all &= point_defined_[p];
  for (size_t k = 0; k < m; ++k) defined[k] = point_defined_[outputs_.point_of(k)];
  return static_cast<int>(kLanes) - std::popcount(static_cast<unsigned>(all));
}

void SampleMeasurer::MeasureOne(const double* theta, double* y, bool* defined) {
  chain_.Evaluate(theta, &sample_);
  outputs_.Measure(chain_, sample_, theta, y, defined);
}

}  // namespace vstcal
