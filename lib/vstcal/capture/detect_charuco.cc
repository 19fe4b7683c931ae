// ChArUco boards: OpenCV's ArUco module finds the markers and interpolates the chessboard corners
// between them; vstcal checks the markers' layout against the target, drops corners that are not
// X-junctions, refines the rest and measures the blur (detect_steps.h).
#include <cmath>
#include <cstdio>

#include <opencv2/aruco/charuco.hpp>

#include "vstcal/capture/aruco_tags.h"
#include "vstcal/capture/detect_steps.h"
#include "vstcal/capture/detectors.h"
#include "vstcal/capture/miss_diagnosis.h"

namespace vstcal {
namespace {

// The window around a ChArUco corner must stay clear of the markers' data cells: the markers'
// black borders sit symmetrically about the corner, their insides do not.
double CharucoWindow(const Target& t) {
  const MarkerFamily* family = FindMarkerFamily(ArucoDictionaries(), t.dictionary);
  const double inset = 0.5 * (t.square_size - t.marker_size), cell = t.marker_size / (family->bits + 2);
  return std::min(0.4, (inset + cell) * std::sqrt(2.0) / t.square_size);
}

// The board OpenCV interpolates the corners with. OpenCV 4.6 (Debian bookworm) has no
// CharucoBoard::setLegacyPattern (4.8 on), so a legacy board whose colours swap (target.h,
// IsBlackSquare) is built from OpenCV's current one: rows 1 … of a current board with one square
// row more start white, as the legacy board, and hold its markers in its order. That board's first
// row of markers gets ids no image holds (negative), so the corners between them and the first
// real row have one marker at most and OpenCV returns none of them (minMarkers 2); its corner id
// is the target's plus one row of corners.
struct InterpolationBoard {
  cv::Ptr<cv::aruco::CharucoBoard> board;
  int corner_offset = 0;  // OpenCV's corner id − the target's
};

InterpolationBoard MakeInterpolationBoard(const Target& t, const cv::Ptr<cv::aruco::Dictionary>& dictionary) {
  const bool shifted = !IsBlackSquare(t, 0, 0);
  InterpolationBoard b;
  b.board = cv::aruco::CharucoBoard::create(t.cols + 1, t.rows + 1 + (shifted ? 1 : 0), static_cast<float>(t.square_size),
                                            static_cast<float>(t.marker_size), dictionary);
  const int extra = shifted ? (t.cols + 1) / 2 : 0;  // the added row's markers: its odd squares
  for (int k = 0; k < static_cast<int>(b.board->ids.size()); ++k) b.board->ids[k] = k < extra ? -1 - k : t.first_id + k - extra;
  b.corner_offset = shifted ? t.cols : 0;
  return b;
}

// Where the markers disagree with the target's layout but agree with the other of OpenCV's two
// patterns (current and legacy, which differ only with an even number of square rows), the board
// was printed in that pattern: the fix is the target's legacy field, not its rows or cols.
std::string OtherPatternFits(const Target& target, const MarkerLayoutCheck& layout, const std::vector<DetectedMarker>& markers) {
  Target other = target;
  other.legacy = !target.legacy;
  if (IsBlackSquare(other, 0, 0) == IsBlackSquare(target, 0, 0)) return {};
  const MarkerLayoutCheck check = CheckMarkerLayout(MarkerQuads(other), markers);
  if (check.checkable == 0 || !LayoutMismatch(check, markers, "markers", "").empty()) return {};
  char counts[160];
  std::snprintf(counts, sizeof counts, "%zu of %d markers disagree with the target file's pattern, %zu of %d with the other", layout.inconsistent.size(),
                layout.checkable, check.inconsistent.size(), check.checkable);
  return target.legacy ? std::string("pattern mismatch: the markers sit where OpenCV's current ChArUco pattern puts them (top-left square "
                                     "black, OpenCV 4.6 and later), not where the target's legacy pattern does (") +
                             counts + "); set the target's legacy to false"
                       : std::string("pattern mismatch: the markers sit where OpenCV's legacy ChArUco pattern puts them (top-left square "
                                     "white: boards of an even number of square rows drawn before OpenCV 4.6), not where the target file does (") +
                             counts + "); set the target's legacy to true";
}

}  // namespace

Detection DetectCharuco(const GrayImage& image, const Target& target, const DetectorOptions& options) {
  const cv::Mat gray(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
  const int dictionary_index = ArucoDictionaryIndex(target.dictionary);
  const cv::Ptr<cv::aruco::Dictionary> dictionary = cv::aruco::getPredefinedDictionary(dictionary_index);
  // In an image above 1 MP the markers are found in a reduced copy (search_image.h); OpenCV then
  // interpolates the corners between them, and cornerSubPix's them, at full resolution.
  const ArucoSearch search = FindArucoTags(image, dictionary_index, 1, MarkerSearch::kReduced);
  const std::vector<ArucoTag>& found = search.tags;
  Detection d;
  const std::vector<Quad> quads = MarkerQuads(target);
  std::vector<DetectedMarker> markers;
  std::vector<std::vector<cv::Point2f>> board_corners;
  std::vector<int> board_ids;
  for (const ArucoTag& tag : found) {
    const int index = tag.id - target.first_id;  // the board's k-th marker has id first_id + k
    if (index < 0 || index >= static_cast<int>(quads.size())) continue;  // another board's marker
    markers.push_back(DetectedMarker{index, tag.corners});
    board_corners.emplace_back();
    for (const Eigen::Vector2d& p : tag.corners) board_corners.back().emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
    board_ids.push_back(tag.id);
  }
  if (markers.empty()) {
    d.reason = found.empty() ? "no " + target.dictionary + " marker"
                             : std::to_string(found.size()) + " " + target.dictionary + " markers, none of this board's ids " +
                                        std::to_string(target.first_id) + " … " + std::to_string(target.first_id + static_cast<int>(quads.size()) - 1) +
                                        " (the target's first_id, rows and cols)";
    const MarkerFamily* family = FindMarkerFamily(ArucoDictionaries(), target.dictionary);
    if (std::string hint = MissHint(image, options, TooSmallMarkers(search.undecoded_sides_px, family->bits + 2, "marker")); !hint.empty()) d.reason += "; " + hint;
    return d;
  }
  const MarkerLayoutCheck layout = CheckMarkerLayout(quads, markers);
  if (std::string mismatch = LayoutMismatch(layout, markers, "markers", "rows, cols, marker_size, first_id, legacy or dictionary"); !mismatch.empty()) {
    d.status = DetectionStatus::kRejected;
    std::string other = OtherPatternFits(target, layout, markers);
    d.reason = other.empty() ? std::move(mismatch) : std::move(other);
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
  const InterpolationBoard board = MakeInterpolationBoard(target, dictionary);
  std::vector<cv::Point2f> corners;
  std::vector<int> ids;
  cv::aruco::interpolateCornersCharuco(board_corners, board_ids, gray, board.board, corners, ids);
  for (size_t k = 0; k < ids.size(); ++k) {
    const int id = ids[k] - board.corner_offset;
    if (id >= 0 && id < NumCorners(target)) d.corners.push_back({id, Eigen::Vector2d(corners[k].x, corners[k].y)});
  }
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
