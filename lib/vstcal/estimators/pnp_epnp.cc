#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <vector>

#include "vstcal/estimators/pnp_starts.h"
#include "vstcal/geometry/linalg.h"
#include "vstcal/geometry/point_registration.h"

namespace vstcal::pnp_starts {

namespace {

// ---- EPnP (Lepetit, Moreno-Noguer & Fua 2009): the points as weighted sums of four control
// points; the control points' camera coordinates lie in the null space of a 2n × 12 system.

using Vec12 = Eigen::Matrix<double, 12, 1>;
constexpr int kPairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

// Camera coordinates of the control points for betas over the kernel vectors v[0..3].
std::array<Eigen::Vector3d, 4> ControlPointsInCamera(const std::array<Vec12, 4>& v, const Eigen::Vector4d& beta) {
  std::array<Eigen::Vector3d, 4> c;
  for (int j = 0; j < 4; ++j) {
    c[j].setZero();
    for (int k = 0; k < 4; ++k) c[j] += beta(k) * v[k].segment<3>(3 * j);
  }
  return c;
}

// The pose from the control points in the camera: each point is Σ α c_j; the camera-frame points
// are aligned with the world points by Horn's absolute orientation.
std::optional<Rigid3d> PoseFromControlPoints(const std::array<Eigen::Vector3d, 4>& c,
                                             const std::vector<Eigen::Vector4d>& alphas,
                                             std::span<const Eigen::Vector3d> world) {
  std::vector<Eigen::Vector3d> in_camera(world.size());
  double mean_z = 0;
  for (size_t i = 0; i < world.size(); ++i) {
    in_camera[i] = alphas[i](0) * c[0] + alphas[i](1) * c[1] + alphas[i](2) * c[2] + alphas[i](3) * c[3];
    mean_z += in_camera[i].z();
  }
  if (mean_z < 0) {  // the kernel's sign is free: the points are in front
    for (auto& p : in_camera) p = -p;
  }
  return RegisterPointsHorn(world, in_camera);
}

}  // namespace

ClosedFormPose EpnpPose(std::span<const Eigen::Vector3d> world, std::span<const Eigen::Vector3d> rays, const Spread& s) {
  const size_t n = world.size();
  // Control points: the centroid and one step of σ/√n along each principal axis.
  std::array<Eigen::Vector3d, 4> cw;
  cw[0] = s.centroid;
  Eigen::Matrix3d basis;
  for (int j = 0; j < 3; ++j) {
    basis.col(j) = s.axes.col(j) * (s.sigma(j) / std::sqrt(static_cast<double>(n)));
    cw[j + 1] = s.centroid + basis.col(j);
  }
  const Eigen::Matrix3d basis_inverse = basis.inverse();
  std::vector<Eigen::Vector4d> alphas(n);
  Eigen::Matrix<double, 12, 12> MtM = Eigen::Matrix<double, 12, 12>::Zero();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d b = basis_inverse * (world[i] - s.centroid);
    alphas[i] << 1 - b.sum(), b;
    Eigen::Matrix<double, 2, 12> rows;
    for (int j = 0; j < 4; ++j) {
      rows.block<1, 3>(0, 3 * j) << alphas[i](j), 0, -alphas[i](j) * rays[i].x();
      rows.block<1, 3>(1, 3 * j) << 0, alphas[i](j), -alphas[i](j) * rays[i].y();
    }
    MtM.noalias() += rows.transpose() * rows;
  }
  const SymmetricEigen12 eig = DecomposeSymmetric12(MtM);
  std::array<Vec12, 4> v;
  for (int k = 0; k < 4; ++k) v[k] = eig.vectors.col(k);  // smallest eigenvalues first

  // Distance constraints |c_a − c_b|² = |cw_a − cw_b|² as a linear system in the ten products
  // β_k β_l, ordered (11, 12, 22, 13, 23, 33, 14, 24, 34, 44).
  Eigen::Matrix<double, 6, 10> L;
  Eigen::Matrix<double, 6, 1> rho;
  for (int p = 0; p < 6; ++p) {
    const int a = kPairs[p][0], b = kPairs[p][1];
    std::array<Eigen::Vector3d, 4> d;
    for (int k = 0; k < 4; ++k) d[k] = v[k].segment<3>(3 * a) - v[k].segment<3>(3 * b);
    L.row(p) << d[0].dot(d[0]), 2 * d[0].dot(d[1]), d[1].dot(d[1]), 2 * d[0].dot(d[2]), 2 * d[1].dot(d[2]),
        d[2].dot(d[2]), 2 * d[0].dot(d[3]), 2 * d[1].dot(d[3]), 2 * d[2].dot(d[3]), d[3].dot(d[3]);
    rho(p) = (cw[a] - cw[b]).squaredNorm();
  }
  // The product index of (k, l) in L's columns.
  constexpr int kProduct[4][4] = {{0, 1, 3, 6}, {1, 2, 4, 7}, {3, 4, 5, 8}, {6, 7, 8, 9}};
  auto products = [&](const Eigen::Vector4d& beta) {
    Eigen::Matrix<double, 10, 1> b;
    for (int k = 0; k < 4; ++k) {
      for (int l = k; l < 4; ++l) b(kProduct[k][l]) = beta(k) * beta(l);
    }
    return b;
  };
  // Approximations of the betas (the paper's N = 1, 2, 3 cases): solve for a subset of the
  // products by least squares, then read the betas off them.
  // One dynamic-size QR for the three systems, compiled once in geometry/linalg.cc: it gives the
  // fixed-size ones' solutions bit for bit (60,000 random systems checked, and as many with ρ as a
  // dynamic vector) at a fraction of the compile time (docs/performance.md#build).
  const auto least_squares = [&](std::initializer_list<int> columns) {
    Eigen::MatrixXd A(6, static_cast<Eigen::Index>(columns.size()));
    Eigen::Index c = 0;
    for (const int column : columns) A.col(c++) = L.col(column);
    return SolveLeastSquares(A, Eigen::VectorXd(rho)).x;
  };
  std::vector<Eigen::Vector4d> starts;
  {
    const Eigen::VectorXd b = least_squares({kProduct[0][0], kProduct[0][1], kProduct[0][2], kProduct[0][3]});
    const double b0 = std::sqrt(std::abs(b(0)));
    if (b0 > 0) starts.push_back(Eigen::Vector4d(b0, b(1) / b0, b(2) / b0, b(3) / b0) * (b(0) < 0 ? -1 : 1));
  }
  {
    const Eigen::VectorXd b = least_squares({0, 1, 2});
    const double b0 = std::sqrt(std::abs(b(0))), b1 = std::sqrt(std::abs(b(2)));
    if (b0 > 0) starts.push_back(Eigen::Vector4d(b0, (b(1) < 0 ? -1 : 1) * b1, 0, 0) * (b(0) < 0 ? -1 : 1));
  }
  {
    const Eigen::VectorXd b = least_squares({0, 1, 2, 3, 4});
    const double b0 = std::sqrt(std::abs(b(0))), b1 = std::sqrt(std::abs(b(2)));
    if (b0 > 0) starts.push_back(Eigen::Vector4d(b0, (b(1) < 0 ? -1 : 1) * b1, b(3) / b0, 0) * (b(0) < 0 ? -1 : 1));
  }
  ClosedFormPose best;
  double best_error = std::numeric_limits<double>::infinity();
  for (Eigen::Vector4d beta : starts) {
    // Gauss–Newton on the four betas against the six distance constraints.
    for (int iteration = 0; iteration < 5; ++iteration) {
      const Eigen::Matrix<double, 6, 1> r = L * products(beta) - rho;
      Eigen::Matrix<double, 6, 4> J;
      // ∂(β_k β_l)/∂β_k: 2β_k on the diagonal product, β_l on the others (counted once each).
      for (int p = 0; p < 6; ++p) {
        for (int k = 0; k < 4; ++k) {
          double g = 2 * L(p, kProduct[k][k]) * beta(k);
          for (int l = 0; l < 4; ++l) {
            if (l != k) g += L(p, kProduct[k][l]) * beta(l);
          }
          J(p, k) = g;
        }
      }
      beta -= (J.transpose() * J).ldlt().solve(J.transpose() * r);
    }
    const auto pose = PoseFromControlPoints(ControlPointsInCamera(v, beta), alphas, world);
    if (!pose) continue;
    const double error = ReprojectionError(*pose, world, rays);
    if (error < best_error) {
      best_error = error;
      best = {PoseStatus::kOk, *pose, std::nullopt};
    }
  }
  return best;
}

}  // namespace vstcal::pnp_starts
