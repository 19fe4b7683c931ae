// Counter-based random numbers: Philox-4×32-10 (Salmon et al., "Parallel random numbers: as easy
// as 1, 2, 3", SC 2011). A draw is a pure function of (seed, stream, index, lane), so results do
// not depend on thread count, order of evaluation or shard split (docs/conventions.md#randomness).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace vstcal {

using PhiloxCounter = std::array<uint32_t, 4>;
using PhiloxKey = std::array<uint32_t, 2>;

// One Philox-4×32 block with 10 rounds. Matches the Random123 known-answer vectors.
constexpr PhiloxCounter Philox4x32(PhiloxCounter ctr, PhiloxKey key) {
  constexpr uint32_t kM0 = 0xD2511F53u, kM1 = 0xCD9E8D57u;
  constexpr uint32_t kW0 = 0x9E3779B9u, kW1 = 0xBB67AE85u;
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {
      key[0] += kW0;
      key[1] += kW1;
    }
    const uint64_t p0 = uint64_t{kM0} * ctr[0];
    const uint64_t p1 = uint64_t{kM1} * ctr[2];
    ctr = {static_cast<uint32_t>(p1 >> 32) ^ ctr[1] ^ key[0], static_cast<uint32_t>(p1),
           static_cast<uint32_t>(p0 >> 32) ^ ctr[3] ^ key[1], static_cast<uint32_t>(p0)};
  }
  return ctr;
}

// A stream of random numbers keyed by (seed, stream). Draw `index` (e.g. a Monte Carlo sample or
// a point) and `lane` (which draw within it) address one Philox block of 128 bits.
class CounterRng {
 public:
  constexpr CounterRng(uint64_t seed, uint32_t stream)
      : key_{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32)}, stream_(stream) {}

  constexpr PhiloxCounter Bits(uint64_t index, uint32_t lane) const {
    return Philox4x32({static_cast<uint32_t>(index), static_cast<uint32_t>(index >> 32), lane, stream_}, key_);
  }

  // Two independent uniforms in the open interval (0, 1), 53 bits each.
  std::array<double, 2> Uniform2(uint64_t index, uint32_t lane) const {
    const PhiloxCounter b = Bits(index, lane);
    return {ToOpenUnit(b[0], b[1]), ToOpenUnit(b[2], b[3])};
  }

  // Two independent standard normal deviates (Box–Muller on Uniform2).
  std::array<double, 2> Normal2(uint64_t index, uint32_t lane) const {
    const auto [u1, u2] = Uniform2(index, lane);
    const double radius = std::sqrt(-2.0 * std::log(u1));
    const double angle = 6.283185307179586476925 * u2;
    return {radius * std::cos(angle), radius * std::sin(angle)};
  }

  // The block cipher's key and the stream word, for batched (SIMD) evaluations of Bits.
  constexpr PhiloxKey key() const { return key_; }
  constexpr uint32_t stream() const { return stream_; }

 private:
  // (k + 0.5) / 2^53 for the top 53 bits k: never 0 or 1, so log(u) is finite.
  static constexpr double ToOpenUnit(uint32_t hi, uint32_t lo) {
    const uint64_t k = ((uint64_t{hi} << 32) | lo) >> 11;
    return (static_cast<double>(k) + 0.5) * 0x1.0p-53;
  }

  PhiloxKey key_;
  uint32_t stream_;
};

}  // namespace vstcal
