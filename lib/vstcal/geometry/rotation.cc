#include "vstcal/geometry/rotation.h"

#include <Eigen/SVD>
#include <algorithm>

namespace vstcal {

Eigen::Matrix3d LeftJacobianSO3(const Eigen::Vector3d& omega) {
  const double theta2 = omega.squaredNorm();
  const Eigen::Matrix3d W = Hat(omega);
  double a, b;  // (1 − cos θ)/θ², (θ − sin θ)/θ³
  if (theta2 < 1e-10) {
    a = 0.5 - theta2 / 24.0;
    b = 1.0 / 6.0 - theta2 / 120.0;
  } else {
    const double theta = std::sqrt(theta2);
    a = (1 - std::cos(theta)) / theta2;
    b = (theta - std::sin(theta)) / (theta2 * theta);
  }
  return Eigen::Matrix3d::Identity() + a * W + b * (W * W);
}

Eigen::Vector3d RotvecFromRotation(const Eigen::Matrix3d& R) {
  // Through the quaternion: stable at θ → 0 and θ → π, unlike acos((tr R − 1)/2).
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d v = q.vec();
  const double s = v.norm();
  if (s < 1e-300) return Eigen::Vector3d::Zero();
  const double theta = 2.0 * std::atan2(s, q.w());
  return v * (theta / s);
}

std::array<double, 4> QuaternionWxyzFromRotation(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return {q.w(), q.x(), q.y(), q.z()};
}

Eigen::Matrix3d RotationFromQuaternionWxyz(const std::array<double, 4>& q) {
  Eigen::Quaterniond e(q[0], q[1], q[2], q[3]);
  e.normalize();
  return e.toRotationMatrix();
}

Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& M) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

bool IsRotation(const Eigen::Matrix3d& R, double tolerance) {
  if (!R.allFinite()) return false;
  const double orthogonality = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  return orthogonality <= tolerance && R.determinant() > 0;
}

double AngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return RotvecFromRotation(a.transpose() * b).norm();
}

}  // namespace vstcal
