// Fast draws of θ for err-sim's Monte Carlo (docs/math/vst-chain.md#sampling).
//
// Parameter j of sample i is a pure function of (seed, i, j): the j-th 64-bit word of the Philox
// stream (seed, stream 1) at index i — block lane j/2, first or second half — so a sample is the
// same whatever the thread count, the shard, or which other parameters are random. Constant
// parameters take their value without a draw. A uniform takes the word's top 53 bits; a normal
// goes through a 1024-layer ziggurat (Marsaglia & Tsang 2000, Doornik's 2005 layout) whose layer
// table is frozen in the source, so no libm call is made in 99.6 % of draws (the tail and the
// wedges draw further words from lanes 2³¹ + …). Compared with the sensitivity module's inverse CDF
// (AS 241, 11.5 ns a draw) this is the same distribution at about a fifth of the cost; it gives up
// the one-coordinate-per-parameter property that quasi-Monte Carlo needs, which err-sim run does
// not use. Every path below (AVX2 or not, one sample or four) gives the same bits.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "vstcal/core/simd_double.h"
#include "vstcal/errsim/chain_model.h"
#include "vstcal/random/philox.h"

namespace vstcal {

// A standard normal deviate from one 64-bit word and, rarely, further words of `rng` at
// (index, lanes 2³¹ + (parameter << 7) + k).
double ZigguratNormal(uint64_t word, const CounterRng& rng, uint64_t index, uint32_t parameter);

class ThetaSampler {
 public:
  static constexpr size_t kLanes = SimdDouble::kLanes;  // samples per group in FillLanes

  ThetaSampler(const ChainModel& model, uint64_t seed);

  size_t size() const { return num_parameters_; }
  size_t num_random() const { return draws_.size(); }
  // θ of samples first … first + kLanes·groups − 1 in groups of kLanes, one sample per lane: θ_j
  // of sample first + kLanes·g + l is lane l of theta[g·size() + j] — one group is the θ of a
  // ChainEvaluator::Evaluate<SimdDouble> call. Where the CPU has AVX2 a group's Philox blocks and
  // ziggurat rectangles are computed four samples at a time (the same bits as one at a time).
  void FillLanes(uint64_t first, size_t groups, SimdDouble* theta) const;
  // Rows first … first + count − 1 of θ, row-major (count × size()), one draw at a time without
  // SIMD: the reference for FillLanes, which gives the same numbers.
  void Fill(uint64_t first, size_t count, double* theta) const;

  // One random parameter: its value is a + b·z (normal, z standard normal) or a + b·u (uniform,
  // u in (0, 1)) from the 64-bit word `word` of the sampler's Philox words of a sample — word 2k
  // and 2k + 1 are the two halves of the block at the k-th lane of `blocks_` (sampler.cc).
  struct Draw {
    uint32_t parameter;
    uint32_t word;
    bool normal;
    double a, b;  // normal: mean, σ; uniform: lower bound, width
  };
  struct Constant {
    uint32_t parameter;
    double value;
  };

 private:
  size_t num_parameters_ = 0;
  std::vector<Constant> constants_;     // the parameters that are not drawn
  std::vector<uint32_t> blocks_;        // the Philox lanes that hold some draw (lane j/2 for parameter j)
  std::vector<Draw> draws_;             // in parameter order
  CounterRng rng_;
};

}  // namespace vstcal
