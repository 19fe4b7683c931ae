#include "vstcal/estimators/decompose.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>

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
