// ChArUco boards: OpenCV's ArUco module finds the markers and interpolates the chessboard corners
// between them; vstcal checks the markers' layout against the target, drops corners that are not
// X-junctions, refines the rest and measures the blur (detect_steps.h).
#include <cmath>
#include <cstdio>

#include <opencv2/aruco/charuco.hpp>

#include "vstcal/capture/detect_steps.h"
#include "vstcal/capture/detectors.h"

namespace vstcal {
namespace {

// The window around a ChArUco corner must stay clear of the markers' data cells: the markers'
// black borders sit symmetrically about the corner, their insides do not.
double CharucoWindow(const Target& t) {
  const MarkerFamily* family = FindMarkerFamily(ArucoDictionaries(), t.dictionary);
  const double inset = 0.5 * (t.square_size - t.marker_size), cell = t.marker_size / (family->bits + 2);
  return std::min(0.4, (inset + cell) * std::sqrt(2.0) / t.square_size);
}

}  // namespace

Detection DetectCharuco(const GrayImage& image, const Target& target, const DetectorOptions& options) {
  const cv::Mat gray(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
  const cv::Ptr<cv::aruco::Dictionary> dictionary = cv::aruco::getPredefinedDictionary(ArucoDictionaryIndex(target.dictionary));
  std::vector<std::vector<cv::Point2f>> marker_corners;
  std::vector<int> marker_ids;
  cv::aruco::detectMarkers(gray, dictionary, marker_corners, marker_ids);
  Detection d;
  const std::vector<Quad> quads = MarkerQuads(target);
  std::vector<DetectedMarker> markers;
  std::vector<std::vector<cv::Point2f>> board_corners;
  std::vector<int> board_ids;
  for (size_t k = 0; k < marker_ids.size(); ++k) {
    const int index = marker_ids[k] - target.first_id;  // the board's k-th marker has id first_id + k
    if (index < 0 || index >= static_cast<int>(quads.size())) continue;  // another board's marker
    DetectedMarker m{index, {}};
    for (int c = 0; c < 4; ++c) m.pixels[c] = Eigen::Vector2d(marker_corners[k][c].x, marker_corners[k][c].y);
    markers.push_back(m);
    board_corners.push_back(marker_corners[k]);
    board_ids.push_back(marker_ids[k]);
  }
  if (markers.empty()) {
    d.reason = marker_ids.empty() ? "no " + target.dictionary + " marker"
                                  : std::to_string(marker_ids.size()) + " " + target.dictionary + " markers, none of this board's ids " +
                                        std::to_string(target.first_id) + " … " + std::to_string(target.first_id + static_cast<int>(quads.size()) - 1) +
                                        " (the target's first_id, rows and cols)";
    return d;
  }
  const MarkerLayoutCheck layout = CheckMarkerLayout(quads, markers);
  if (std::string mismatch = LayoutMismatch(layout, markers, "markers", "rows, cols, marker_size, first_id or dictionary"); !mismatch.empty()) {
    d.status = DetectionStatus::kRejected;
    d.reason = std::move(mismatch);
    return d;
  }
  // A few markers out of place (an id misread, a marker of another board in view): without them.
  if (!layout.inconsistent.empty()) {
    std::vector<bool> drop(markers.size(), false);
    for (const auto& bad : layout.inconsistent) drop[static_cast<size_t>(bad.marker)] = true;
    std::vector<std::vector<cv::Point2f>> kept_corners;
    std::vector<int> kept_ids;
    for (size_t k = 0; k < markers.size(); ++k) {
      if (drop[k]) continue;
      kept_corners.push_back(board_corners[k]);
      kept_ids.push_back(board_ids[k]);
    }
    board_corners = std::move(kept_corners);
    board_ids = std::move(kept_ids);
  }
  const cv::Ptr<cv::aruco::CharucoBoard> board = cv::aruco::CharucoBoard::create(
      target.cols + 1, target.rows + 1, static_cast<float>(target.square_size), static_cast<float>(target.marker_size), dictionary);
  for (size_t k = 0; k < board->ids.size(); ++k) board->ids[k] = target.first_id + static_cast<int>(k);
  std::vector<cv::Point2f> corners;
  std::vector<int> ids;
  cv::aruco::interpolateCornersCharuco(board_corners, board_ids, gray, board, corners, ids);
  for (size_t k = 0; k < ids.size(); ++k) d.corners.push_back({ids[k], Eigen::Vector2d(corners[k].x, corners[k].y)});
  std::sort(d.corners.begin(), d.corners.end(), [](const DetectedCorner& a, const DetectedCorner& b) { return a.id < b.id; });
  // OpenCV has already run cornerSubPix on these (they still sit about ½ px off, down and right:
  // docs/experiments/corners.md). The symmetry refinement starts from them; then a corner around
  // which the image is not point-symmetric was interpolated from misplaced markers, and goes.
  if (options.refiner == CornerRefiner::kSymmetry) {
    const double window = CharucoWindow(target);
    RefineXCorners(image, target, CornerRefiner::kSymmetry, window, &d.corners);
    DropAsymmetricCorners(image, target, window, &d.corners);
  }
  // Across a square's edge the marker's border starts (S − m)/2 away: the profile stops short of it.
  d.blur_px = MedianGridEdgeBlur(image, target, d.corners, 0.4 * (target.square_size - target.marker_size) / target.square_size);
  d.status = DetectionStatus::kFound;
  Conclude(options, &d);
  return d;
}

}  // namespace vstcal
