#include "vstcal/errsim/sample_measurer.h"

#include <algorithm>

namespace vstcal::errsim {
namespace {

// The whole group in one function body (flatten inlines the chain, the measures and Eigen's
// expression templates into it), cloned for AVX2 and for the x86-64 baseline: each SimdDouble
// operation is then one 256-bit instruction or two 128-bit ones, with the same results. y moves
// out here too, so that its stores have the width of the arithmetic.
[[gnu::target_clones("avx2", "default"), gnu::flatten]] bool EvaluateLanes(const ChainEvaluator& chain,
                                                                         const ErrorOutputs& outputs,
                                                                         const SimdDouble* theta, double* y,
                                                                         ChainSample<SimdDouble>* sample,
                                                                         SimdDouble* y_lanes) {
  chain.Evaluate(theta, sample);
  if (!outputs.Measure(chain, *sample, theta, y_lanes)) return false;
  for (size_t k = 0; k < outputs.size(); ++k) y_lanes[k].Store(y + SimdDouble::kLanes * k);
  return true;
}

}  // namespace

SampleMeasurer::SampleMeasurer(const ChainEvaluator& chain, const ErrorOutputs& outputs)
    : chain_(chain),
      outputs_(outputs),
      sample_(chain.num_points()),
      lanes_sample_(chain.num_points()),
      y_lanes_(outputs.size()),
      row_(chain.model().parameters.size()),
      y_row_(outputs.size()) {}

void SampleMeasurer::MeasureLanes(const SimdDouble* theta, double* y, bool* defined) {
  SimdDivergence::Clear();
  const bool all_defined = EvaluateLanes(chain_, outputs_, theta, y, &lanes_sample_, y_lanes_.data());
  if (!SimdDivergence::Occurred()) {
    std::fill_n(defined, kLanes, all_defined);
    return;
  }
  ++divergent_groups_;
  const size_t n = row_.size(), m = y_row_.size();
  for (size_t l = 0; l < kLanes; ++l) {
    for (size_t j = 0; j < n; ++j) row_[j] = theta[j].lane(static_cast<int>(l));
    defined[l] = MeasureOne(row_.data(), y_row_.data());
    for (size_t k = 0; k < m; ++k) y[kLanes * k + l] = y_row_[k];
  }
}

bool SampleMeasurer::MeasureOne(const double* theta, double* y) {
  chain_.Evaluate(theta, &sample_);
  return outputs_.Measure(chain_, sample_, theta, y);
}

}  // namespace vstcal::errsim
