// SimdDouble: four doubles that behave as one scalar, so that code templated on the scalar (the
// err-sim chain, written for double and ceres::Jet) evaluates four samples at once, one sample
// per lane. Arithmetic is lane by lane with IEEE double semantics — +, −, ×, ÷ and √ are
// correctly rounded, with no fused multiply-add (the project builds with -ffp-contract=off) — so
// every lane holds exactly the bits the double instantiation gives for that lane's inputs.
//
// Branches. A comparison gives a SimdMask. Where templated code branches on one (`if (x < y)`),
// the mask converts to bool: true when every lane is true, false when none is. When the lanes
// disagree the lanes would need different paths; the conversion then returns false and records a
// divergence for the calling thread (SimdDivergence), and the caller must discard the results and
// evaluate those inputs lane by lane with double. So a result that is kept was computed along
// the path the double code takes for every lane, whatever the branch structure of the template.
// Branches that routinely split the lanes are written with Select (computing both sides) instead.
//
// Storage: GCC vector extensions, 32 bytes. In a function compiled for AVX2 (target attribute or
// target_clones) each operation is one 256-bit instruction, elsewhere two SSE2 ones; the values
// are the same either way. libm functions (sin, atan2, …; the chain's rare paths) run per lane.
#pragma once

#include <emmintrin.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include <Eigen/Core>

namespace vstcal {

// Divergences recorded by SimdMask's bool conversion on this thread (see the header comment).
class SimdDivergence {
 public:
  static void Clear() { flag_ = false; }
  static bool Occurred() { return flag_; }
  static void Record() { flag_ = true; }

 private:
  static inline thread_local bool flag_ = false;
};

class SimdMask {
 public:
  // Alignment stated: without it GCC aligns 32-byte vectors to 16 outside AVX code and to 32 inside.
  using Bits = int64_t __attribute__((vector_size(32), aligned(32)));  // −1 (all ones) or 0 per lane
  Bits bits;

  static SimdMask FromBits(const Bits& b) { return SimdMask{b}; }
  // The sign bits of two lanes (movmskpd: one instruction, where extracting lanes takes several).
  static int SignBits(int64_t __attribute__((vector_size(16))) pair) {
    return _mm_movemask_pd(reinterpret_cast<__m128d>(pair));
  }
  bool lane(int i) const { return bits[i] != 0; }
  bool all() const {
    return SignBits(__builtin_shufflevector(bits, bits, 0, 1) & __builtin_shufflevector(bits, bits, 2, 3)) == 3;
  }
  bool any() const {
    return SignBits(__builtin_shufflevector(bits, bits, 0, 1) | __builtin_shufflevector(bits, bits, 2, 3)) != 0;
  }

  // A branch on the mask: see the header comment.
  explicit operator bool() const {
    if (all()) return true;
    if (any()) SimdDivergence::Record();
    return false;
  }
};

inline SimdMask operator!(const SimdMask& a) { return SimdMask::FromBits(~a.bits); }
inline SimdMask operator&&(const SimdMask& a, const SimdMask& b) { return SimdMask::FromBits(a.bits & b.bits); }
inline SimdMask operator||(const SimdMask& a, const SimdMask& b) { return SimdMask::FromBits(a.bits | b.bits); }
inline SimdMask operator!=(const SimdMask& a, const SimdMask& b) { return SimdMask::FromBits(a.bits ^ b.bits); }

struct SimdDouble {
  static constexpr int kLanes = 4;
  using Lanes = double __attribute__((vector_size(32), aligned(32)));  // aligned: see SimdMask::Bits
  Lanes v;

  SimdDouble() = default;
  explicit SimdDouble(double x) : v{x, x, x, x} {}
  static SimdDouble FromLanes(const Lanes& lanes) {
    SimdDouble out;
    out.v = lanes;
    return out;
  }
  // Four consecutive doubles (no alignment needed).
  static SimdDouble Load(const double* p) {
    Lanes lanes;
    std::memcpy(&lanes, p, sizeof lanes);
    return FromLanes(lanes);
  }
  void Store(double* p) const { std::memcpy(p, &v, sizeof v); }
  double lane(int i) const { return v[i]; }
  void set_lane(int i, double x) { v[i] = x; }

  SimdDouble& operator+=(const SimdDouble& o) { return v += o.v, *this; }
  SimdDouble& operator-=(const SimdDouble& o) { return v -= o.v, *this; }
  SimdDouble& operator*=(const SimdDouble& o) { return v *= o.v, *this; }
  SimdDouble& operator/=(const SimdDouble& o) { return v /= o.v, *this; }
};

inline SimdDouble operator+(const SimdDouble& a) { return a; }
inline SimdDouble operator-(const SimdDouble& a) { return SimdDouble::FromLanes(-a.v); }
inline SimdDouble operator+(const SimdDouble& a, const SimdDouble& b) { return SimdDouble::FromLanes(a.v + b.v); }
inline SimdDouble operator-(const SimdDouble& a, const SimdDouble& b) { return SimdDouble::FromLanes(a.v - b.v); }
inline SimdDouble operator*(const SimdDouble& a, const SimdDouble& b) { return SimdDouble::FromLanes(a.v * b.v); }
inline SimdDouble operator/(const SimdDouble& a, const SimdDouble& b) { return SimdDouble::FromLanes(a.v / b.v); }
inline SimdDouble operator+(double a, const SimdDouble& b) { return SimdDouble::FromLanes(a + b.v); }
inline SimdDouble operator-(double a, const SimdDouble& b) { return SimdDouble::FromLanes(a - b.v); }
inline SimdDouble operator*(double a, const SimdDouble& b) { return SimdDouble::FromLanes(a * b.v); }
inline SimdDouble operator/(double a, const SimdDouble& b) { return SimdDouble::FromLanes(a / b.v); }
inline SimdDouble operator+(const SimdDouble& a, double b) { return SimdDouble::FromLanes(a.v + b); }
inline SimdDouble operator-(const SimdDouble& a, double b) { return SimdDouble::FromLanes(a.v - b); }
inline SimdDouble operator*(const SimdDouble& a, double b) { return SimdDouble::FromLanes(a.v * b); }
inline SimdDouble operator/(const SimdDouble& a, double b) { return SimdDouble::FromLanes(a.v / b); }

inline SimdMask operator<(const SimdDouble& a, const SimdDouble& b) { return SimdMask::FromBits(a.v < b.v); }
inline SimdMask operator>(const SimdDouble& a, const SimdDouble& b) { return SimdMask::FromBits(a.v > b.v); }
inline SimdMask operator<=(const SimdDouble& a, const SimdDouble& b) { return SimdMask::FromBits(a.v <= b.v); }
inline SimdMask operator>=(const SimdDouble& a, const SimdDouble& b) { return SimdMask::FromBits(a.v >= b.v); }
inline SimdMask operator==(const SimdDouble& a, const SimdDouble& b) { return SimdMask::FromBits(a.v == b.v); }
inline SimdMask operator!=(const SimdDouble& a, const SimdDouble& b) { return SimdMask::FromBits(a.v != b.v); }
inline SimdMask operator<(const SimdDouble& a, double b) { return a < SimdDouble(b); }
inline SimdMask operator>(const SimdDouble& a, double b) { return a > SimdDouble(b); }

// Whether every lane is set, without recording a divergence (for loops that run until all lanes are
// done, with finished lanes kept by Select). For bool, the value itself.
inline bool AllLanes(const SimdMask& m) { return m.all(); }
inline bool AllLanes(bool b) { return b; }

// Lane by lane: a where the mask is set, b elsewhere. For bool, the plain choice, so that
// templated code can use it for every scalar type.
inline SimdDouble Select(const SimdMask& m, const SimdDouble& a, const SimdDouble& b) {
  return SimdDouble::FromLanes(m.bits ? a.v : b.v);
}
template <typename T>
T Select(bool m, const T& a, const T& b) {
  return m ? a : b;
}

inline SimdDouble sqrt(const SimdDouble& a) {
  // SSE2 on each half (correctly rounded like std::sqrt, with no errno path to keep it scalar);
  // split and joined in registers: through memory, the 32-byte reload of two 16-byte stores stalls.
  using Half = double __attribute__((vector_size(16)));
  const Half lo = __builtin_shufflevector(a.v, a.v, 0, 1), hi = __builtin_shufflevector(a.v, a.v, 2, 3);
  const Half root_lo = _mm_sqrt_pd(lo), root_hi = _mm_sqrt_pd(hi);
  return SimdDouble::FromLanes(__builtin_shufflevector(root_lo, root_hi, 0, 1, 2, 3));
}

inline SimdDouble abs(const SimdDouble& a) {
  return SimdDouble::FromLanes(reinterpret_cast<SimdDouble::Lanes>(reinterpret_cast<SimdMask::Bits>(a.v) & INT64_MAX));
}

// libm per lane: the rare paths (large rotations, wide angles).
#define VSTCAL_SIMD_PER_LANE_1(name)                                       \
  inline SimdDouble name(const SimdDouble& a) {                                  \
    return SimdDouble::FromLanes(SimdDouble::Lanes{                       \
        std::name(a.v[0]), std::name(a.v[1]), std::name(a.v[2]), std::name(a.v[3])}); \
  }
VSTCAL_SIMD_PER_LANE_1(sin)
VSTCAL_SIMD_PER_LANE_1(cos)
VSTCAL_SIMD_PER_LANE_1(exp)
VSTCAL_SIMD_PER_LANE_1(log)
#undef VSTCAL_SIMD_PER_LANE_1

inline SimdDouble atan2(const SimdDouble& y, const SimdDouble& x) {
  return SimdDouble::FromLanes(SimdDouble::Lanes{std::atan2(y.v[0], x.v[0]), std::atan2(y.v[1], x.v[1]),
                                                 std::atan2(y.v[2], x.v[2]), std::atan2(y.v[3], x.v[3])});
}

}  // namespace vstcal

namespace Eigen {

template <>
struct NumTraits<vstcal::SimdDouble> {
  using Real = vstcal::SimdDouble;
  using NonInteger = vstcal::SimdDouble;
  using Nested = vstcal::SimdDouble;
  using Literal = vstcal::SimdDouble;
  static Real dummy_precision() { return Real(NumTraits<double>::dummy_precision()); }
  static Real epsilon() { return Real(std::numeric_limits<double>::epsilon()); }
  static int digits10() { return NumTraits<double>::digits10(); }
  static Real highest() { return Real(std::numeric_limits<double>::max()); }
  static Real lowest() { return Real(-std::numeric_limits<double>::max()); }
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    ReadCost = 1,
    AddCost = 1,
    MulCost = 1,
    HasFloatingPoint = 1,
    RequireInitialization = 0
  };
};

namespace internal {

// Eigen aligns a fixed-size matrix's array to 16 bytes under SSE; SimdDouble already asks for 32,
// and clang rejects an alignas weaker than the type's own (GCC ignores it). 0: no alignas, the
// array keeps SimdDouble's 32 — the layout GCC gave it before. (No packet maths is defined for
// SimdDouble, so Eigen's alignment flag chooses no code path here.)
template <int Size>
struct compute_default_alignment<vstcal::SimdDouble, Size> {
  enum { value = 0 };
};
template <>
struct compute_default_alignment<vstcal::SimdDouble, Dynamic> {
  enum { value = 0 };
};

}  // namespace internal
}  // namespace Eigen
