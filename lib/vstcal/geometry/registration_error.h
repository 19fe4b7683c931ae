// Registration-error measures, defined once (docs/math/registration-error.md) and shared by every
// tool that reports a 3-D registration error: err-sim's misregistration and misperception, and the
// reports' measured overlay errors.
//
// Holloway (1997, "Registration error analysis for augmented reality", Presence 6(4); seed 001
// Fig. 2) splits a 3-D offset Δ = P' − P of a seen point P' from where it should be, P, as looked
// at from a viewpoint C (the cyclopean eye, midway between the eyes), with the line of sight
// ℓ = (P − C)/|P − C|:
//
//   linear  = |Δ|                          length unit
//   depth   = Δ·ℓ                          signed, > 0 farther from the viewer
//   lateral = |Δ − (Δ·ℓ) ℓ| = |Δ × ℓ|      across the line of sight
//   angular = ∠(P − C, P' − C)             radians, the visual angle between the two
//
// A stereo viewer sees a point where the rays of its two eyes pass closest: TriangulateMidpoint.
//
// Templated on the scalar (double, ceres::Jet, SimdDouble — four samples at once); products and
// sums run in a fixed order (geometry/fixed_order.h) so every scalar type gives the bits of double.
#pragma once

#include <cmath>

#include "vstcal/core/simd_double.h"
#include "vstcal/geometry/fixed_order.h"

namespace vstcal {

// The angle θ ∈ [0, π] with sin θ ∝ s ≥ 0 and cos θ ∝ c, i.e. atan2(s, c) for s = |a × b|,
// c = a·b: accurate for tiny angles, unlike acos. Below 0.1 rad a series replaces atan2, exact to
// rounding, 5× cheaper, and one polynomial for the whole range so that four samples evaluated
// together never need different paths.
template <typename T>
T AngleFromSinCos(const T& s, const T& c) {
  using std::atan2;
  if (c > T(0) && s < T(0.1) * c) {
    // atan x = x (1 − x²/3 + x⁴/5 − …) through x¹⁵: the first omitted term x¹⁷/17 is below
    // 6e-18·x for x < 0.1, under rounding. Estrin's scheme shortens the dependency chain.
    const T x = s / c, x2 = x * x, x4 = x2 * x2;
    constexpr double k3 = 1.0 / 3, k5 = 1.0 / 5, k7 = 1.0 / 7, k9 = 1.0 / 9, k11 = 1.0 / 11, k13 = 1.0 / 13,
                     k15 = 1.0 / 15;
    const T low = (T(1) - k3 * x2) + x4 * (T(k5) - k7 * x2);
    const T high = (T(k9) - k11 * x2) + x4 * (T(k13) - k15 * x2);
    return x * (low + (x4 * x4) * high);
  }
  return atan2(s, c);
}

// Angle between two non-zero vectors, radians.
template <typename T>
T AngleBetweenVectors(const Vec3<T>& a, const Vec3<T>& b) {
  return AngleFromSinCos(fixed_order::Norm(fixed_order::Cross(a, b)), fixed_order::Dot(a, b));
}

template <typename T>
struct RegistrationErrorOf {
  T linear, lateral, depth, angular;  // length unit (depth signed), radians
};

// Holloway's terms of the offset Δ of a point that should be seen at `reference`, looked at from
// `viewpoint` (the header's formulas). The reference must differ from the viewpoint.
template <typename T>
RegistrationErrorOf<T> RegistrationError(const Vec3<T>& viewpoint, const Vec3<T>& reference, const Vec3<T>& offset) {
  using std::sqrt;
  namespace fo = fixed_order;
  const Vec3<T> sight = reference - viewpoint;  // not normalised: depth = Δ·s/|s|, lateral = |Δ × s|/|s|
  const T distance2 = fo::SquaredNorm(sight);
  const T inverse_distance = T(1) / sqrt(distance2);
  const T along = fo::Dot(offset, sight);
  const T across = fo::Norm(fo::Cross(offset, sight));
  // ∠(s, s + Δ): |s × (s + Δ)| = |Δ × s| and s·(s + Δ) = |s|² + Δ·s, from what is at hand.
  return {fo::Norm(offset), across * inverse_distance, along * inverse_distance, AngleFromSinCos(across, distance2 + along)};
}

// The point a stereo viewer sees: the midpoint of the closest approach of the rays e₀ + s₀ d₀ and
// e₁ + s₁ d₁ (directions need not be unit). With n = d₀ × d₁,
//   s₀ = ((e₁ − e₀) × d₁)·n / |n|²,   s₁ = ((e₁ − e₀) × d₀)·n / |n|²,   P = ½ (e₀ + s₀ d₀ + e₁ + s₁ d₁).
// The textbook (a c − b²)⁻¹ form cancels catastrophically for nearly parallel rays (vergence
// 0.02 rad at 3 m with a 63 mm baseline loses 7 digits); this one does not. Returns false, leaving
// `midpoint` untouched, for rays parallel to 1e-12 (no point is seen).
template <typename T>
bool TriangulateMidpoint(const Vec3<T>& e0, const Vec3<T>& d0, const Vec3<T>& e1, const Vec3<T>& d1, Vec3<T>* midpoint) {
  namespace fo = fixed_order;
  const Vec3<T> n = fo::Cross(d0, d1);
  const T n2 = fo::SquaredNorm(n);
  if (!(n2 > T(1e-24) * fo::SquaredNorm(d0) * fo::SquaredNorm(d1))) return false;
  const T inverse_n2 = T(1) / n2;
  const Vec3<T> between = e1 - e0;
  const T s0 = fo::Dot(fo::Cross(between, d1), n) * inverse_n2;
  const T s1 = fo::Dot(fo::Cross(between, d0), n) * inverse_n2;
  *midpoint = T(0.5) * (e0 + s0 * d0 + e1 + s1 * d1);
  return true;
}

}  // namespace vstcal

namespace vstcal {

// The double instantiations live in registration_error.cc (reports use them; the chain instantiates
// its own scalar types).
extern template RegistrationErrorOf<double> RegistrationError(const Vec3<double>&, const Vec3<double>&,
                                                              const Vec3<double>&);
extern template bool TriangulateMidpoint(const Vec3<double>&, const Vec3<double>&, const Vec3<double>&,
                                         const Vec3<double>&, Vec3<double>*);

}  // namespace vstcal
