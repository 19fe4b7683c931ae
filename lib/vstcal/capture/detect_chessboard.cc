// Chessboards: OpenCV finds the grid, vstcal numbers it (chessboard_orientation.h), refines it and
// measures its blur (detect_steps.h).
#include <cstdio>

#include <opencv2/calib3d.hpp>

#include "vstcal/capture/chessboard_orientation.h"
#include "vstcal/capture/detect_steps.h"
#include "vstcal/capture/detectors.h"

namespace vstcal {

// Window of the refinement and reach of the blur profile, as fractions of the local square size:
// the four squares around a corner reach one square away, and the blur (a few px) must fit too.
constexpr double kChessboardWindow = 0.4;

Detection DetectChessboard(const GrayImage& image, const Target& target, const DetectorOptions& options) {
  const cv::Mat gray(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
  const cv::Size size(target.cols, target.rows);
  std::vector<cv::Point2f> points;
  bool found = false;
  if (options.finder != ChessboardFinder::kSectorBased) {
    // Without CALIB_CB_FAST_CHECK: on images that hold a board it doubled the time and missed
    // boards of 12 px squares (docs/experiments/corners.md).
    found = cv::findChessboardCorners(gray, size, points, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
  }
  if (!found && options.finder != ChessboardFinder::kClassic) {
    // Without CALIB_CB_ACCURACY: the refinement below does better, in a fraction of the time.
    found = cv::findChessboardCornersSB(gray, size, points, cv::CALIB_CB_NORMALIZE_IMAGE);
  }
  Detection d;
  if (!found || static_cast<int>(points.size()) != target.rows * target.cols) {
    d.reason = "no chessboard of " + std::to_string(target.cols) + "×" + std::to_string(target.rows) + " inner corners";
    return d;
  }
  std::vector<Eigen::Vector2d> grid;
  grid.reserve(points.size());
  for (const cv::Point2f& p : points) grid.emplace_back(p.x, p.y);
  const GridOrientation orientation = OrientChessboard(image, target, grid, options.refuse_ambiguous_orientation);
  if (!orientation.problem.empty()) {
    d.status = DetectionStatus::kRejected;
    d.reason = orientation.problem;
    return d;
  }
  d.corners.resize(grid.size());
  for (size_t id = 0; id < grid.size(); ++id) d.corners[id] = {static_cast<int>(id), grid[orientation.detected_index[id]]};
  RefineXCorners(image, target, options.refiner, kChessboardWindow, &d.corners);
  if (std::string lost = LostOuterLine(target, d.corners); !lost.empty()) {
    d.status = DetectionStatus::kRejected;
    d.reason = std::move(lost);
    d.corners.clear();
    return d;
  }
  d.blur_px = MedianGridEdgeBlur(image, target, d.corners, kChessboardWindow);
  d.status = DetectionStatus::kFound;
  Conclude(options, &d);
  return d;
}

}  // namespace vstcal
