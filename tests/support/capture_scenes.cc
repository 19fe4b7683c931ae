#include "support/capture_scenes.h"

#include <cmath>

#include "vstcal/capture/target_pattern.h"
#include "vstcal/random/philox.h"

namespace vstcal::testing {

Target Chessboard9x6() {
  Target t;
  t.rows = 6;
  t.cols = 9;
  t.square_size = 25;
  t.margin = 25;
  return t;
}

Target Charuco7x5() {
  Target t;
  t.type = TargetType::kCharuco;
  t.rows = 5;
  t.cols = 7;
  t.square_size = 30;
  t.marker_size = 22.5;
  t.dictionary = "DICT_5X5_100";
  t.margin = 30;
  return t;
}

Target AprilGrid6x4() {
  Target t;
  t.type = TargetType::kAprilTagGrid;
  t.rows = 4;
  t.cols = 6;
  t.tag_size = 30;
  t.tag_gap = 7.5;
  t.family = "tag36h11";
  t.margin = 7.5;
  return t;
}

Target KalibrAprilGrid6x4() {
  Target t;
  t.type = TargetType::kAprilGrid;
  t.rows = 4;
  t.cols = 6;
  t.tag_size = 30;
  t.tag_spacing = 0.3;
  t.family = "tag36h11";
  t.margin = 9;
  return t;
}

Camera PinholeCamera(int width, int height, double f) {
  Eigen::Matrix3d K;
  K << f, 0, 0.5 * (width - 1), 0, f, 0.5 * (height - 1), 0, 0, 1;
  return Camera::FromK(K, ImageSize{width, height});
}

Camera DistortedCamera(int width, int height, double f) {
  const Camera pinhole = PinholeCamera(width, height, f);
  const double d[5] = {-0.12, 0.03, 4e-4, -3e-4, 0};
  return Camera::FromK(pinhole.K(), pinhole.image_size, RadialTangentialModel{}, d);
}

namespace {

Rigid3d ViewPose(const Camera& camera, const Target& target, double square_px, int k, uint64_t seed, double extra_roll_deg,
                 double min_tilt_deg, double max_tilt_deg) {
  const CounterRng rng(seed, 0x5CE7u);
  const auto a = rng.Uniform2(static_cast<uint64_t>(k), 0), b = rng.Uniform2(static_cast<uint64_t>(k), 1);
  const double square = target.type == TargetType::kAprilTagGrid || target.type == TargetType::kAprilGrid ? target.tag_size : target.square_size;
  const double depth = camera.params[0] * square / square_px;
  // Written so that a minimum of 0 gives exactly the former DegToRad(35.0) * a[0].
  const double tilt = DegToRad(min_tilt_deg) + (DegToRad(max_tilt_deg) - DegToRad(min_tilt_deg)) * a[0], axis = 2 * kPi * a[1];
  const double roll = DegToRad(60.0 * (b[0] - 0.5) + extra_roll_deg);
  const Eigen::Matrix3d R = RotationFromRotvec(Eigen::Vector3d(tilt * std::cos(axis), tilt * std::sin(axis), 0)) *
                            RotationFromRotvec(Eigen::Vector3d(0, 0, roll));
  Eigen::Vector2d lo = CornerPosition(target, 0), hi = lo;
  for (const TargetCorner& c : TargetCorners(target)) lo = lo.cwiseMin(c.xy), hi = hi.cwiseMax(c.xy);
  const Eigen::Vector3d centre(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), 0);
  const Eigen::Vector3d shift(0.05 * depth * (b[1] - 0.5), 0, depth);
  return Rigid3d{R, shift - R * centre};
}

}  // namespace

Rigid3d TestViewPose(const Camera& camera, const Target& target, double square_px, int k, uint64_t seed,
                     double extra_roll_deg) {
  return ViewPose(camera, target, square_px, k, seed, extra_roll_deg, 0, 35);
}

Rigid3d HardViewPose(const Camera& camera, const Target& target, double square_px, int k, uint64_t seed) {
  return ViewPose(camera, target, square_px, k, seed, 0, 45, 60);
}

RenderedView RenderTestView(const Camera& camera, const Target& target, const Rigid3d& camera_from_board,
                            const RenderOptions& options, uint32_t view) {
  RenderedView out;
  out.camera_from_board = camera_from_board;
  out.image = RenderView(PixelCornerRays(camera), TargetPattern(target), camera_from_board, options, view);
  for (const TargetCorner& c : TargetCorners(target)) {
    const auto px = camera.Project(camera_from_board * Eigen::Vector3d(c.xy.x(), c.xy.y(), 0));
    if (px && camera.InImage(*px)) out.truth[c.id] = *px;
  }
  return out;
}

Target SpeedTestBoard() {
  Target t = Chessboard9x6();
  t.rows = t.cols = 10;
  return t;
}

std::vector<GrayImage> SpeedTestImages(int width) {
  const bool vga = width == 640;
  const Camera camera = DistortedCamera(width, vga ? 480 : 720, vga ? 600 : 1000);
  RenderOptions options;
  options.blur_px = 0.8;
  options.noise = 2;
  std::vector<GrayImage> images;
  for (int k = 0; k < 8; ++k) {
    const Rigid3d pose = TestViewPose(camera, SpeedTestBoard(), vga ? 30 : 50, k, 9);
    images.push_back(RenderTestView(camera, SpeedTestBoard(), pose, options, k).image);
  }
  return images;
}

CornerErrors CompareWithTruth(const Detection& detection, const RenderedView& view) {
  CornerErrors e;
  double sum2 = 0;
  for (const DetectedCorner& c : detection.corners) {
    const auto it = view.truth.find(c.id);
    if (it == view.truth.end()) {
      ++e.wrong_id;
      continue;
    }
    const double d = (c.pixel - it->second).norm();
    if (d > 2) {
      ++e.wrong_id;
      continue;
    }
    sum2 += d * d;
    e.max_px = std::max(e.max_px, d);
    ++e.matched;
  }
  e.rms_px = e.matched > 0 ? std::sqrt(sum2 / e.matched) : 0;
  return e;
}

}  // namespace vstcal::testing
