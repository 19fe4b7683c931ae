// Fast draws of θ for err-sim's Monte Carlo (docs/math/vst-chain.md#sampling).
//
// Parameter j of sample i is a pure function of (seed, i, j): the j-th 64-bit word of the Philox
// stream (seed, stream 1) at index i — block lane j/2, first or second half — so a sample is the
// same whatever the thread count, the shard, or which other parameters are random. Constant
// parameters take their value without a draw. A uniform takes the word's top 53 bits; a normal
// goes through a 128-layer ziggurat (Marsaglia & Tsang 2000, Doornik's 2005 layout) whose layer
// table is frozen in the source, so no libm call is made in 98.8 % of draws (the tail and the
// wedges draw further words from lanes 2³¹ + …). Compared with the sensitivity module's inverse CDF
// (AS 241, 11.5 ns a draw) this is the same distribution at about a fifth of the cost; it gives up
// the one-coordinate-per-parameter property that quasi-Monte Carlo needs, which err-sim run does
// not use.
#pragma once

#include <cstdint>
#include <vector>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/random/philox.h"

namespace vstcal::errsim {

// A standard normal deviate from one 64-bit word and, rarely, further words of `rng` at
// (index, lanes 2³¹ + (parameter << 7) + k).
double ZigguratNormal(uint64_t word, const CounterRng& rng, uint64_t index, uint32_t parameter);

// The Philox blocks (index first + s, lane, stream) for s < count as two 64-bit words each,
// out[s·stride] = b₀·2³² + b₁ and out[s·stride + 1] = b₂·2³² + b₃. Four samples at a time with
// AVX2 where the CPU has it: integer arithmetic, so the same bits as CounterRng::Bits anywhere.
void PhiloxWords(const CounterRng& rng, uint64_t first, size_t count, uint32_t lane, uint64_t* out, size_t stride = 2);

class ThetaSampler {
 public:
  ThetaSampler(const ChainModel& model, uint64_t seed);

  size_t size() const { return constants_.size(); }
  size_t num_random() const { return draws_.size(); }
  // Rows first … first + count − 1 of θ, row-major (count × size()).
  void Fill(uint64_t first, size_t count, double* theta) const;

 private:
  struct Draw {
    uint32_t parameter;
    bool normal;  // else uniform
    double a, b;  // normal: mean, σ; uniform: lower bound, width
  };
  std::vector<double> constants_;
  std::vector<Draw> draws_;        // in parameter order
  std::vector<uint32_t> lanes_;    // the Philox lanes that hold some draw
  std::vector<uint32_t> slot_;     // per draw: its lane's position in lanes_
  CounterRng rng_;
};

}  // namespace vstcal::errsim
