#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include "vstcal/estimators/pnp_starts.h"
#include "vstcal/geometry/point_registration.h"

namespace vstcal::pnp_starts {

namespace {

// ---- Few points in space (4 or 5): EPnP's kernel is then (nearly) four-dimensional and its
// approximations of the betas are unreliable. Grunert's P3P (1841, as Haralick, Lee, Ottenberg &
// Nölle, IJCV 13, 1994 give it) on the largest triangle, the other points choosing among its up to
// four solutions.
std::vector<Rigid3d> P3P(const std::array<Eigen::Vector3d, 3>& world, const std::array<Eigen::Vector3d, 3>& ray) {
  const std::array<Eigen::Vector3d, 3> j = {ray[0].normalized(), ray[1].normalized(), ray[2].normalized()};
  // Angles at the centre opposite the sides a = |P2 − P3|, b = |P1 − P3|, c = |P1 − P2|.
  const double ca = j[1].dot(j[2]), cb = j[0].dot(j[2]), cg = j[0].dot(j[1]);
  const double a2 = (world[1] - world[2]).squaredNorm(), b2 = (world[0] - world[2]).squaredNorm(),
               c2 = (world[0] - world[1]).squaredNorm();
  // With s2 = u s1, s3 = v s1 the law of cosines gives a quartic in v (Grunert).
  const double p = (a2 - c2) / b2, q = (a2 + c2) / b2;
  const double A[5] = {(1 + p) * (1 + p) - 4 * a2 / b2 * cg * cg,
                       4 * (-p * (1 + p) * cb + 2 * a2 / b2 * cg * cg * cb - (1 - q) * ca * cg),
                       2 * (p * p - 1 + 2 * p * p * cb * cb + 2 * (b2 - c2) / b2 * ca * ca - 4 * q * ca * cb * cg +
                            2 * (b2 - a2) / b2 * cg * cg),
                       4 * (p * (1 - p) * cb - (1 - q) * ca * cg + 2 * c2 / b2 * ca * ca * cb),
                       (p - 1) * (p - 1) - 4 * c2 / b2 * ca * ca};
  std::vector<Rigid3d> poses;
  if (!(std::abs(A[4]) > 1e-12 * (std::abs(A[0]) + std::abs(A[2])))) return poses;
  Eigen::Matrix4d companion = Eigen::Matrix4d::Zero();
  for (int k = 0; k < 4; ++k) companion(0, k) = -A[3 - k] / A[4];
  companion.bottomLeftCorner<3, 3>().setIdentity();
  const Eigen::EigenSolver<Eigen::Matrix4d> roots(companion, false);
  for (int k = 0; k < 4; ++k) {
    const std::complex<double> root = roots.eigenvalues()(k);
    const double v = root.real();
    if (std::abs(root.imag()) > 1e-6 * (1 + std::abs(v)) || !(v > 0)) continue;
    const double denominator = 2 * (cg - v * ca);
    if (std::abs(denominator) < 1e-12) continue;
    const double u = ((p - 1) * v * v - 2 * p * cb * v + 1 + p) / denominator;
    const double s1_squared = b2 / (1 + v * v - 2 * v * cb);
    if (!(u > 0) || !(s1_squared > 0)) continue;
    const double s1 = std::sqrt(s1_squared);
    const std::array<Eigen::Vector3d, 3> in_camera = {s1 * j[0], u * s1 * j[1], v * s1 * j[2]};
    if (const auto pose = RegisterPointsHorn(world, in_camera)) poses.push_back(*pose);
  }
  return poses;
}

}  // namespace

ClosedFormPose FewPointsPose(std::span<const Eigen::Vector3d> world, std::span<const Eigen::Vector3d> rays) {
  std::array<size_t, 3> best{};
  double largest = -1;
  for (size_t a = 0; a < world.size(); ++a) {
    for (size_t b = a + 1; b < world.size(); ++b) {
      for (size_t c = b + 1; c < world.size(); ++c) {
        const double area = (world[b] - world[a]).cross(world[c] - world[a]).norm();
        if (area > largest) largest = area, best = {a, b, c};
      }
    }
  }
  ClosedFormPose result;
  double best_error = std::numeric_limits<double>::infinity();
  for (const Rigid3d& pose : P3P({world[best[0]], world[best[1]], world[best[2]]}, {rays[best[0]], rays[best[1]], rays[best[2]]})) {
    const double error = ReprojectionError(pose, world, rays);
    if (error < best_error) best_error = error, result = {PoseStatus::kOk, pose, std::nullopt};
  }
  return result;
}

}  // namespace vstcal::pnp_starts
