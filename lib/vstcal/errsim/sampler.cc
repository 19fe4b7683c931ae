#include "vstcal/errsim/sampler.h"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

namespace vstcal {
namespace {

#include "vstcal/errsim/ziggurat_table.inc"

// A word's low kZigLayerBits bits pick the layer, the next bit the sign; the top 53 bits (bits 11
// to 63, which OpenUnit takes) the position.
constexpr uint64_t kLayerBits = (uint64_t{1} << kZigLayerBits) - 1, kSignBit = uint64_t{1} << kZigLayerBits;
constexpr int kSignToTop = 63 - kZigLayerBits;  // the sign bit's shift to a double's sign
static_assert(kZigLayerBits + 1 <= 11, "the layer and the sign must stay below OpenUnit's 53 bits");
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
    const int layer = static_cast<int>(word & kLayerBits);
    const double sign = (word & kSignBit) ? -1.0 : 1.0;
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

// Bits 0–9 pick the layer, bit 10 the sign, the top 53 the position: inside the layer's rectangle
// (99.6 % of draws) the deviate is sign · u · x[layer].
inline double ZigguratFast(uint64_t word, const CounterRng& rng, uint64_t index, uint32_t parameter) {
  const int layer = static_cast<int>(word & kLayerBits);
  const double x = OpenUnit(word) * kZigX[layer];
  // The sign by flipping the sign bit, not by a branch: the sign bit is a coin toss no predictor can learn.
  if (x < kZigX[layer + 1]) return std::bit_cast<double>(std::bit_cast<uint64_t>(x) ^ ((word & kSignBit) << kSignToTop));
  return ZigguratSlow(word, rng, index, parameter);
}

// The value of one draw from its word (sample `index`).
inline double DrawValue(const ThetaSampler::Draw& d, uint64_t word, const CounterRng& rng, uint64_t index) {
  return d.normal ? d.a + d.b * ZigguratFast(word, rng, index, d.parameter) : d.a + d.b * OpenUnit(word);
}

using Draw = ThetaSampler::Draw;
using Constant = ThetaSampler::Constant;
constexpr size_t kLanes = ThetaSampler::kLanes;

// One sample's draws one at a time, put(j, value) for parameter j: the reference that the AVX2
// kernel reproduces bit for bit.
template <typename Put>
void DrawSample(const std::vector<uint32_t>& blocks, const std::vector<Draw>& draws, const CounterRng& rng,
                uint64_t index, Put&& put) {
  PhiloxCounter bits{};
  uint32_t block = UINT32_MAX;
  for (const Draw& d : draws) {
    if (d.word / 2 != block) bits = rng.Bits(index, blocks[block = d.word / 2]);
    put(d.parameter, DrawValue(d, Word(bits, d.word % 2), rng, index));
  }
}

void FillGroupsScalar(size_t size, const std::vector<uint32_t>& blocks, const std::vector<Draw>& draws,
                      const std::vector<Constant>& constants, const CounterRng& rng, uint64_t first, size_t groups,
                      SimdDouble* theta) {
  for (size_t g = 0; g < groups; ++g) {
    SimdDouble* out = theta + g * size;
    for (const Constant& c : constants) out[c.parameter] = SimdDouble(c.value);
    for (size_t l = 0; l < kLanes; ++l) {
      DrawSample(blocks, draws, rng, first + kLanes * g + l,
                 [&](uint32_t j, double value) { out[j].set_lane(static_cast<int>(l), value); });
    }
  }
}

// OpenUnit on four words: the top 53 bits k converted exactly in two parts (no 64-bit integer to
// double conversion before AVX-512), k = (2⁸⁴ + hi·2³²) − 2⁸⁴ + (2⁵² + lo) − 2⁵², then the same
// (k + ½)·2⁻⁵³ as the scalar path.
[[gnu::target("avx2")]] inline __m256d OpenUnitAvx2(__m256i word) {
  const __m256i k = _mm256_srli_epi64(word, 11);
  const __m256i hi = _mm256_or_si256(_mm256_srli_epi64(k, 32), _mm256_set1_epi64x(0x4530000000000000));
  const __m256i lo =
      _mm256_or_si256(_mm256_and_si256(k, _mm256_set1_epi64x(0xffffffff)), _mm256_set1_epi64x(0x4330000000000000));
  const __m256d exact = _mm256_add_pd(_mm256_sub_pd(_mm256_castsi256_pd(hi), _mm256_set1_pd(0x1.0p84)),
                                      _mm256_sub_pd(_mm256_castsi256_pd(lo), _mm256_set1_pd(0x1.0p52)));
  return _mm256_mul_pd(_mm256_add_pd(exact, _mm256_set1_pd(0.5)), _mm256_set1_pd(0x1.0p-53));
}

// ZigguratFast's rectangle test on the four words at `words`: z for the lanes inside their
// rectangle, and which lanes those are (bit l for lane l); the others need ZigguratSlow.
[[gnu::target("avx2")]] inline __m256d ZigguratRectangleAvx2(const uint64_t* words, int* inside) {
  const __m256i word = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(words));
  // Each lane's layer edges (x[layer], x[layer + 1]) are adjacent in the table: one 16-byte load
  // per lane and a transpose, where two gathers cost more than everything else here on Zen 3.
  const __m256d pairs02 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&kZigX[words[0] & kLayerBits])),
                                               _mm_loadu_pd(&kZigX[words[2] & kLayerBits]), 1);
  const __m256d pairs13 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&kZigX[words[1] & kLayerBits])),
                                               _mm_loadu_pd(&kZigX[words[3] & kLayerBits]), 1);
  const __m256d x = _mm256_mul_pd(OpenUnitAvx2(word), _mm256_unpacklo_pd(pairs02, pairs13));
  const __m256d edge = _mm256_unpackhi_pd(pairs02, pairs13);
  const __m256i sign = _mm256_slli_epi64(_mm256_and_si256(word, _mm256_set1_epi64x(kSignBit)), kSignToTop);
  *inside = _mm256_movemask_pd(_mm256_cmp_pd(x, edge, _CMP_LT_OQ));
  return _mm256_xor_pd(x, _mm256_castsi256_pd(sign));
}

// Philox-4×32-10 on the four samples of a group at once: each 32-bit word sits in the low half of
// a 64-bit element, so _mm256_mul_epu32 gives the four 32×32→64 products of a round in one
// instruction. Integer arithmetic: the same bits as CounterRng::Bits.
//
// Rounds 0 and 1 mostly repeat: a block's counter is (index low, index high, lane, stream), and
// within a group only the index's low word varies, so each word after those two rounds is a part
// that depends on the group (one vector per group) xor a part that depends on the lane and the
// index's high word (scalars per block, recomputed when the high word changes). The blocks then
// start at round 2: 8 rounds each instead of 10 (6 % of the draws' time).
// GCC 12.2 (bookworm) warns that the AVX-512 intrinsics' own placeholder (`__m512i __Y = __Y;`,
// _mm512_undefined_epi32 in avx512fintrin.h) may be used uninitialized: GCC bug 105593, fixed in
// 12.3. The placeholder is a pass-through the full mask never reads; silenced for this class only.
#pragma GCC diagnostic push
#if !defined(__clang__)  // clang has no such warning, and warns of the unknown name
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
class PhiloxAvx2 {
 public:
  static constexpr uint32_t kM0 = 0xD2511F53u, kM1 = 0xCD9E8D57u;

  // Scalars only: GCC aligns __m256i members to 16 bytes outside AVX code and to 32 inside.
  PhiloxAvx2(const CounterRng& rng, const std::vector<uint32_t>& blocks)
      : stream_(rng.stream()), blocks_(blocks), lane_parts_(blocks.size()) {
    PhiloxKey key = rng.key();
    for (int round = 0; round < 10; ++round) {
      if (round > 0) key[0] += 0x9E3779B9u, key[1] += 0xBB67AE85u;
      key0_[round] = key[0], key1_[round] = key[1];
    }
  }

  // The blocks of samples i0 … i0 + 3: block b's word 0 of the four samples to out[8b…8b + 3],
  // word 1 to out[8b + 4…8b + 7].
  [[gnu::target("avx2")]] void Group(uint64_t i0, uint64_t* out) {
    const __m256i index_low = _mm256_set_epi64x(static_cast<uint32_t>(i0 + 3), static_cast<uint32_t>(i0 + 2),
                                                static_cast<uint32_t>(i0 + 1), static_cast<uint32_t>(i0));
    const size_t n = blocks_.size();
    size_t b = 0;
    if (i0 >> 32 != (i0 + kLanes - 1) >> 32) {  // the high word differs between the samples
      const __m256i index_high = _mm256_set_epi64x((i0 + 3) >> 32, (i0 + 2) >> 32, (i0 + 1) >> 32, i0 >> 32);
      const __m256i counter[2] = {index_low, index_high};
      for (; b < n; ++b) Blocks<1>(counter, nullptr, &blocks_[b], 0, out + 2 * kLanes * b);
      return;
    }
    SetIndexHigh(static_cast<uint32_t>(i0 >> 32));
    // Rounds 0 and 1, group part: p0 = M0·(index low), q = M1·(hi p0 ^ stream ^ k1₀).
    const __m256i p0 = _mm256_mul_epu32(index_low, _mm256_set1_epi64x(kM0));
    const __m256i q = _mm256_mul_epu32(
        _mm256_xor_si256(_mm256_srli_epi64(p0, 32), _mm256_set1_epi64x(stream_ ^ key1_[0])), _mm256_set1_epi64x(kM1));
    const __m256i group[3] = {_mm256_xor_si256(_mm256_srli_epi64(q, 32), _mm256_set1_epi64x(key0_[1])), q,
                              _mm256_xor_si256(p0, _mm256_set1_epi64x(key1_[1]))};
    for (; b + 3 <= n; b += 3) Blocks<3>(group, &lane_parts_[b], nullptr, 2, out + 2 * kLanes * b);
    for (; b < n; ++b) Blocks<1>(group, &lane_parts_[b], nullptr, 2, out + 2 * kLanes * b);
  }

  // Group with AVX-512 where the CPU has it: two blocks in one register (4 samples × 2 blocks), so
  // each instruction does twice the work. The same integer arithmetic: the same words.
  [[gnu::target("avx512f")]] void Group512(uint64_t i0, uint64_t* out) {
    if (i0 >> 32 != (i0 + kLanes - 1) >> 32) return Group(i0, out);  // rare: the AVX2 path's first case
    SetIndexHigh(static_cast<uint32_t>(i0 >> 32));
    const __m256i index_low = _mm256_set_epi64x(static_cast<uint32_t>(i0 + 3), static_cast<uint32_t>(i0 + 2),
                                                static_cast<uint32_t>(i0 + 1), static_cast<uint32_t>(i0));
    const __m256i p0 = _mm256_mul_epu32(index_low, _mm256_set1_epi64x(kM0));
    const __m256i q = _mm256_mul_epu32(
        _mm256_xor_si256(_mm256_srli_epi64(p0, 32), _mm256_set1_epi64x(stream_ ^ key1_[0])), _mm256_set1_epi64x(kM1));
    const __m512i group[3] = {
        _mm512_broadcast_i64x4(_mm256_xor_si256(_mm256_srli_epi64(q, 32), _mm256_set1_epi64x(key0_[1]))),
        _mm512_broadcast_i64x4(q), _mm512_broadcast_i64x4(_mm256_xor_si256(p0, _mm256_set1_epi64x(key1_[1])))};
    const size_t n = blocks_.size();
    size_t b = 0;
    for (; b + 6 <= n; b += 6) Pairs512<3>(group, b, n, out);
    for (; b < n; b += 2) Pairs512<1>(group, b, n, out);
  }

 private:
  // Four copies of `low` in the register's lower half, four of `high` in the upper.
  [[gnu::target("avx512f"), gnu::always_inline]] static inline __m512i Pair512(uint64_t low, uint64_t high) {
    return _mm512_inserti64x4(_mm512_set1_epi64(static_cast<int64_t>(low)), _mm256_set1_epi64x(static_cast<int64_t>(high)), 1);
  }

  // K pairs of blocks (b, b + 1), (b + 2, b + 3), … from round 2, as Blocks does one block; a pair
  // past the last block repeats the last one and stores nothing for it.
  template <int K>
  [[gnu::target("avx512f"), gnu::always_inline]] inline void Pairs512(const __m512i* group, size_t b, size_t n,
                                                                     uint64_t* out) const {
    __m512i c0[K], c1[K], c2[K], c3[K];
#pragma GCC unroll 4
    for (int k = 0; k < K; ++k) {
      const LanePart& first = lane_parts_[b + 2 * k];
      const LanePart& second = lane_parts_[std::min(b + 2 * k + 1, n - 1)];
      c0[k] = _mm512_xor_si512(group[0], Pair512(first.w0, second.w0));
      c1[k] = group[1];
      c2[k] = _mm512_xor_si512(group[2], Pair512(first.w2, second.w2));
      c3[k] = Pair512(first.w3, second.w3);
    }
    for (int round = 2; round < 10; ++round) {
#pragma GCC unroll 4
      for (int k = 0; k < K; ++k) {
        const __m512i p0 = _mm512_mul_epu32(c0[k], _mm512_set1_epi64(kM0));
        const __m512i p1 = _mm512_mul_epu32(c2[k], _mm512_set1_epi64(kM1));
        c0[k] = _mm512_xor_si512(_mm512_xor_si512(_mm512_srli_epi64(p1, 32), c1[k]),
                                 _mm512_set1_epi64(static_cast<int64_t>(key0_[round])));
        c2[k] = _mm512_xor_si512(_mm512_xor_si512(_mm512_srli_epi64(p0, 32), c3[k]),
                                 _mm512_set1_epi64(static_cast<int64_t>(key1_[round])));
        c1[k] = p1;
        c3[k] = p0;
      }
    }
    const __m512i low = _mm512_set1_epi64(0xffffffff);
#pragma GCC unroll 4
    for (int k = 0; k < K; ++k) {
      const __m512i word0 = _mm512_or_si512(_mm512_slli_epi64(c0[k], 32), _mm512_and_si512(c1[k], low));
      const __m512i word1 = _mm512_or_si512(_mm512_slli_epi64(c2[k], 32), _mm512_and_si512(c3[k], low));
      uint64_t* first = out + 2 * kLanes * (b + 2 * k);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(first), _mm512_castsi512_si256(word0));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(first + kLanes), _mm512_castsi512_si256(word1));
      if (b + 2 * k + 1 < n) {
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(first + 2 * kLanes), _mm512_extracti64x4_epi64(word0, 1));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(first + 3 * kLanes), _mm512_extracti64x4_epi64(word1, 1));
      }
    }
  }

  // Rounds 0 and 1, block part: with p1 = M1·lane and e = M0·(hi p1 ^ index high ^ k0₀), after
  // round 1 the block holds (g0 ^ lo p1, g1, g2 ^ hi e, lo e), g the group part.
  struct LanePart {
    uint64_t w0, w2, w3;
  };

  void SetIndexHigh(uint32_t high) {
    if (high == index_high_ && lane_parts_valid_) return;
    for (size_t b = 0; b < blocks_.size(); ++b) {
      const uint64_t p1 = uint64_t{kM1} * blocks_[b];
      const uint64_t e = uint64_t{kM0} * (static_cast<uint32_t>(p1 >> 32) ^ high ^ key0_[0]);
      lane_parts_[b] = {static_cast<uint32_t>(p1), e >> 32, static_cast<uint32_t>(e)};
    }
    index_high_ = high;
    lane_parts_valid_ = true;
  }

  // c1 and c3 keep the high halves of the products: _mm256_mul_epu32 ignores the high half of its
  // inputs, and Blocks masks them once at the end.
  [[gnu::target("avx2"), gnu::always_inline]] inline void Round(int round, __m256i& c0, __m256i& c1, __m256i& c2,
                                                               __m256i& c3) const {
    const __m256i p0 = _mm256_mul_epu32(c0, _mm256_set1_epi64x(kM0));
    const __m256i p1 = _mm256_mul_epu32(c2, _mm256_set1_epi64x(kM1));
    c0 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(p1, 32), c1), _mm256_set1_epi64x(key0_[round]));
    c2 = _mm256_xor_si256(_mm256_xor_si256(_mm256_srli_epi64(p0, 32), c3), _mm256_set1_epi64x(key1_[round]));
    c1 = p1;
    c3 = p0;
  }

  // K blocks interleaved from round `first_round`: the rounds of one block are a chain of
  // dependent multiplications, and three chains keep the multiplier busy (two leave it idle, four
  // run out of registers). From round 0, `start` is the counter's index (low, high) and `lanes`
  // the blocks' lanes; from round 2, `start` is the group part and `parts` the blocks' parts.
  template <int K>
  [[gnu::target("avx2"), gnu::always_inline]] inline void Blocks(const __m256i* start, const LanePart* parts,
                                                                const uint32_t* lanes, int first_round,
                                                                uint64_t* out) const {
    __m256i c0[K], c1[K], c2[K], c3[K];
#pragma GCC unroll 4
    for (int k = 0; k < K; ++k) {
      if (first_round == 0) {
        c0[k] = start[0], c1[k] = start[1], c2[k] = _mm256_set1_epi64x(lanes[k]), c3[k] = _mm256_set1_epi64x(stream_);
      } else {
        c0[k] = _mm256_xor_si256(start[0], _mm256_set1_epi64x(parts[k].w0));
        c1[k] = start[1];
        c2[k] = _mm256_xor_si256(start[2], _mm256_set1_epi64x(parts[k].w2));
        c3[k] = _mm256_set1_epi64x(parts[k].w3);
      }
    }
    for (int round = first_round; round < 10; ++round) {
#pragma GCC unroll 4
      for (int k = 0; k < K; ++k) Round(round, c0[k], c1[k], c2[k], c3[k]);
    }
    const __m256i low = _mm256_set1_epi64x(0xffffffff);
#pragma GCC unroll 4
    for (int k = 0; k < K; ++k) {
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + 2 * kLanes * k),
                          _mm256_or_si256(_mm256_slli_epi64(c0[k], 32), _mm256_and_si256(c1[k], low)));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + 2 * kLanes * k + kLanes),
                          _mm256_or_si256(_mm256_slli_epi64(c2[k], 32), _mm256_and_si256(c3[k], low)));
    }
  }

  uint64_t stream_;
  std::array<uint64_t, 10> key0_{}, key1_{};  // round keys
  const std::vector<uint32_t>& blocks_;
  std::vector<LanePart> lane_parts_;
  uint32_t index_high_ = 0;
  bool lane_parts_valid_ = false;
};
#pragma GCC diagnostic pop

// A group's Philox blocks first, then the draws from the words.
[[gnu::target("avx2")]] void FillGroupsAvx2(size_t size, const std::vector<uint32_t>& blocks,
                                            const std::vector<Draw>& draws, const std::vector<Constant>& constants,
                                            const CounterRng& rng, uint64_t first, size_t groups, SimdDouble* theta) {
  static const bool avx512 = __builtin_cpu_supports("avx512f");
  PhiloxAvx2 philox(rng, blocks);
  const size_t num_blocks = blocks.size();
  // Not a vector of __m256i: outside AVX code GCC aligns that type to 16 bytes only.
  std::vector<uint64_t> words(2 * kLanes * num_blocks);
  struct Pending {
    const Draw* draw;
    int inside;  // bit l: lane l was inside its rectangle
  };
  std::vector<Pending> pending(draws.size());
  for (size_t g = 0; g < groups; ++g) {
    SimdDouble* out = theta + g * size;
    for (const Constant& c : constants) out[c.parameter] = SimdDouble(c.value);
    const uint64_t i0 = first + kLanes * g;
    if (avx512) {
      philox.Group512(i0, words.data());
    } else {
      philox.Group(i0, words.data());
    }
    // The rectangles first, recording the draws with a lane outside (without a branch: which
    // vectors those are is a coin toss for the predictor); then the slow lanes, whose chains of
    // Philox rounds and exp calls are independent of each other and overlap.
    size_t num_pending = 0;
    for (const Draw& d : draws) {
      const uint64_t* w = &words[kLanes * d.word];
      int inside = 0xf;
      const __m256d v = d.normal ? ZigguratRectangleAvx2(w, &inside)
                                 : OpenUnitAvx2(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(w)));
      const __m256d value = _mm256_add_pd(_mm256_set1_pd(d.a), _mm256_mul_pd(_mm256_set1_pd(d.b), v));
      out[d.parameter].v = reinterpret_cast<SimdDouble::Lanes>(value);
      pending[num_pending] = {&d, inside};
      num_pending += inside != 0xf;
    }
    for (size_t p = 0; p < num_pending; ++p) {
      const Draw& d = *pending[p].draw;
      // The lanes outside by their bits: a test of each lane would mispredict about once a draw.
      for (unsigned outside = ~pending[p].inside & 0xfu; outside != 0; outside &= outside - 1) {
        const int l = std::countr_zero(outside);
        out[d.parameter].set_lane(l, d.a + d.b * ZigguratSlow(words[kLanes * d.word + l], rng, i0 + l, d.parameter));
      }
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

void ThetaSampler::FillLanes(uint64_t first, size_t groups, SimdDouble* theta) const {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  (avx2 ? FillGroupsAvx2 : FillGroupsScalar)(num_parameters_, blocks_, draws_, constants_, rng_, first, groups,
                                                        theta);
}

void ThetaSampler::Fill(uint64_t first, size_t count, double* theta) const {
  for (size_t s = 0; s < count; ++s) {
    double* row = theta + s * num_parameters_;
    for (const Constant& c : constants_) row[c.parameter] = c.value;
    DrawSample(blocks_, draws_, rng_, first + s, [row](uint32_t j, double value) { row[j] = value; });
  }
}

}  // namespace vstcal
