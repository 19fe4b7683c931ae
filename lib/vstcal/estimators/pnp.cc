#include "vstcal/estimators/pnp.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include "vstcal/estimators/homography.h"
#include "vstcal/geometry/point_registration.h"

namespace vstcal {

std::string_view PoseStatusText(PoseStatus status) {
  switch (status) {
    case PoseStatus::kOk: return "ok";
    case PoseStatus::kTooFewPoints: return "fewer than 4 points";
    case PoseStatus::kCollinear: return "the points lie on one line (the rotation about it is free)";
    case PoseStatus::kNoRay: return "a pixel has no ray through the lens model";
    case PoseStatus::kNoSolution: return "no pose puts the points in front of the camera";
    case PoseStatus::kNotConverged: return "the pose refinement did not converge";
  }
  return "?";
}

namespace {

// Below this many points in space EPnP's kernel is too large for its approximations.
constexpr size_t kMinEpnpPoints = 6;

// Centroid, principal axes (columns, by decreasing spread) and the spread σ along each (the square
// roots of the scatter matrix's eigenvalues).
struct Spread {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();
};

Spread SpreadOf(std::span<const Eigen::Vector3d> points) {
  Spread s;
  for (const auto& p : points) s.centroid += p;
  s.centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) scatter += (p - s.centroid) * (p - s.centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  for (int i = 0; i < 3; ++i) {
    s.axes.col(i) = eig.eigenvectors().col(2 - i);
    s.sigma(i) = std::sqrt(std::max(0.0, eig.eigenvalues()(2 - i)));
  }
  return s;
}

PointLayout LayoutOf(const Spread& s) {
  if (!(s.sigma(1) > 1e-6 * s.sigma(0))) return PointLayout::kCollinear;
  if (!(s.sigma(2) > 1e-3 * s.sigma(0))) return PointLayout::kPlanar;
  return PointLayout::kSpatial;
}

double ReprojectionError(const Rigid3d& camera_from_world, std::span<const Eigen::Vector3d> world,
                         std::span<const Eigen::Vector3d> rays) {
  double sum = 0;
  for (size_t i = 0; i < world.size(); ++i) {
    const Eigen::Vector3d p = camera_from_world * world[i];
    if (!(p.z() > 0)) return std::numeric_limits<double>::infinity();
    sum += (p.head<2>() / p.z() - rays[i].head<2>()).squaredNorm();
  }
  return sum;
}

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
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>> eig(MtM);
  std::array<Vec12, 4> v;
  for (int k = 0; k < 4; ++k) v[k] = eig.eigenvectors().col(k);  // smallest eigenvalues first

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
  std::vector<Eigen::Vector4d> starts;
  {
    Eigen::Matrix<double, 6, 4> A;
    for (int k = 0; k < 4; ++k) A.col(k) = L.col(kProduct[0][k]);
    const Eigen::Vector4d b = A.colPivHouseholderQr().solve(rho);
    const double b0 = std::sqrt(std::abs(b(0)));
    if (b0 > 0) starts.push_back(Eigen::Vector4d(b0, b(1) / b0, b(2) / b0, b(3) / b0) * (b(0) < 0 ? -1 : 1));
  }
  {
    Eigen::Matrix<double, 6, 3> A;
    A << L.col(0), L.col(1), L.col(2);
    const Eigen::Vector3d b = A.colPivHouseholderQr().solve(rho);
    const double b0 = std::sqrt(std::abs(b(0))), b1 = std::sqrt(std::abs(b(2)));
    if (b0 > 0) starts.push_back(Eigen::Vector4d(b0, (b(1) < 0 ? -1 : 1) * b1, 0, 0) * (b(0) < 0 ? -1 : 1));
  }
  {
    Eigen::Matrix<double, 6, 5> A;
    A << L.col(0), L.col(1), L.col(2), L.col(3), L.col(4);
    const Eigen::Matrix<double, 5, 1> b = A.colPivHouseholderQr().solve(rho);
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

// ---- Coplanar points: the homography of their plane, H ∝ [r1 r2 t] in the plane's frame.
ClosedFormPose PlanarPose(std::span<const Eigen::Vector3d> world, std::span<const Eigen::Vector3d> rays, const Spread& s) {
  // plane_from_world: x, y along the two main axes, z along the normal (right-handed).
  Rigid3d plane_from_world;
  plane_from_world.R.row(0) = s.axes.col(0).transpose();
  plane_from_world.R.row(1) = s.axes.col(1).transpose();
  plane_from_world.R.row(2) = s.axes.col(0).cross(s.axes.col(1)).transpose();
  plane_from_world.t = -(plane_from_world.R * s.centroid);
  std::vector<Observation> on_plane(world.size());
  for (size_t i = 0; i < world.size(); ++i) {
    on_plane[i].point << (plane_from_world * world[i]).head<2>(), 0;
    on_plane[i].pixel = rays[i].head<2>();
  }
  const auto H = EstimateHomography(on_plane);
  if (!H) return {};
  Eigen::Matrix<double, 3, 2> r12 = H->leftCols<2>();
  const double scale = 0.5 * (r12.col(0).norm() + r12.col(1).norm());
  Eigen::Vector3d t = H->col(2) / scale;
  r12 /= scale;
  if (t.z() < 0) {  // H's sign is free: the plane is in front
    t = -t;
    r12 = -r12;
  }
  // The nearest pair of orthonormal columns (polar decomposition), then r3 = r1 × r2.
  const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>> svd(r12, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix<double, 3, 2> orthonormal = svd.matrixU().leftCols<2>() * svd.matrixV().transpose();
  Rigid3d camera_from_plane;
  camera_from_plane.R << orthonormal.col(0), orthonormal.col(1), orthonormal.col(0).cross(orthonormal.col(1));
  camera_from_plane.t = t;
  ClosedFormPose pose{PoseStatus::kOk, camera_from_plane * plane_from_world, std::nullopt};
  // The mirrored branch: the normal n reflected about the line of sight ŝ to the centroid (the
  // plane frame's origin, at t), n' = 2(n·ŝ)ŝ − n, by the rotation about n × n' through the centroid.
  const Eigen::Vector3d n = camera_from_plane.R.col(2), sight = t.normalized();
  const Eigen::Vector3d mirrored = 2 * n.dot(sight) * sight - n;
  const Eigen::Vector3d axis = n.cross(mirrored);
  if (axis.norm() > 1e-9) {
    const Eigen::Vector3d rotvec = axis.normalized() * std::atan2(axis.norm(), n.dot(mirrored));
    pose.mirrored = Rigid3d{RotationFromRotvec(rotvec) * camera_from_plane.R, t} * plane_from_world;
  }
  return pose;
}

}  // namespace

PointLayout ClassifyLayout(std::span<const Eigen::Vector3d> points) { return LayoutOf(SpreadOf(points)); }

ClosedFormPose SolvePnpClosedForm(const Camera& camera, std::span<const Eigen::Vector3d> points_in_world,
                                  std::span<const Eigen::Vector2d> pixels) {
  if (points_in_world.size() < kMinPnpPoints || pixels.size() != points_in_world.size()) {
    return {PoseStatus::kTooFewPoints, {}, std::nullopt};
  }
  const Spread spread = SpreadOf(points_in_world);
  const PointLayout layout = LayoutOf(spread);
  if (layout == PointLayout::kCollinear) return {PoseStatus::kCollinear, {}, std::nullopt};
  std::vector<Eigen::Vector3d> rays(pixels.size());
  for (size_t i = 0; i < pixels.size(); ++i) {
    const auto ray = camera.Unproject(pixels[i]);
    if (!ray) return {PoseStatus::kNoRay, {}, std::nullopt};
    rays[i] = *ray;
  }
  if (layout == PointLayout::kPlanar) return PlanarPose(points_in_world, rays, spread);
  return points_in_world.size() < kMinEpnpPoints ? FewPointsPose(points_in_world, rays)
                                                 : EpnpPose(points_in_world, rays, spread);
}

}  // namespace vstcal
