#include "support/handeye_scenes.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

namespace vstcal::testing {
namespace {

Rigid3d BoardFromCamera(double tau, bool one_axis) {
  const Eigen::Vector3d turn = one_axis ? Eigen::Vector3d(0, 0, 0.4 * std::sin(0.5 * tau + 2))
                                        : Eigen::Vector3d(0.25 * std::sin(0.7 * tau), 0.25 * std::sin(1.1 * tau + 1), 0.3 * std::sin(0.5 * tau + 2));
  return Rigid3d::FromRotvec(turn, Eigen::Vector3d(120 + 100 * std::sin(0.6 * tau), 75 + 60 * std::sin(0.9 * tau), -600 + 80 * std::sin(0.4 * tau)));
}

}  // namespace

HandEyeRecording RecordHandEye(double delta, double noise_px, uint64_t seed, bool one_axis, int views) {
  HandEyeRecording r;
  r.camera = Camera::FromK((Eigen::Matrix3d() << 600, 0, 319.5, 0, 600, 239.5, 0, 0, 1).finished(), ImageSize{640, 480});
  for (int k = 0; k <= 1000; ++k) {
    const double tau = 0.01 * k;
    r.log.push_back({tau, kTrackerFromBoard * BoardFromCamera(tau, one_axis) * kHmdFromCamera.inverse()});
  }
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  for (int i = 0; i < views; ++i) {
    TimedView v;
    v.name = "frame-" + std::to_string(i);
    v.time = 0.5 + 9.0 * i / std::max(1, views - 1);
    const Rigid3d camera_from_board = BoardFromCamera(v.time + delta, one_axis).inverse();
    for (int row = 0; row < 6; ++row) {
      for (int col = 0; col < 9; ++col) {
        const Eigen::Vector3d P(30.0 * col, 30.0 * row, 0);
        const auto q = r.camera.Project(camera_from_board * P);
        const Eigen::Vector2d noise(g(rng), g(rng));  // drawn for every corner: the noise does not depend on which are kept
        if (!q || q->x() < 1 || q->y() < 1 || q->x() > 638 || q->y() > 478) continue;  // corners in the image only
        v.observations.push_back({P, *q + noise_px * noise, 1.0});
      }
    }
    r.views.push_back(std::move(v));
  }
  return r;
}

}  // namespace vstcal::testing
