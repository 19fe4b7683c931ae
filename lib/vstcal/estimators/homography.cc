#include "vstcal/estimators/homography.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

#include "vstcal/geometry/linalg.h"

namespace vstcal {
namespace {

// Similarity moving 2-D points to zero mean and RMS distance √2.
Eigen::Matrix3d Normalizer(std::span<const Eigen::Vector2d> points) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  double ss = 0;
  for (const auto& p : points) ss += (p - mean).squaredNorm();
  const double s = std::sqrt(2.0 * static_cast<double>(points.size()) / ss);
  Eigen::Matrix3d T;
  T << s, 0, -s * mean.x(), 0, s, -s * mean.y(), 0, 0, 1;
  return T;
}

}  // namespace

std::optional<Eigen::Matrix3d> EstimateHomography(std::span<const Observation> obs) {
  const size_t n = obs.size();
  if (n < 4) return std::nullopt;
  std::vector<Eigen::Vector2d> board(n), image(n);
  for (size_t i = 0; i < n; ++i) {
    board[i] = obs[i].point.head<2>();
    image[i] = obs[i].pixel;
  }
  const Eigen::Matrix3d Tb = Normalizer(board), Ti = Normalizer(image);
  if (!Tb.allFinite() || !Ti.allFinite()) return std::nullopt;
  // The right singular vectors of the 2n × 9 system A are the eigenvectors of the 9 × 9 AᵀA, and
  // its singular values the square roots of the eigenvalues: on normalized coordinates AᵀA is well
  // enough conditioned, and a 9 × 9 eigenproblem costs a fraction of A's Jacobi SVD (PnP starts
  // from a homography every frame). On the dynamic type (geometry/linalg.h), which gives the fixed
  // type's bits at 9 × 9 (docs/performance.md#build, stop 35).
  Eigen::Matrix<double, 9, 9> AtA = Eigen::Matrix<double, 9, 9>::Zero();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d X = Tb * board[i].homogeneous();
    const Eigen::Vector3d q = Ti * image[i].homogeneous();
    Eigen::Matrix<double, 2, 9> rows;
    rows.row(0) << X.transpose(), 0, 0, 0, -q.x() * X.transpose();
    rows.row(1) << 0, 0, 0, X.transpose(), -q.y() * X.transpose();
    AtA.noalias() += rows.transpose() * rows;
  }
  const SymmetricEigen eig = DecomposeSymmetric(AtA);
  // σ₇ > 1e-6 σ₀ for the second-smallest and the largest singular values, squared.
  if (!(eig.values(1) > 1e-12 * eig.values(8))) return std::nullopt;
  const Eigen::Matrix<double, 9, 1> h = eig.vectors.col(0);
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  Eigen::Matrix3d H = Ti.inverse() * Hn * Tb;
  H /= H.norm();
  if (H(2, 2) < 0) H = -H;
  return H;
}

}  // namespace vstcal
