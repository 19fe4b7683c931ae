#include "vstcal/estimators/pnp.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "vstcal/estimators/pnp_starts.h"

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

namespace pnp_starts {

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

}  // namespace pnp_starts

namespace {

using pnp_starts::Spread;

// Below this many points in space EPnP's kernel is too large for its approximations.
constexpr size_t kMinEpnpPoints = 6;

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
  if (layout == PointLayout::kPlanar) return pnp_starts::PlanarPose(points_in_world, rays, spread);
  return points_in_world.size() < kMinEpnpPoints ? pnp_starts::FewPointsPose(points_in_world, rays)
                                                 : pnp_starts::EpnpPose(points_in_world, rays, spread);
}

}  // namespace vstcal
