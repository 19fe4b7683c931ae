#include "vstcal/estimators/decompose.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <string>

#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal {

std::optional<ProjectionDecomposition> DecomposeProjection(const Matrix34d& P) {
  const Eigen::Matrix3d M = P.leftCols<3>();
  if (!M.allFinite() || !(M.determinant() > 0)) return std::nullopt;
  // RQ through QR of the row-reversed transpose: with E the exchange matrix (E = Eᵀ = E⁻¹),
  // (E M)ᵀ = Q U  ⇒  M = (E Uᵀ E)(E Qᵀ), where E Uᵀ E is upper triangular and E Qᵀ orthogonal.
  Eigen::Matrix3d E;
  E << 0, 0, 1, 0, 1, 0, 1, 0, 0;
  Eigen::HouseholderQR<Eigen::Matrix3d> qr((E * M).transpose());
  const Eigen::Matrix3d U = qr.matrixQR().triangularView<Eigen::Upper>();
  const Eigen::Matrix3d Q = qr.householderQ();
  Eigen::Matrix3d K = E * U.transpose() * E;
  Eigen::Matrix3d R = E * Q.transpose();
  // Make K's diagonal positive: K R = (K D)(D R) for D = diag(±1).
  const Eigen::Vector3d d = K.diagonal().cwiseSign();
  K = K * d.asDiagonal();
  R = d.asDiagonal() * R;
  if (R.determinant() < 0) return std::nullopt;  // cannot happen when det M > 0; guards rounding
  const double scale = K(2, 2);
  ProjectionDecomposition out;
  out.K = K / scale;
  out.K(1, 0) = out.K(2, 0) = out.K(2, 1) = 0;  // exact zeros below the diagonal
  out.K(2, 2) = 1;
  out.camera_from_world.R = R;
  out.camera_from_world.t = K.triangularView<Eigen::Upper>().solve(Eigen::Vector3d(P.col(3)));
  return out;
}

ParameterCovariance DecompositionCovariance(const ProjectionDecomposition& d,
                                            const Eigen::Matrix<double, 12, 12>& P_covariance) {
  using Matrix12x11 = Eigen::Matrix<double, 12, 11>;
  const Eigen::Matrix3d& K = d.K;
  const Matrix34d Rt = d.camera_from_world.matrix3x4();
  const auto vec = [](const Matrix34d& M) {
    Eigen::Matrix<double, 12, 1> v;
    for (int i = 0; i < 12; ++i) v(i) = M(i / 4, i % 4);
    return v;
  };
  Matrix12x11 J;
  // dP = dK [R|t] for the intrinsics (fx, fy, cx, cy, s at K(0,0), K(1,1), K(0,2), K(1,2), K(0,1)).
  const int at[5][2] = {{0, 0}, {1, 1}, {0, 2}, {1, 2}, {0, 1}};
  for (int k = 0; k < 5; ++k) {
    Eigen::Matrix3d dK = Eigen::Matrix3d::Zero();
    dK(at[k][0], at[k][1]) = 1;
    J.col(k) = vec(dK * Rt);
  }
  // R' = Exp(ω) R, t' = Exp(ω) t + ρ: d[R|t] = [ω]×[R|t] + [0|ρ].
  for (int k = 0; k < 3; ++k) {
    J.col(5 + k) = vec(K * Hat<double>(Eigen::Vector3d::Unit(k)) * Rt);
    Matrix34d dP = Matrix34d::Zero();
    dP.col(3) = K.col(k);
    J.col(8 + k) = vec(dP);
  }
  // J⁺ by least squares on unit columns (px and length units differ by orders of magnitude).
  // alignas(16): as in tsai.cc's FocalStandardError, so that the column norms' summation order does
  // not depend on where the compiler puts the vector.
  alignas(16) const Eigen::Matrix<double, 11, 1> scale = J.colwise().norm().transpose();
  const Matrix12x11 Js = J * scale.cwiseInverse().asDiagonal();
  const Eigen::HouseholderQR<Matrix12x11> qr(Js);
  const Eigen::Matrix<double, 11, 12> pinv = scale.cwiseInverse().asDiagonal() * qr.solve(Eigen::Matrix<double, 12, 12>::Identity());
  ParameterCovariance out;
  out.parameters = {"fx", "fy", "cx", "cy", "s"};
  for (const char* axis : {"rx", "ry", "rz", "tx", "ty", "tz"}) out.parameters.push_back(std::string("camera_from_world.") + axis);
  out.matrix = pinv * P_covariance * pinv.transpose();
  out.matrix = (0.5 * (out.matrix + out.matrix.transpose())).eval();
  return out;
}

Eigen::Matrix3d CameraCentreCovariance(const ParameterCovariance& covariance, const Rigid3d& camera_from_world) {
  Eigen::Matrix3d rho = Eigen::Matrix3d::Zero();
  const char* axes[3] = {"camera_from_world.tx", "camera_from_world.ty", "camera_from_world.tz"};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const auto a = covariance.Find(axes[i]), b = covariance.Find(axes[j]);
      VSTCAL_CHECK(a && b, "the covariance names camera_from_world's translation");
      rho(i, j) = covariance.matrix(static_cast<Eigen::Index>(*a), static_cast<Eigen::Index>(*b));
    }
  }
  const Eigen::Matrix3d& R = camera_from_world.R;
  return R.transpose() * rho * R;
}

Eq13Decomposition DecomposeProjectionEq13(const Matrix34d& P) {
  const Eigen::Vector3d a1 = P.block<1, 3>(0, 0).transpose();
  const Eigen::Vector3d a2 = P.block<1, 3>(1, 0).transpose();
  const Eigen::Vector3d a3 = P.block<1, 3>(2, 0).transpose();
  const Eigen::Vector3d b = P.col(3);
  Eq13Decomposition out;
  // Sign of ρ: P's depth row ρ(a₃·X + b₃) must be positive in front. A normalized P already has
  // positive depth, so ρ > 0 (ε = +1 in Forsyth & Ponce's notation).
  const double rho = 1.0 / a3.norm();
  const double rho2 = rho * rho;
  const Eigen::Vector3d c13 = a1.cross(a3), c23 = a2.cross(a3);
  SkewForm& f = out.intrinsics;
  f.u0 = rho2 * a1.dot(a3);
  f.v0 = rho2 * a2.dot(a3);
  f.theta_rad = std::acos(std::clamp(-c13.dot(c23) / (c13.norm() * c23.norm()), -1.0, 1.0));
  f.fu = rho2 * c13.norm() * std::sin(f.theta_rad);
  f.fv = rho2 * c23.norm() * std::sin(f.theta_rad);
  out.rho = rho;
  Rigid3d& pose = out.camera_from_world;
  const Eigen::Vector3d r1 = c23 / c23.norm();
  const Eigen::Vector3d r3 = rho * a3;
  const Eigen::Vector3d r2 = r3.cross(r1);
  pose.R.row(0) = r1.transpose();
  pose.R.row(1) = r2.transpose();
  pose.R.row(2) = r3.transpose();
  pose.t = rho * KFromSkewForm(f).inverse() * b;
  return out;
}

}  // namespace vstcal
