// Rotation parametrisations (docs/conventions.md#rotations).
//
// Templated functions run with double and with ceres::Jet (tests/unit/geometry_test.cc,
// Rotation.JetDerivatives, instantiates them with Jets). Rotation vector r = θ·axis in radians;
// quaternions are [w, x, y, z].
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>

namespace vstcal {

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Mat3 = Eigen::Matrix<T, 3, 3>;

// Skew-symmetric matrix [v]× with [v]× w = v × w.
template <typename T>
Mat3<T> Hat(const Vec3<T>& v) {
  Mat3<T> m;
  m << T(0), -v(2), v(1), v(2), T(0), -v(0), -v(1), v(0), T(0);
  return m;
}

// Rodrigues' formula R = I + sin θ [a]× + (1 − cos θ) [a]×². Below θ² = 1e-20 it uses the
// first-order form I + [r]×, exact to machine precision there and with correct Jet derivatives
// at r = 0 (the closed form would divide 0 by 0).
template <typename T>
Mat3<T> RotationFromRotvec(const Vec3<T>& r) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T theta2 = r.squaredNorm();
  if (theta2 > T(1e-20)) {
    const T theta = sqrt(theta2);
    const Vec3<T> axis = r / theta;
    const Mat3<T> k = Hat(axis);
    return Mat3<T>::Identity() + sin(theta) * k + (T(1) - cos(theta)) * (k * k);
  }
  return Mat3<T>::Identity() + Hat(r);
}

// R = I + A[r]× + B[r]×² from the coefficients A and B, with [r]×² = r rᵀ − θ² I (t2 = θ²): the
// assembly of RotationFromSmallRotvec, in a fixed order of operations.
template <typename T>
Mat3<T> RotationFromCoefficients(const Vec3<T>& r, const T& t2, const T& A, const T& B) {
  const T d = T(1) - B * t2;
  const T ax = A * r(0), ay = A * r(1), az = A * r(2);
  const T bxy = B * r(0) * r(1), bxz = B * r(0) * r(2), byz = B * r(1) * r(2);
  Mat3<T> m;
  m << d + B * r(0) * r(0), bxy - az, bxz + ay,  //
      bxy + az, d + B * r(1) * r(1), byz - ax,   //
      bxz - ay, byz + ax, d + B * r(2) * r(2);
  return m;
}

// The same rotation as RotationFromRotvec, about 5× faster for the small angles of error models
// (θ < 0.1 rad): R = I + A[r]× + B[r]×² with A = sin θ/θ and B = (1 − cos θ)/θ² from their
// Taylor series through θ¹⁰ (the first omitted terms are below 2e-22 there, under rounding), so no
// sqrt or trig. Polynomial in r, hence exact Jet derivatives at r = 0 too. Larger angles take
// RotationFromRotvec. Below 0.1 rad every operation is in a fixed order (θ² summed left to right,
// as Eigen sums a double 3-vector), so any scalar type gives double's bits (fixed_order.h).
template <typename T>
Mat3<T> RotationFromSmallRotvec(const Vec3<T>& r) {
  const T t2 = r(0) * r(0) + r(1) * r(1) + r(2) * r(2);
  if (!(t2 < T(1e-2))) return RotationFromRotvec(r);
  const T A = T(1) - t2 * (T(1.0 / 6) - t2 * (T(1.0 / 120) - t2 * (T(1.0 / 5040) - t2 * (T(1.0 / 362880) - t2 * T(1.0 / 39916800)))));
  const T B = T(0.5) - t2 * (T(1.0 / 24) - t2 * (T(1.0 / 720) - t2 * (T(1.0 / 40320) - t2 * (T(1.0 / 3628800) - t2 * T(1.0 / 479001600)))));
  return RotationFromCoefficients(r, t2, A, B);
}

// R·p without forming R (used inside cost functions).
template <typename T>
Vec3<T> RotateByRotvec(const Vec3<T>& r, const Vec3<T>& p) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T theta2 = r.squaredNorm();
  if (theta2 > T(1e-20)) {
    const T theta = sqrt(theta2);
    const Vec3<T> a = r / theta;
    const T c = cos(theta);
    return p * c + a.cross(p) * sin(theta) + a * (a.dot(p) * (T(1) - c));
  }
  return p + r.cross(p);
}

// The left Jacobian of SO(3): Exp(ω + dω) ≈ Exp(J_l(ω) dω) Exp(ω), so that
// ∂(Exp(ω) y)/∂ω = −[Exp(ω) y]× J_l(ω).
// J_l(ω) = I + (1 − cos θ)/θ² [ω]× + (θ − sin θ)/θ³ [ω]×², θ = ‖ω‖ (series below θ = 1e-5).
Eigen::Matrix3d LeftJacobianSO3(const Eigen::Vector3d& omega);

// Rotation vector of R (angle in [0, π]). R must be a rotation (see IsRotation).
Eigen::Vector3d RotvecFromRotation(const Eigen::Matrix3d& R);

// Quaternion [w, x, y, z] with w ≥ 0.
std::array<double, 4> QuaternionWxyzFromRotation(const Eigen::Matrix3d& R);
// Rotation of a quaternion [w, x, y, z]; the quaternion is normalized first (must be non-zero).
Eigen::Matrix3d RotationFromQuaternionWxyz(const std::array<double, 4>& q);

// The rotation nearest to M in the Frobenius norm (SVD, determinant forced to +1).
Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& M);

// True when ‖RᵀR − I‖_max ≤ tolerance and det R > 0.
bool IsRotation(const Eigen::Matrix3d& R, double tolerance = 1e-9);

// Rotation angle between two rotations, radians, in [0, π].
double AngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double DegToRad(double deg) { return deg * (kPi / 180.0); }
inline constexpr double RadToDeg(double rad) { return rad * (180.0 / kPi); }

}  // namespace vstcal
