#include "vstcal/stereo/synthetic_tracks.h"

#include <cmath>
#include <string>

#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

constexpr uint32_t kNoiseStream = 0x73747231;  // "str1": pixel noise of synthetic tracks

std::string Name(const char* prefix, size_t i, int width) {
  std::string digits = std::to_string(i);
  if (static_cast<int>(digits.size()) < width) digits.insert(0, static_cast<size_t>(width) - digits.size(), '0');
  return prefix + digits;
}

std::vector<std::optional<Eigen::Vector2d>> Observe(const Camera& camera, const Rigid3d& camera_from_world,
                                                    const std::vector<NamedPoint>& points, const CounterRng& rng,
                                                    uint64_t index, double noise_px) {
  std::vector<std::optional<Eigen::Vector2d>> out;
  for (size_t i = 0; i < points.size(); ++i) {
    const auto px = camera.Project(camera_from_world * points[i].point_in_world);
    const auto n = rng.Normal2(index, static_cast<uint32_t>(i));
    const std::optional<Eigen::Vector2d> noisy =
        px ? std::optional<Eigen::Vector2d>(*px + noise_px * Eigen::Vector2d(n[0], n[1])) : std::nullopt;
    out.push_back(noisy && camera.InImage(*noisy) ? noisy : std::nullopt);
  }
  return out;
}

}  // namespace

Tracks SyntheticTracks(const StereoRig& rig, const SyntheticTracksSpec& spec) {
  Tracks t;
  t.length_unit = rig.length_unit;
  t.left_image_size = rig.left.camera.image_size;
  t.right_image_size = rig.right.camera.image_size;
  const double h = spec.size / 2;
  if (spec.planar) {
    const double square[4][2] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
    for (int i = 0; i < 4; ++i) t.embedded.push_back({Name("E", i, 1), Eigen::Vector3d(square[i][0], square[i][1], 0)});
  } else {
    const double cube[6][3] = {{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}, {0, 0, -spec.size}, {h, 0, -h}};
    for (int i = 0; i < 6; ++i) t.embedded.push_back({Name("E", i, 1), Eigen::Vector3d(cube[i][0], cube[i][1], cube[i][2])});
  }
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner((i & 1 ? 1 : -1) * 2 * h, (i & 2 ? 1 : -1) * 1.5 * h, (i & 4 ? -2 : 0.5) * h);
    t.virtual_points.push_back({Name("V", i, 1), corner});
  }
  const CounterRng left_noise(spec.seed, kNoiseStream), right_noise(spec.seed, kNoiseStream + 1);
  const int width = static_cast<int>(std::to_string(spec.frames).size());
  for (size_t k = 0; k < spec.frames; ++k) {
    const double phase = 2 * kPi * static_cast<double>(k) / static_cast<double>(std::max<size_t>(spec.frames, 1));
    const Eigen::Vector3d rotvec(DegToRad(6) * std::sin(2 * phase), DegToRad(9) * std::sin(phase), DegToRad(3) * std::cos(phase));
    const Eigen::Vector3d offset(0.1 * std::sin(phase), 0.1 * std::cos(3 * phase), 0.1 * std::sin(2 * phase + 1));
    // The world origin sits `distance` in front of the cameras' midpoint, moved by `offset`.
    const Rigid3d view = Rigid3d::FromRotvec(rotvec, spec.distance * (Eigen::Vector3d(0, 0, 1) + offset));
    const Rigid3d left_from_centre{Eigen::Matrix3d::Identity(), 0.5 * rig.right_from_left.inverse().t};
    TrackedFrame f;
    f.name = Name("frame-", k, width);
    f.truth_left_from_world = left_from_centre * view;
    f.left = Observe(rig.left.camera, *f.truth_left_from_world, t.embedded, left_noise, k, spec.noise_px);
    f.right = Observe(rig.right.camera, rig.right_from_left * *f.truth_left_from_world, t.embedded, right_noise, k,
                      spec.noise_px);
    t.frames.push_back(std::move(f));
  }
  return t;
}

}  // namespace vstcal
