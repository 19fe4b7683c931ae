#include "support/scenes.h"

#include "vstcal/random/philox.h"

namespace vstcal::testing {

Scene RandomVolumeScene(size_t n, double noise_px, uint64_t seed) {
  Scene s;
  Eigen::Matrix3d K;
  K << 1700, 0.8, 652.3, 0, 1695, 498.1, 0, 0, 1;
  s.camera = Camera::FromK(K, ImageSize{1280, 1024});
  s.camera_from_world = Rigid3d::FromRotvec(Eigen::Vector3d(0.05, -0.2, 0.03), Eigen::Vector3d(-120, 80, 2600));
  const CounterRng points(seed, 0), noise(seed, 1);
  size_t index = 0;
  while (s.observations.size() < n) {
    const auto a = points.Uniform2(index, 0), b = points.Uniform2(index, 1);
    ++index;
    const Eigen::Vector3d p((a[0] - 0.5) * 1200, (a[1] - 0.5) * 900, b[0] * 2000);
    const auto px = s.camera.Project(s.camera_from_world * p);
    if (!px || !s.camera.InImage(*px)) continue;
    const auto e = noise.Normal2(s.observations.size(), 0);
    s.true_pixels.push_back(*px);
    s.observations.push_back({p, *px + noise_px * Eigen::Vector2d(e[0], e[1])});
  }
  return s;
}

std::vector<Eigen::Vector3d> PointsInFront(int n, uint64_t seed, double half_width, double half_height) {
  const CounterRng rng(seed, 0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    const auto a = rng.Uniform2(i, 0), b = rng.Uniform2(i, 1);
    const double z = 0.3 + 4 * b[0];
    points.emplace_back((2 * a[0] - 1) * half_width * z, (2 * a[1] - 1) * half_height * z, z);
  }
  return points;
}

VolumeSpec NearWideVolumeSpec() {
  VolumeSpec spec;
  spec.grid_cols = 15;
  spec.grid_rows = 9;
  spec.spacing = 60;
  spec.far = 1000;
  spec.interval = 100;
  spec.camera_distance = 500;
  spec.tilt_deg = 8;
  return spec;
}

Camera DistortedWideCamera() {
  Eigen::Matrix3d K;
  K << 700.2, 0, 641.3, 0, 698.4, 361.7, 0, 0, 1;
  const double d[5] = {-0.171, 0.028, 0.0007, -0.0004, 0.0};
  return Camera::FromK(K, ImageSize{1280, 720}, RadialTangentialModel{}, d);
}

Correspondences WithNoise(const Correspondences& clean, double sigma_px, uint64_t seed) {
  Correspondences c = clean;
  const CounterRng rng(seed, 0);
  uint64_t k = 0;
  for (View& v : c.views) {
    for (Observation& o : v.observations) {
      const auto e = rng.Normal2(k++, 0);
      o.pixel += sigma_px * Eigen::Vector2d(e[0], e[1]);
    }
  }
  return c;
}

}  // namespace vstcal::testing
