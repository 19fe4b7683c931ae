#include "vstcal/calib/homography.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>

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
  Eigen::MatrixXd A(2 * n, 9);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d X = Tb * board[i].homogeneous();
    const Eigen::Vector3d q = Ti * image[i].homogeneous();
    const Eigen::Index r = 2 * static_cast<Eigen::Index>(i);
    A.row(r) << X.transpose(), 0, 0, 0, -q.x() * X.transpose();
    A.row(r + 1) << 0, 0, 0, X.transpose(), -q.y() * X.transpose();
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const auto& sv = svd.singularValues();
  if (!(sv(7) > 1e-6 * sv(0))) return std::nullopt;
  const Eigen::Matrix<double, 9, 1> h = svd.matrixV().col(8);
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  Eigen::Matrix3d H = Ti.inverse() * Hn * Tb;
  H /= H.norm();
  if (H(2, 2) < 0) H = -H;
  return H;
}

}  // namespace vstcal
