#include "vstcal/errsim/sampler.h"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

namespace vstcal::errsim {
namespace {

#include "vstcal/errsim/ziggurat_table.inc"

constexpr double kR = 3.442619855899;  // the base strip's edge (Marsaglia & Tsang 2000)
constexpr uint32_t kExtraLanes = 0x80000000u;

// (k + ½)·2⁻⁵³ for the top 53 bits k: in (0, 1), never 0 or 1. (Through int64: x86-64 converts
// a signed integer in one instruction, an unsigned one in a branchy sequence.)
inline double OpenUnit(uint64_t word) {
  return (static_cast<double>(static_cast<int64_t>(word >> 11)) + 0.5) * 0x1.0p-53;
}

inline uint64_t Word(const PhiloxCounter& block, int half) {
  return half == 0 ? (uint64_t{block[0]} << 32 | block[1]) : (uint64_t{block[2]} << 32 | block[3]);
}

// Further words for rejections: lane 2³¹ + (parameter << 7) + k/2, half k % 2.
class ExtraWords {
 public:
  ExtraWords(const CounterRng& rng, uint64_t index, uint32_t parameter) : rng_(rng), index_(index), parameter_(parameter) {}
  uint64_t Next() {
    if (k_ % 2 == 0) block_ = rng_.Bits(index_, kExtraLanes + (parameter_ << 7) + (k_ / 2) % 128);
    return Word(block_, k_++ % 2);
  }

 private:
  const CounterRng& rng_;
  uint64_t index_;
  uint32_t parameter_;
  uint32_t k_ = 0;
  PhiloxCounter block_{};
};

}  // namespace

namespace {

// Everything but the rectangle: the tail, the wedges, and retries with further words.
[[gnu::noinline]] double ZigguratSlow(uint64_t word, const CounterRng& rng, uint64_t index, uint32_t parameter) {
  ExtraWords extra(rng, index, parameter);
  for (;;) {
    const int layer = static_cast<int>(word & 127);
    const double sign = (word & 128) ? -1.0 : 1.0;
    const double x = OpenUnit(word) * kZigX[layer];
    if (x < kZigX[layer + 1]) return sign * x;
    if (layer == 0) {
      // The tail beyond r (Marsaglia 1964): a = −ln(u₁)/r, b = −ln(u₂), accept when 2b > a².
      for (;;) {
        const double a = -std::log(OpenUnit(extra.Next())) / kR;
        const double b = -std::log(OpenUnit(extra.Next()));
        if (b + b > a * a) return sign * (kR + a);
      }
    }
    // The wedge between the rectangle and the curve.
    const double y = kZigF[layer + 1] + OpenUnit(extra.Next()) * (kZigF[layer] - kZigF[layer + 1]);
    if (y < std::exp(-0.5 * x * x)) return sign * x;
    word = extra.Next();
  }
}

// Bits 0–6 pick the layer, bit 7 the sign, the top 53 the position: inside the layer's rectangle
// (98.8 % of draws) the deviate is sign · u · x[layer].
inline double ZigguratFast(uint64_t word, const CounterRng& rng, uint64_t index, uint32_t parameter) {
  const int layer = static_cast<int>(word & 127);
  const double x = OpenUnit(word) * kZigX[layer];
  // The sign by flipping the sign bit, not by a branch: bit 7 is a coin toss no predictor can learn.
  if (x < kZigX[layer + 1]) return std::bit_cast<double>(std::bit_cast<uint64_t>(x) ^ ((word & 128) << 56));
  return ZigguratSlow(word, rng, index, parameter);
}

void PhiloxWordsScalar(const CounterRng& rng, uint64_t first, size_t count, uint32_t lane, uint64_t* out, size_t stride) {
  for (size_t s = 0; s < count; ++s) {
    const PhiloxCounter b = rng.Bits(first + s, lane);
    out[s * stride] = Word(b, 0);
    out[s * stride + 1] = Word(b, 1);
  }
}

// Philox-4×32-10 on four counters at once: each 32-bit word sits in the low half of a 64-bit
// element, so _mm256_mul_epu32 gives the four 32×32→64 products of a round in one instruction.
[[gnu::target("avx2")]] void PhiloxWordsAvx2(const CounterRng& rng, uint64_t first, size_t count, uint32_t lane,
                                             uint64_t* out, size_t stride) {
  const __m256i m0 = _mm256_set1_epi64x(0xD2511F53), m1 = _mm256_set1_epi64x(0xCD9E8D57);
  const __m256i low = _mm256_set1_epi64x(0xffffffff);
  const PhiloxKey key = rng.key();
  size_t s = 0;
  for (; s + 4 <= count; s += 4) {
    const uint64_t i0 = first + s;
    __m256i c0 = _mm256_set_epi64x(static_cast<uint32_t>(i0 + 3), static_cast<uint32_t>(i0 + 2),
                                   static_cast<uint32_t>(i0 + 1), static_cast<uint32_t>(i0));
    __m256i c1 = _mm256_set_epi64x((i0 + 3) >> 32, (i0 + 2) >> 32, (i0 + 1) >> 32, i0 >> 32);
    __m256i c2 = _mm256_set1_epi64x(lane);
    __m256i c3 = _mm256_set1_epi64x(rng.stream());
    uint32_t k0 = key[0], k1 = key[1];
    for (int round = 0; round < 10; ++round) {
      if (round > 0) {
        k0 += 0x9E3779B9u;
        k1 += 0xBB67AE85u;
      }
      const __m256i p0 = _mm256_mul_epu32(c0, m0);
      const __m256i p1 = _mm256_mul_epu32(c2, m1);
      const __m256i n0 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(p1, 32), c1), _mm256_set1_epi64x(k0));
      const __m256i n2 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(p0, 32), c3), _mm256_set1_epi64x(k1));
      c1 = _mm256_and_si256(p1, low);
      c3 = _mm256_and_si256(p0, low);
      c0 = n0;
      c2 = n2;
    }
    alignas(32) uint64_t w0[4], w1[4];
    _mm256_store_si256(reinterpret_cast<__m256i*>(w0), _mm256_or_si256(_mm256_slli_epi64(c0, 32), c1));
    _mm256_store_si256(reinterpret_cast<__m256i*>(w1), _mm256_or_si256(_mm256_slli_epi64(c2, 32), c3));
    for (int k = 0; k < 4; ++k) {
      out[(s + k) * stride] = w0[k];
      out[(s + k) * stride + 1] = w1[k];
    }
  }
  PhiloxWordsScalar(rng, first + s, count - s, lane, out + s * stride, stride);
}

}  // namespace

double ZigguratNormal(uint64_t word, const CounterRng& rng, uint64_t index, uint32_t parameter) {
  return ZigguratFast(word, rng, index, parameter);
}

void PhiloxWords(const CounterRng& rng, uint64_t first, size_t count, uint32_t lane, uint64_t* out, size_t stride) {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) {
    PhiloxWordsAvx2(rng, first, count, lane, out, stride);
  } else {
    PhiloxWordsScalar(rng, first, count, lane, out, stride);
  }
}

ThetaSampler::ThetaSampler(const ChainModel& model, uint64_t seed) : rng_(seed, 1) {
  for (size_t j = 0; j < model.parameters.size(); ++j) {
    const Distribution& d = model.parameters[j].distribution;
    constants_.push_back(d.Mean());
    if (d.IsConstant()) continue;
    if (const auto* n = std::get_if<Distribution::Normal>(&d.form())) {
      draws_.push_back({static_cast<uint32_t>(j), true, n->mean, n->sigma});
    } else if (const auto* u = std::get_if<Distribution::Uniform>(&d.form())) {
      draws_.push_back({static_cast<uint32_t>(j), false, u->lo, u->hi - u->lo});
    }
    const uint32_t lane = static_cast<uint32_t>(j / 2);
    if (lanes_.empty() || lanes_.back() != lane) lanes_.push_back(lane);
    slot_.push_back(static_cast<uint32_t>(lanes_.size() - 1));
  }
}

void ThetaSampler::Fill(uint64_t first, size_t count, double* theta) const {
  const size_t n = constants_.size(), lanes = lanes_.size();
  // Words for a chunk of samples (vectorized over samples), sample-major so that each row reads
  // its words contiguously; 32 samples × 2 words × lanes stays in the L1 cache.
  constexpr size_t kChunk = 32;
  thread_local std::vector<uint64_t> words;
  words.resize(2 * kChunk * lanes);
  for (size_t c = 0; c < count; c += kChunk) {
    const size_t m = std::min(kChunk, count - c);
    for (size_t l = 0; l < lanes; ++l) PhiloxWords(rng_, first + c, m, lanes_[l], &words[2 * l], 2 * lanes);
    for (size_t s = 0; s < m; ++s) {
      double* row = theta + (c + s) * n;
      const uint64_t* w = &words[2 * lanes * s];
      std::memcpy(row, constants_.data(), n * sizeof(double));
      for (size_t k = 0; k < draws_.size(); ++k) {
        const Draw& d = draws_[k];
        const uint64_t word = w[2 * slot_[k] + d.parameter % 2];
        row[d.parameter] =
            d.normal ? d.a + d.b * ZigguratFast(word, rng_, first + c + s, d.parameter) : d.a + d.b * OpenUnit(word);
      }
    }
  }
}

}  // namespace vstcal::errsim
