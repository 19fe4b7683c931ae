// The chain and its error measures for err-sim's Monte Carlo loop (engine.h), four samples at a
// time: ChainEvaluator::Evaluate and ErrorOutputs::Measure instantiated with SimdDouble, one
// sample per lane, compiled for AVX-512 machines (32 registers) and for AVX2 where the CPU has
// them, else for the x86-64 baseline. The same templates with double give
// every lane's numbers bit for bit (simd_double.h, geometry/fixed_order.h), so where the lanes
// would branch differently (in some lanes only: a point undefined, a rotation or an angle beyond
// 0.1 rad, a fiducial registration that converges later) the group is redone one sample at a time,
// and the results never depend on the grouping (docs/math/vst-chain.md#lanes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "vstcal/core/simd_double.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/measures.h"

// The attribute for a function that evaluates a group of lanes in one body (chain and measures
// inlined into it). Under AddressSanitizer the flattened body takes minutes of compile time to
// instrument (once it was most of the sanitizer build), and clang (the fuzz build) refuses flatten
// on a target_clones function; inlining does not change a result (-ffp-contract=off), so those
// builds evaluate the same code without it.
#if defined(__SANITIZE_ADDRESS__) || defined(__clang__)
#define VSTCAL_FLATTEN_LANES
#else
#define VSTCAL_FLATTEN_LANES gnu::flatten
#endif

namespace vstcal {

class SampleMeasurer {
 public:
  static constexpr size_t kLanes = SimdDouble::kLanes;

  // Keeps references: chain and outputs must outlive the measurer. One measurer per thread.
  SampleMeasurer(const ChainEvaluator& chain, const ErrorOutputs& outputs);

  // Four samples, one per lane of θ (one group of ThetaSampler::FillLanes). Writes the outputs
  // lane-interleaved, output k of lane l at y[kLanes·k + l] (kLanes·outputs.size() values), and
  // defined[k], the lanes (bit l) where output k's test point is defined (elsewhere y is
  // unspecified). Returns how many of the four samples have some test point undefined.
  int MeasureLanes(const SimdDouble* theta, double* y, uint8_t* defined);
  // One sample from a row of θ, with double: y and defined[k] per test point (ErrorOutputs::Measure).
  void MeasureOne(const double* theta, double* y, bool* defined);
  // Groups redone one sample at a time since construction (lanes that took different branches).
  size_t divergent_groups() const { return divergent_groups_; }

 private:
  const ChainEvaluator& chain_;
  const ErrorOutputs& outputs_;
  ChainSample<double> sample_;
  ChainSample<SimdDouble> lanes_sample_;
  std::vector<SimdDouble> y_lanes_;
  std::vector<double> row_, y_row_;
  std::vector<uint8_t> point_defined_;  // per test point, one byte of lane bits
  std::unique_ptr<bool[]> row_defined_;
  size_t divergent_groups_ = 0;
};

}  // namespace vstcal
