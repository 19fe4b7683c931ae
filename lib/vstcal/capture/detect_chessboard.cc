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

namespace vstcal {
namespace {

// Window of the refinement and reach of the blur profile, as fractions of the local square size:
// the four squares around a corner reach one square away, and the blur (a few px) must fit too.
constexpr double kChessboardWindow = 0.4;
// The largest image the finders search (1280×720 and smaller are searched as they are). The
// sector-based finder takes 0.1–0.7 s of one core on a 1 MP image.
constexpr double kSearchPixels = 1.0e6;

// An image the finders search: `factor` × `factor` full-resolution pixels averaged into each of
// its pixels. Its pixel (x, y) is centred on full-resolution pixel factor·(x, y) + (factor − 1)/2.
struct SearchImage {
  cv::Mat image;
  int factor = 1;
};

SearchImage Shrink(const SearchImage& from, int by) {
  if (by <= 1) return from;
  SearchImage out;
  out.factor = from.factor * by;
  // Cropped to whole blocks, so that INTER_AREA is the exact box average of each block.
  const cv::Mat whole = from.image(cv::Rect(0, 0, from.image.cols / by * by, from.image.rows / by * by));
  cv::resize(whole, out.image, cv::Size(whole.cols / by, whole.rows / by), 0, 0, cv::INTER_AREA);
  return out;
}

// Reduced images keep at least this many pixels a side (a strip of an image stays searchable).
constexpr int kMinSearchSide = 8;

bool CanShrink(int width, int height, int by) { return width / by >= kMinSearchSide && height / by >= kMinSearchSide; }

// The smallest integer factor that brings the image to at most kSearchPixels.
int SearchFactor(int width, int height) {
  int f = 1;
  while (static_cast<double>(width / f) * (height / f) > kSearchPixels && CanShrink(width, height, f + 1)) ++f;
  return f;
}

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
  const SearchImage full{gray, 1};
  const SearchImage search = Shrink(full, SearchFactor(gray.cols, gray.rows));
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
    return d;
  }
  std::vector<Eigen::Vector2d> grid;
  grid.reserve(s.points.size());
  const double offset = 0.5 * (s.factor - 1);
  for (const cv::Point2f& p : s.points) grid.emplace_back(s.factor * p.x + offset, s.factor * p.y + offset);
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
