// Rendered captures shared by the capture tests and benchmarks: standard targets, cameras and
// views of them with the true corner of every id (the truth comes from Camera::Project of the
// target's corner positions, independent of any detector).
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "vstcal/camera/camera.h"
#include "vstcal/capture/detect.h"
#include "vstcal/image/image.h"
#include "vstcal/capture/render.h"
#include "vstcal/capture/target.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal::testing {

// A 9×6 chessboard of 25 mm squares (OpenCV's sample board), one square of margin.
Target Chessboard9x6();
// A 7×5 ChArUco board of 30 mm squares with 22.5 mm DICT_5X5_100 markers.
Target Charuco7x5();
// A 6×4 tag36h11 grid of 30 mm tags, 7.5 mm apart.
Target AprilGrid6x4();
// Kalibr's aprilgrid of 6×4 tag36h11 tags, 30 mm, spacing 0.3 (its two-cell black border).
Target KalibrAprilGrid6x4();

// A pinhole camera with fx = fy = f and the principal point at the image centre.
Camera PinholeCamera(int width, int height, double f);
// The same with barrel distortion (k1 −0.12, k2 0.03, p1 4e-4, p2 −3e-4).
Camera DistortedCamera(int width, int height, double f);

struct RenderedView {
  GrayImage image;
  Rigid3d camera_from_board;
  std::map<int, Eigen::Vector2d> truth;  // corner id → true pixel, corners inside the image
};

// View k of a family of poses: the target's corner centre straight ahead at the depth where a
// square (or tag) spans about `square_px` pixels, tilted by up to 35° and rolled by up to ±30°
// (plus `extra_roll_deg`), all from Philox draws keyed by (seed, k).
Rigid3d TestViewPose(const Camera& camera, const Target& target, double square_px, int k, uint64_t seed,
                     double extra_roll_deg = 0);
// The same family tilted by 45° to 60° (the hard views of bench_capture and the bounded-time tests).
Rigid3d HardViewPose(const Camera& camera, const Target& target, double square_px, int k, uint64_t seed);
RenderedView RenderTestView(const Camera& camera, const Target& target, const Rigid3d& camera_from_board,
                            const RenderOptions& options, uint32_t view);

// The speed-test images of bench_capture and scripts/bench-capture: a 10×10-corner chessboard of
// 25 mm squares (a board mrgingham reads too) through DistortedCamera at 640×480 (f 600, squares
// ≈ 30 px) or 1280×720 (f 1000, ≈ 50 px), 8 views with blur σ 0.8 px and noise σ 2.
Target SpeedTestBoard();
std::vector<GrayImage> SpeedTestImages(int width);

struct CornerErrors {
  double rms_px = 0;
  double max_px = 0;
  int matched = 0;   // detected corners with a true pixel
  int wrong_id = 0;  // detected corners more than 2 px from their id's true pixel
};
CornerErrors CompareWithTruth(const Detection& detection, const RenderedView& view);

}  // namespace vstcal::testing
