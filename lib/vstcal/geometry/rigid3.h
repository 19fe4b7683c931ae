// Rigid transforms named a_from_b: x_a = a_from_b * x_b = R x_b + t (docs/conventions.md).
#pragma once

#include <Eigen/Core>

#include "vstcal/geometry/rotation.h"

namespace vstcal {

template <typename T>
struct Rigid3 {
  Mat3<T> R = Mat3<T>::Identity();
  Vec3<T> t = Vec3<T>::Zero();

  static Rigid3 Identity() { return Rigid3{}; }

  // From a rotation vector (radians) and a translation.
  static Rigid3 FromRotvec(const Vec3<T>& rotvec, const Vec3<T>& translation) {
    return Rigid3{RotationFromRotvec(rotvec), translation};
  }

  Vec3<T> operator*(const Vec3<T>& x_b) const { return R * x_b + t; }

  // a_from_c = a_from_b * b_from_c.
  Rigid3 operator*(const Rigid3& b_from_c) const { return Rigid3{R * b_from_c.R, R * b_from_c.t + t}; }

  Rigid3 inverse() const {
    const Mat3<T> Rt = R.transpose();
    return Rigid3{Rt, -(Rt * t)};
  }

  // [R | t] as a 3×4 matrix.
  Eigen::Matrix<T, 3, 4> matrix3x4() const {
    Eigen::Matrix<T, 3, 4> m;
    m.template leftCols<3>() = R;
    m.col(3) = t;
    return m;
  }

  template <typename U>
  Rigid3<U> cast() const {
    return Rigid3<U>{R.template cast<U>(), t.template cast<U>()};
  }
};

using Rigid3d = Rigid3<double>;

// A pose's tangent (ω, ρ) and the blocks of its covariance (docs/conventions.md#poses-in-optimisation).
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Matrix6Xd = Eigen::Matrix<double, 6, Eigen::Dynamic>;

// Left perturbation in the destination frame (docs/conventions.md#poses-in-optimisation):
// a_from_b' = (Exp(omega), rho) · a_from_b, i.e. R' = Exp(ω)R, t' = Exp(ω)t + ρ. Perturbations
// are small: RotationFromSmallRotvec (the same rotation, faster below 0.1 rad).
template <typename T>
Rigid3<T> PerturbLeft(const Rigid3<T>& a_from_b, const Vec3<T>& omega, const Vec3<T>& rho) {
  return Rigid3<T>{RotationFromSmallRotvec(omega), rho} * a_from_b;
}

// PerturbLeft's inverse: the (ω, ρ) with to = (Exp(ω), ρ) · from — an estimate's error against the
// truth, a bootstrap replicate's offset from the estimate, in the covariance's convention.
inline Vector6d LeftPerturbationBetween(const Rigid3d& from, const Rigid3d& to) {
  const Eigen::Vector3d omega = RotvecFromRotation(to.R * from.R.transpose());
  Vector6d e;
  e << omega, to.t - RotationFromRotvec(omega) * from.t;
  return e;
}

}  // namespace vstcal
