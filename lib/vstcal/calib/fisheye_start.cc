#include "vstcal/calib/fisheye_start.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "vstcal/geometry/linalg.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal {
namespace {

// The rounds from K; !ok when the first fails (a view left with too few corners, Zhang refusing
// the linearized corners), else the last round that succeeded.
ZhangResult Rounds(const Correspondences& c, Eigen::Matrix3d K) {
  constexpr double kMaxAngle = 75 * kPi / 180;  // tan 75° = 3.7: a corner there still weighs like the others
  ZhangResult best;
  for (int round = 0; round < 50; ++round) {
    const Eigen::Matrix3d K_inverse = K.inverse();
    Correspondences linear = c;
    for (View& view : linear.views) {
      std::vector<Observation> kept;
      for (Observation o : view.observations) {
        const Eigen::Vector3d x = K_inverse * o.pixel.homogeneous();
        const double theta_d = x.head<2>().norm();
        if (!(theta_d < kMaxAngle)) continue;
        const double scale = theta_d > 0 ? std::tan(theta_d) / theta_d : 1.0;
        o.pixel = (K * Eigen::Vector3d(scale * x.x(), scale * x.y(), 1)).head<2>();
        kept.push_back(o);
      }
      if (kept.size() < kMinPointsPerPlanarView) return best;
      view.observations = std::move(kept);
    }
    ZhangResult next = ZhangInitialization(linear);
    if (!next.ok) return best;
    const double moved = (next.camera.K() - K).norm() / K.norm();
    K = next.camera.K();
    best = std::move(next);
    if (moved < 1e-9) break;
  }
  return best;
}

// Sum of squared reprojection errors, px², of every corner through `camera` at the poses; a corner
// the camera cannot project costs the image diagonal squared (a start that loses corners is worse
// than any that keeps them inside the image).
double ReprojectionCost(const Correspondences& c, const Camera& camera, const std::vector<Rigid3d>& poses) {
  const double lost = std::pow(std::hypot(c.image_size.width, c.image_size.height), 2);
  double cost = 0;
  for (size_t v = 0; v < c.views.size(); ++v) {
    for (const Observation& o : c.views[v].observations) {
      const auto px = camera.Project(poses[v] * o.point);
      const double e = px ? (*px - o.pixel).squaredNorm() : lost;
      cost += std::isfinite(e) ? std::min(e, lost) : lost;
    }
  }
  return cost;
}

// k1…k4 by linear least squares with K and the poses fixed: the Kannala–Brandt radius is linear in
// them, θd = θ + k1 θ³ + k2 θ⁵ + k3 θ⁷ + k4 θ⁹, with θ the angle of the board corner off the axis at
// its pose and θd = |K⁻¹ pixel| the normalized radius it was seen at. nullopt when the angles do
// not determine four coefficients (too few corners off the axis).
std::optional<Camera> FitCoefficients(const Correspondences& c, const Eigen::Matrix3d& K, const std::vector<Rigid3d>& poses) {
  const Eigen::Matrix3d K_inverse = K.inverse();
  size_t n = 0;
  for (const View& v : c.views) n += v.observations.size();
  Eigen::MatrixXd A(n, 4);
  Eigen::VectorXd b(n);
  size_t row = 0;
  for (size_t v = 0; v < c.views.size(); ++v) {
    for (const Observation& o : c.views[v].observations) {
      const Eigen::Vector3d p = poses[v] * o.point;
      const double theta = std::atan2(p.head<2>().norm(), p.z());
      const double theta_d = (K_inverse * o.pixel.homogeneous()).head<2>().norm();
      double power = theta * theta * theta;
      for (int j = 0; j < 4; ++j, power *= theta * theta) A(row, j) = power;
      b(row++) = theta_d - theta;
    }
  }
  const LeastSquaresSolution ls = SolveLeastSquares(A, b);
  if (ls.rank < 4) return std::nullopt;
  const Eigen::Vector4d k = ls.x;
  if (!k.allFinite()) return std::nullopt;
  return Camera::FromK(K, c.image_size, KannalaBrandtModel{}, std::span<const double>(k.data(), 4));
}

}  // namespace

FisheyeStart ChooseFisheyeStart(const Correspondences& c, const ZhangResult& pinhole) {
  // OpenCV's fisheye guess (180° across the longer side, centred): a pinhole K from a wide lens's
  // bent homographies can be tens of % off, too far for the linearized corners to be consistent.
  const double f = std::max(c.image_size.width, c.image_size.height) / kPi;
  Eigen::Matrix3d guess;
  guess << f, 0, 0.5 * c.image_size.width - 0.5, 0, f, 0.5 * c.image_size.height - 0.5, 0, 0, 1;

  std::vector<std::pair<const char*, ZhangResult>> candidates;
  candidates.emplace_back("equidistant rounds from the fisheye guess", Rounds(c, guess));
  if (pinhole.ok) {
    candidates.emplace_back("equidistant rounds from the pinhole start", Rounds(c, pinhole.camera.K()));
    candidates.emplace_back("the pinhole start", pinhole);
  }
  FisheyeStart best;
  FisheyeStartDecision& d = best.decision;
  d.cost = std::numeric_limits<double>::infinity();
  for (const View& v : c.views) d.num_points += v.observations.size();
  for (auto& [name, start] : candidates) {
    if (!start.ok) {
      d.candidates.push_back({name, false, false, 0});
      continue;
    }
    const Eigen::Matrix3d K = start.camera.K();
    std::vector<Camera> cameras = {Camera::FromK(K, c.image_size, KannalaBrandtModel{})};
    if (auto fitted = FitCoefficients(c, K, start.camera_from_board)) cameras.push_back(std::move(*fitted));
    for (size_t i = 0; i < cameras.size(); ++i) {
      const double cost = ReprojectionCost(c, cameras[i], start.camera_from_board);
      d.candidates.push_back({name, true, i == 1, cost});
      if (!(cost < d.cost)) continue;
      d.cost = cost;
      d.chosen = name;
      d.coefficients_fitted = i == 1;
      best.start = start;
      best.start.camera = cameras[i];
    }
  }
  if (!std::isfinite(d.cost)) {
    best.start = pinhole;
    d.cost = 0;
    d.chosen = "";
    d.coefficients_fitted = false;
  }
  return best;
}

}  // namespace vstcal
