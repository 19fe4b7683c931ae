#include "vstcal/calib/fisheye_start.h"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

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

}  // namespace

ZhangResult EquidistantZhangStart(const Correspondences& c, const ZhangResult& pinhole) {
  // OpenCV's fisheye guess first (180° across the longer side, centred): a pinhole K from bent
  // homographies can be tens of % off, too far for the linearized corners to be consistent.
  const double f = std::max(c.image_size.width, c.image_size.height) / kPi;
  Eigen::Matrix3d guess;
  guess << f, 0, 0.5 * c.image_size.width - 0.5, 0, f, 0.5 * c.image_size.height - 0.5, 0, 0, 1;
  ZhangResult r = Rounds(c, guess);
  if (r.ok) return r;
  if (pinhole.ok) r = Rounds(c, pinhole.camera.K());
  return r.ok ? r : pinhole;
}

}  // namespace vstcal
