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

// The value of one draw from its word (sample `index`).
inline double DrawValue(const ThetaSampler::Draw& d, uint64_t word, const CounterRng& rng, uint64_t index) {
  return d.normal ? d.a + d.b * ZigguratFast(word, rng, index, d.parameter) : d.a + d.b * OpenUnit(word);
}

using Draw = ThetaSampler::Draw;
using Constant = ThetaSampler::Constant;
constexpr size_t kLanes = ThetaSampler::kLanes;

// One sample's draws one at a time, parameter j to out[j·stride]: the reference that the AVX2
// kernel reproduces bit for bit.
void DrawSample(const std::vector<uint32_t>& blocks, const std::vector<Draw>& draws, const CounterRng& rng,
                uint64_t index, double* out, size_t stride) {
  PhiloxCounter bits{};
  uint32_t block = UINT32_MAX;
  for (const Draw& d : draws) {
    if (d.word / 2 != block) bits = rng.Bits(index, blocks[block = d.word / 2]);
    out[d.parameter * stride] = DrawValue(d, Word(bits, d.word % 2), rng, index);
  }
}

void FillGroupsScalar(size_t size, const std::vector<uint32_t>& blocks, const std::vector<Draw>& draws,
                      const std::vector<Constant>& constants, const CounterRng& rng, uint64_t first, size_t groups,
                      double* theta) {
  for (size_t g = 0; g < groups; ++g) {
    double* out = theta + g * kLanes * size;
    for (const Constant& c : constants) std::fill_n(out + kLanes * c.parameter, kLanes, c.value);
    for (size_t l = 0; l < kLanes; ++l) DrawSample(blocks, draws, rng, first + kLanes * g + l, out + l, kLanes);
  }
}

// OpenUnit on four words: the top 53 bits k converted exactly in two parts (no 64-bit integer to
// double conversion before AVX-512), k = (2⁸⁴ + hi·2³²) − 2⁸⁴ + (2⁵² + lo) − 2⁵², then the same
// (k + ½)·2⁻⁵³ as the scalar path.
[[gnu::target("avx2")]] inline __m256d OpenUnitAvx2(__m256i word) {
  const __m256i k = _mm256_srli_epi64(word, 11);
  const __m256i hi = _mm256_or_si256(_mm256_srli_epi64(k, 32), _mm256_set1_epi64x(0x4530000000000000));
  const __m256i lo = _mm256_or_si256(_mm256_and_si256(k, _mm256_set1_epi64x(0xffffffff)), _mm256_set1_epi64x(0x4330000000000000));
  const __m256d exact = _mm256_add_pd(_mm256_sub_pd(_mm256_castsi256_pd(hi), _mm256_set1_pd(0x1.0p84)),
                                      _mm256_sub_pd(_mm256_castsi256_pd(lo), _mm256_set1_pd(0x1.0p52)));
  return _mm256_mul_pd(_mm256_add_pd(exact, _mm256_set1_pd(0.5)), _mm256_set1_pd(0x1.0p-53));
}

// ZigguratFast on the four words at `words` (samples index … index + 3); lanes outside their
// rectangle take the scalar slow path.
[[gnu::target("avx2")]] inline __m256d ZigguratAvx2(const uint64_t* words, const CounterRng& rng, uint64_t index,
                                                   uint32_t parameter) {
  const __m256i word = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(words));
  // The layer's two edges by scalar loads: on Zen 3 two gathers cost more than the rest together.
  const double* x0 = &kZigX[words[0] & 127];
  const double* x1 = &kZigX[words[1] & 127];
  const double* x2 = &kZigX[words[2] & 127];
  const double* x3 = &kZigX[words[3] & 127];
  const __m256d x = _mm256_mul_pd(OpenUnitAvx2(word), _mm256_setr_pd(x0[0], x1[0], x2[0], x3[0]));
  const __m256d edge = _mm256_setr_pd(x0[1], x1[1], x2[1], x3[1]);
  const __m256i sign = _mm256_slli_epi64(_mm256_and_si256(word, _mm256_set1_epi64x(128)), 56);
  const __m256d z = _mm256_xor_pd(x, _mm256_castsi256_pd(sign));
  const int inside = _mm256_movemask_pd(_mm256_cmp_pd(x, edge, _CMP_LT_OQ));
  if (inside == 0xf) [[likely]] return z;
  alignas(32) double lanes[kLanes];
  _mm256_store_pd(lanes, z);
  for (size_t l = 0; l < kLanes; ++l) {
    if (!(inside >> l & 1)) lanes[l] = ZigguratSlow(words[l], rng, index + l, parameter);
  }
  return _mm256_load_pd(lanes);
}

// Philox-4×32-10 on the four samples of a group at once: each 32-bit word sits in the low half of
// a 64-bit element, so _mm256_mul_epu32 gives the four 32×32→64 products of a round in one
// instruction. Integer arithmetic: the same bits as CounterRng::Bits.
struct PhiloxAvx2 {
  __m256i m0, m1, stream;
  std::array<__m256i, 10> key0, key1;  // round keys

  [[gnu::target("avx2")]] explicit PhiloxAvx2(const CounterRng& rng) {
    m0 = _mm256_set1_epi64x(0xD2511F53), m1 = _mm256_set1_epi64x(0xCD9E8D57);
    stream = _mm256_set1_epi64x(rng.stream());
    PhiloxKey key = rng.key();
    for (int round = 0; round < 10; ++round) {
      if (round > 0) key[0] += 0x9E3779B9u, key[1] += 0xBB67AE85u;
      key0[round] = _mm256_set1_epi64x(key[0]);
      key1[round] = _mm256_set1_epi64x(key[1]);
    }
  }

  // c1 and c3 keep the high halves of the products: _mm256_mul_epu32 ignores the high half of its
  // inputs, and Words masks them once at the end.
  [[gnu::target("avx2"), gnu::always_inline]] inline void Round(int round, __m256i& c0, __m256i& c1, __m256i& c2,
                                                               __m256i& c3) const {
    const __m256i p0 = _mm256_mul_epu32(c0, m0);
    const __m256i p1 = _mm256_mul_epu32(c2, m1);
    c0 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(p1, 32), c1), key0[round]);
    c2 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(p0, 32), c3), key1[round]);
    c1 = p1;
    c3 = p0;
  }

  // The block's two 64-bit words for the four samples: out[0…3] word 0, out[4…7] word 1.
  [[gnu::target("avx2"), gnu::always_inline]] static inline void Words(__m256i c0, __m256i c1, __m256i c2, __m256i c3,
                                                                      uint64_t* out) {
    const __m256i low = _mm256_set1_epi64x(0xffffffff);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_or_si256(_mm256_slli_epi64(c0, 32), _mm256_and_si256(c1, low)));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + kLanes),
                        _mm256_or_si256(_mm256_slli_epi64(c2, 32), _mm256_and_si256(c3, low)));
  }
};

// A group's Philox blocks first (two at a time: the ten rounds of one block are a dependency
// chain, and two chains keep the multipliers busy), then the draws from the words.
[[gnu::target("avx2")]] void FillGroupsAvx2(size_t size, const std::vector<uint32_t>& blocks,
                                            const std::vector<Draw>& draws, const std::vector<Constant>& constants,
                                            const CounterRng& rng, uint64_t first, size_t groups, double* theta) {
  const PhiloxAvx2 philox(rng);
  const size_t group_size = kLanes * size, num_blocks = blocks.size();
  // Not a vector of __m256i: outside AVX code GCC aligns that type to 16 bytes only.
  std::vector<uint64_t> words(2 * kLanes * num_blocks);
  for (size_t g = 0; g < groups; ++g) {
    double* out = theta + g * group_size;
    for (const Constant& c : constants) _mm256_storeu_pd(out + kLanes * c.parameter, _mm256_set1_pd(c.value));
    const uint64_t i0 = first + kLanes * g;
    const __m256i index_low = _mm256_set_epi64x(static_cast<uint32_t>(i0 + 3), static_cast<uint32_t>(i0 + 2),
                                                static_cast<uint32_t>(i0 + 1), static_cast<uint32_t>(i0));
    const __m256i index_high = _mm256_set_epi64x((i0 + 3) >> 32, (i0 + 2) >> 32, (i0 + 1) >> 32, i0 >> 32);
    size_t b = 0;
    for (; b + 2 <= num_blocks; b += 2) {
      __m256i a0 = index_low, a1 = index_high, a2 = _mm256_set1_epi64x(blocks[b]), a3 = philox.stream;
      __m256i b0 = index_low, b1 = index_high, b2 = _mm256_set1_epi64x(blocks[b + 1]), b3 = philox.stream;
      for (int round = 0; round < 10; ++round) {
        philox.Round(round, a0, a1, a2, a3);
        philox.Round(round, b0, b1, b2, b3);
      }
      PhiloxAvx2::Words(a0, a1, a2, a3, &words[2 * kLanes * b]);
      PhiloxAvx2::Words(b0, b1, b2, b3, &words[2 * kLanes * (b + 1)]);
    }
    if (b < num_blocks) {
      __m256i a0 = index_low, a1 = index_high, a2 = _mm256_set1_epi64x(blocks[b]), a3 = philox.stream;
      for (int round = 0; round < 10; ++round) philox.Round(round, a0, a1, a2, a3);
      PhiloxAvx2::Words(a0, a1, a2, a3, &words[2 * kLanes * b]);
    }
    for (const Draw& d : draws) {
      const uint64_t* w = &words[kLanes * d.word];
      const __m256d v = d.normal ? ZigguratAvx2(w, rng, i0, d.parameter)
                                 : OpenUnitAvx2(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(w)));
      _mm256_storeu_pd(out + kLanes * d.parameter, _mm256_add_pd(_mm256_set1_pd(d.a), _mm256_mul_pd(_mm256_set1_pd(d.b), v)));
    }
  }
}

}  // namespace

double ZigguratNormal(uint64_t word, const CounterRng& rng, uint64_t index, uint32_t parameter) {
  return ZigguratFast(word, rng, index, parameter);
}

ThetaSampler::ThetaSampler(const ChainModel& model, uint64_t seed)
    : num_parameters_(model.parameters.size()), rng_(seed, 1) {
  for (size_t j = 0; j < model.parameters.size(); ++j) {
    const Distribution& d = model.parameters[j].distribution;
    if (d.IsConstant()) {
      constants_.push_back({static_cast<uint32_t>(j), d.Mean()});
      continue;
    }
    const uint32_t lane = static_cast<uint32_t>(j / 2);
    if (blocks_.empty() || blocks_.back() != lane) blocks_.push_back(lane);
    Draw draw{static_cast<uint32_t>(j), static_cast<uint32_t>(2 * (blocks_.size() - 1) + j % 2), false, 0, 0};
    if (const auto* n = std::get_if<Distribution::Normal>(&d.form())) {
      draw.normal = true, draw.a = n->mean, draw.b = n->sigma;
    } else if (const auto* u = std::get_if<Distribution::Uniform>(&d.form())) {
      draw.a = u->lo, draw.b = u->hi - u->lo;
    }
    draws_.push_back(draw);
  }
}

void ThetaSampler::FillLanes(uint64_t first, size_t groups, double* theta) const {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  (avx2 ? FillGroupsAvx2 : FillGroupsScalar)(num_parameters_, blocks_, draws_, constants_, rng_, first, groups,
                                                        theta);
}

void ThetaSampler::Fill(uint64_t first, size_t count, double* theta) const {
  for (size_t s = 0; s < count; ++s) {
    double* row = theta + s * num_parameters_;
    for (const Constant& c : constants_) row[c.parameter] = c.value;
    DrawSample(blocks_, draws_, rng_, first + s, row, 1);
  }
}

}  // namespace vstcal::errsim
