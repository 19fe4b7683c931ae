// Chessboards: OpenCV finds the grid, vstcal numbers it (chessboard_orientation.h), refines it and
// measures its blur (detect_steps.h).
//
// Bounded time per image (docs/tools/calib-capture.md#time-budget). OpenCV's finders cannot be
// cancelled, so they are bounded by what they are given:
//  - they search a copy of the image box-filtered down to at most kSearchPixels (an integer factor,
//    so that a corner found there maps back exactly), and the corners are refined at full
//    resolution: a 12 MP or 100 MP image costs the finders what a 1 MP one does;
//  - the default search runs the classic finder without its adaptive-threshold passes (16 cheap
//    passes instead of 56: on a view it cannot read, the adaptive passes took up to tens of s),
//    then the sector-based finder (a Radon-transform search whose cost is set by the image size);
//  - where OpenCV's board-presence check (checkChessboard, what CALIB_CB_FAST_CHECK uses) sees no
//    board in a reduced search image, the sector-based finder searches it at half the size again.
#include <algorithm>
#include <climits>
#include <cstdio>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "vstcal/capture/chessboard_orientation.h"
#include "vstcal/capture/detect_steps.h"
#include "vstcal/capture/detectors.h"
#include "vstcal/capture/miss_diagnosis.h"
#include "vstcal/capture/search_image.h"

namespace vstcal {
namespace {

// Window of the refinement and reach of the blur profile, as fractions of the local square size:
// the four squares around a corner reach one square away, and the blur (a few px) must fit too.
constexpr double kChessboardWindow = 0.4;

bool Classic(const cv::Mat& image, const cv::Size& size, bool adaptive, std::vector<cv::Point2f>* points) {
  // Without CALIB_CB_FAST_CHECK: on images that hold a board it doubled the time and missed
  // boards of 12 px squares (docs/experiments/corners.md).
  return cv::findChessboardCorners(image, size, *points, cv::CALIB_CB_NORMALIZE_IMAGE | (adaptive ? cv::CALIB_CB_ADAPTIVE_THRESH : 0));
}

bool SectorBased(const cv::Mat& image, const cv::Size& size, std::vector<cv::Point2f>* points) {
  // Without CALIB_CB_ACCURACY: the refinement below does better, in a fraction of the time.
  return cv::findChessboardCornersSB(image, size, *points, cv::CALIB_CB_NORMALIZE_IMAGE);
}

struct Search {
  bool found = false;
  bool board_like = false;  // the presence check saw a board (only asked where the finders fail)
  std::vector<cv::Point2f> points;
  int factor = 1;  // of the image the points were found in
};

Search Find(const cv::Mat& gray, const cv::Size& size, ChessboardFinder finder) {
  const SearchImage search = ReduceForSearch(gray);
  Search s;
  s.factor = search.factor;
  switch (finder) {
    case ChessboardFinder::kClassic: s.found = Classic(search.image, size, true, &s.points); break;
    case ChessboardFinder::kSectorBased: s.found = SectorBased(search.image, size, &s.points); break;
    case ChessboardFinder::kClassicThenSectorBased:
      s.found = Classic(search.image, size, false, &s.points);
      if (s.found) break;
      s.board_like = cv::checkChessboard(search.image, size);
      // A reduced image (more than 1 MP) where the presence check sees no board is searched at
      // half the size again: a board-less 12 MP image is then refused in ≈ 0.1 s. Images of
      // 1 MP or less are searched whole (the check misses boards of small squares there).
      if (s.board_like || search.factor == 1 || !CanShrink(search.image.cols, search.image.rows, 2)) {
        s.found = SectorBased(search.image, size, &s.points);
      } else {
        const SearchImage half = Shrink(search, 2);
        s.factor = half.factor;
        s.found = SectorBased(half.image, size, &s.points);
      }
      break;
  }
  return s;
}

}  // namespace

Detection DetectChessboard(const GrayImage& image, const Target& target, const DetectorOptions& options) {
  const cv::Mat gray(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
  const cv::Size size(target.cols, target.rows);
  Detection d;
  // OpenCV's finders remap with 16-bit coordinates: a side of 32767 px or more throws inside them.
  // Only a strip too thin to reduce keeps such a side in the search image, and it holds no board.
  if (const int longest = std::max(image.width, image.height) / SearchFactor(image.width, image.height); longest >= SHRT_MAX) {
    d.reason = "no chessboard of " + std::to_string(target.cols) + "×" + std::to_string(target.rows) + " inner corners (a " +
               std::to_string(image.width) + "×" + std::to_string(image.height) + " image is searched only below 32767 px a side)";
    return d;
  }
  const Search s = Find(gray, size, options.finder);
  if (!s.found || static_cast<int>(s.points.size()) != target.rows * target.cols) {
    d.reason = "no chessboard of " + std::to_string(target.cols) + "×" + std::to_string(target.rows) + " inner corners";
    if (s.board_like) {
      d.reason += " (a board-like pattern is in view, but not all its corners were found: the board is partly outside the image, "
                  "blurred, or its squares are too small)";
    }
    if (std::string hint = MissHint(image, options, TooSmallSquares(image, s.factor)); !hint.empty()) d.reason += "; " + hint;
    return d;
  }
  std::vector<Eigen::Vector2d> grid;
  grid.reserve(s.points.size());
  for (const cv::Point2f& p : s.points) grid.push_back(ToFullResolution(s.factor, p.x, p.y));
  const GridOrientation orientation = OrientChessboard(image, target, grid, options.refuse_ambiguous_orientation);
  if (!orientation.problem.empty()) {
    d.status = DetectionStatus::kRejected;
    d.reason = orientation.problem;
    return d;
  }
  d.corners.resize(grid.size());
  for (size_t id = 0; id < grid.size(); ++id) d.corners[id] = {static_cast<int>(id), grid[orientation.detected_index[id]]};
  // Corners found in a reduced image are up to half a search pixel (factor/2 px) off: cornerSubPix,
  // whose window reaches that far, brings them within the symmetry refinement's reach.
  if (s.factor > 1 && options.refiner == CornerRefiner::kSymmetry) {
    RefineXCorners(image, target, CornerRefiner::kCornerSubPix, kChessboardWindow, &d.corners);
  }
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
