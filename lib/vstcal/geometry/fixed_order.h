// Small linear algebra in a fixed order of operations, for code that must give the same bits with
// every scalar type: the err-sim chain runs with double and with SimdDouble (four samples at once,
// core/simd_double.h), and a sample's numbers must not depend on which. Eigen picks the summation
// order of a product or a reduction by scalar type (SSE2 packets for double, a halving unroller
// for other scalars: (x₀ + x₁) + x₂ against x₀ + (x₁ + x₂)), which is equally accurate but not the
// same bits. Here every sum runs left to right, element by element as written.
//
// Matrices and transforms may hold double while the vectors hold T (constants of the chain times
// per-sample values): double × T is the same operation as T(double) × T.
#pragma once

#include <cmath>

#include "vstcal/geometry/rigid3.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal::fixed_order {

template <typename T, int N>
T Dot(const Eigen::Matrix<T, N, 1>& a, const Eigen::Matrix<T, N, 1>& b) {
  T sum = a(0) * b(0);
  for (int i = 1; i < N; ++i) sum = sum + a(i) * b(i);
  return sum;
}

template <typename T, int N>
T SquaredNorm(const Eigen::Matrix<T, N, 1>& a) {
  return Dot(a, a);
}

template <typename T, int N>
T Norm(const Eigen::Matrix<T, N, 1>& a) {
  using std::sqrt;
  return sqrt(SquaredNorm(a));
}

// a × b, component by component as written (Eigen's is the same formula; stated here so that the
// order does not rest on it).
template <typename T>
Vec3<T> Cross(const Vec3<T>& a, const Vec3<T>& b) {
  return Vec3<T>(a(1) * b(2) - a(2) * b(1), a(2) * b(0) - a(0) * b(2), a(0) * b(1) - a(1) * b(0));
}

// m·v; M is T or double.
template <typename M, typename T>
Vec3<T> Times(const Mat3<M>& m, const Vec3<T>& v) {
  return Vec3<T>(m(0, 0) * v(0) + m(0, 1) * v(1) + m(0, 2) * v(2), m(1, 0) * v(0) + m(1, 1) * v(1) + m(1, 2) * v(2),
                 m(2, 0) * v(0) + m(2, 1) * v(1) + m(2, 2) * v(2));
}

// a·b; B is T or double.
template <typename T, typename B>
Mat3<T> Times(const Mat3<T>& a, const Mat3<B>& b) {
  Mat3<T> m;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m(i, j) = a(i, 0) * b(0, j) + a(i, 1) * b(1, j) + a(i, 2) * b(2, j);
  }
  return m;
}

// a_from_b · x_b; S is T or double.
template <typename S, typename T>
Vec3<T> Apply(const Rigid3<S>& a_from_b, const Vec3<T>& x_b) {
  return Times(a_from_b.R, x_b) + a_from_b.t.template cast<T>();
}

// a_from_c = a_from_b · b_from_c; S is T or double.
template <typename T, typename S>
Rigid3<T> Compose(const Rigid3<T>& a_from_b, const Rigid3<S>& b_from_c) {
  return Rigid3<T>{Times(a_from_b.R, b_from_c.R), Apply(a_from_b, Vec3<T>(b_from_c.t.template cast<T>()))};
}

template <typename T>
Rigid3<T> Inverse(const Rigid3<T>& a_from_b) {
  const Mat3<T> Rt = a_from_b.R.transpose();
  return Rigid3<T>{Rt, -Times(Rt, a_from_b.t)};
}

// Exp(r), the rotation of rotation vector r: RotationFromSmallRotvec below 0.1 rad, Rodrigues'
// coefficients A = sin θ/θ, B = (1 − cos θ)/θ² in the same assembly above.
template <typename T>
Mat3<T> Exp(const Vec3<T>& r) {
  const T t2 = SquaredNorm(r);
  if (t2 < T(1e-2)) return RotationFromSmallRotvec(r);
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T theta = sqrt(t2);
  return RotationFromCoefficients(r, t2, sin(theta) / theta, (T(1) - cos(theta)) / t2);
}

// PerturbLeft of rigid3.h: (Exp(ω), ρ) · a_from_b; S is T or double.
template <typename T, typename S>
Rigid3<T> PerturbLeft(const Rigid3<S>& a_from_b, const Vec3<T>& omega, const Vec3<T>& rho) {
  const Mat3<T> R = Exp(omega);
  return Rigid3<T>{Times(R, a_from_b.R), Times(R, Vec3<T>(a_from_b.t.template cast<T>())) + rho};
}

}  // namespace vstcal::fixed_order
