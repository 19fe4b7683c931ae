// Points of the open unit cube (0, 1)^d addressed by index: coordinate (i, j) is a pure function of
// (options, i, j), so any thread or shard that fills samples [first, first + count) gets the same
// bits as a single run that fills them all.
//
//  - kPseudoRandom: Philox-4×32-10 keyed by (seed, stream); sample i, coordinate j is half of the
//    block (index i, lane j / 2) (random/philox.h, docs/conventions.md#randomness).
//  - kSobol: the Sobol sequence of Boost.Random (Joe–Kuo direction numbers, up to 3667
//    dimensions), in Gray-code order, point 0 included (Boost starts at point 1; we prepend it, so
//    the first 2^m points are a (t, m, d)-net), with a random digital shift: every coordinate's
//    64-bit integer XOR-ed with a Philox word keyed by (seed, stream, j). Why a digital shift
//    (docs/math/sensitivity.md#qmc): it keeps the net property, makes the estimate unbiased,
//    gives independent replicates under different seeds, and moves point 0 off the corner where
//    Φ⁻¹(0) = −∞. Use N = 2^m samples for QMC: other sizes lose the net's balance.
//
// Coordinates are (k + ½)/2^53 for the top 53 bits k: never exactly 0 or 1.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>
#include "vstcal/core/enum_names.h"

namespace vstcal {

enum class SamplingMethod { kPseudoRandom, kSobol };
inline constexpr EnumNames<SamplingMethod, 2> kSamplingMethodNames = {{{SamplingMethod::kPseudoRandom, "pseudo-random"}, {SamplingMethod::kSobol, "sobol"}}};

// "pseudo-random" / "sobol": the words used in files and on command lines.
std::string SamplingMethodName(SamplingMethod method);
SamplingMethod ParseSamplingMethod(const std::string& name);  // InputError naming the choices

struct SamplingOptions {
  SamplingMethod method = SamplingMethod::kPseudoRandom;
  uint64_t seed = 0;
  uint32_t stream = 0;  // Philox stream, so one seed can feed unrelated analyses independently
};

class UnitPoints {
 public:
  // InputError for d = 0, or d above Boost's Sobol table (3667) for kSobol.
  UnitPoints(const SamplingOptions& options, size_t dimensions);

  size_t dimensions() const { return dimensions_; }
  // Writes points first … first + count − 1, row-major (count × d) into out.
  void Fill(uint64_t first, size_t count, double* out) const;

 private:
  void FillPhilox(uint64_t first, size_t count, double* out) const;
  void FillSobol(uint64_t first, size_t count, double* out) const;

  SamplingOptions options_;
  size_t dimensions_;
  std::vector<uint64_t> shifts_;  // Sobol digital shift per coordinate
};

// (k + ½)/2^53 for the top 53 bits k of a 64-bit word.
inline double ToOpenUnit(uint64_t bits) { return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53; }

}  // namespace vstcal
