// Kalibr's aprilgrid (target.h): OpenCV's ArUco module finds the tag36h11 tags with their two-cell
// black border (libapriltag reads only one-cell borders); vstcal keeps this board's ids, checks
// the tags' layout against the target, refines every tag corner by point symmetry — each is an
// X-junction between the tag and the black square at its junction — and measures the blur along
// the tags' edges.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include <Eigen/Geometry>
#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>

#include "vstcal/capture/aruco_tags.h"
#include "vstcal/capture/corner_refinement.h"
#include "vstcal/capture/detect_steps.h"
#include "vstcal/capture/detectors.h"
#include "vstcal/capture/miss_diagnosis.h"
#include "vstcal/estimators/homography.h"

namespace vstcal {
namespace {

// Kalibr prints each tag turned half a turn from OpenCV's drawing (target.h): OpenCV's corner k
// (drawMarker's top-left, top-right, bottom-right, bottom-left) is the printed tag's bottom-right,
// bottom-left, top-left, top-right, i.e. MarkerQuads' corner (k + 2) mod 4.
constexpr int kQuadCorner[4] = {2, 3, 0, 1};

// Point symmetry about a tag corner holds within the tag's two-cell border and the junction
// square (and the gaps beside them, as wide as it): a disc of radius min(g, 2√2 cells) about
// the corner. The window keeps a fifth of it clear for the blur. Largest window as RefineXCorners.
constexpr double kWindowOfSymmetricDisc = 0.8;
constexpr double kMaxWindowPx = 6;
constexpr double kMaxAsymmetry = 0.25;  // as DropAsymmetricCorners

// Kalibr's corner id of MarkerQuads' corner q (top-left, top-right, bottom-right, bottom-left as
// the sheet is read) of tag `tag`: its 2 × 2 block of Kalibr's corner grid, rows counted upwards.
int CornerId(const Target& t, int tag, int q) {
  const int tr = tag / t.cols, tc = tag % t.cols, cols = 2 * t.cols;
  const int base = 2 * tr * cols + 2 * tc;  // bottom-left
  constexpr int kUp[4] = {1, 1, 0, 0}, kRight[4] = {0, 1, 1, 0};
  return base + kUp[q] * cols + kRight[q];
}

double SidePx(const std::array<Eigen::Vector2d, 4>& p) {
  return 0.25 * ((p[1] - p[0]).norm() + (p[2] - p[1]).norm() + (p[3] - p[2]).norm() + (p[0] - p[3]).norm());
}

// A tag's black border touches the junction squares at its corners, so OpenCV's contour of a tag
// can run on into a junction square and put the tag's corner at the square's far corner — the
// neighbouring tag's, one gap away — where the point-symmetry refinement, finding an X-junction,
// keeps it. Each corner is therefore predicted from the corners around it (a homography fitted to
// those within 1.6 pitches on the board, the corner left out) and dropped when it lies more than
// 0.3 of a gap from its prediction, measured on the board.
void DropCornersOffTheirPlace(const Target& t, std::vector<DetectedCorner>* corners) {
  const double pitch = (1 + t.tag_spacing) * t.tag_size, gap = t.tag_spacing * t.tag_size;
  std::vector<DetectedCorner> kept;
  for (size_t i = 0; i < corners->size(); ++i) {
    const Eigen::Vector2d here = CornerPosition(t, (*corners)[i].id);
    std::vector<Observation> around;
    for (size_t j = 0; j < corners->size(); ++j) {
      const Eigen::Vector2d there = CornerPosition(t, (*corners)[j].id);
      if (j != i && (there - here).norm() <= 1.6 * pitch) around.push_back({Eigen::Vector3d(there.x(), there.y(), 0), (*corners)[j].pixel, 1.0});
    }
    Eigen::Vector2d back;
    if (const auto H = EstimateHomography(around)) {
      back = (H->inverse() * (*corners)[i].pixel.homogeneous()).hnormalized();
    } else if (around.size() == 3) {
      // A tag alone: its other three corners fix an affine map (a small tag's perspective is slight).
      Eigen::Matrix3d pixels, board;
      for (int k = 0; k < 3; ++k) {
        pixels.col(k) = around[static_cast<size_t>(k)].pixel.homogeneous();
        board.col(k) = around[static_cast<size_t>(k)].point.head<2>().homogeneous();
      }
      if (std::abs(pixels.determinant()) < 1e-9) continue;
      back = (board * pixels.inverse() * (*corners)[i].pixel.homogeneous()).head<2>();
    } else {
      continue;  // nothing to check it against
    }
    if ((back - here).norm() <= 0.3 * gap) kept.push_back((*corners)[i]);
  }
  *corners = std::move(kept);
}

}  // namespace

Detection DetectAprilGrid(const GrayImage& image, const Target& target, const DetectorOptions& options) {
  const int num_tags = target.rows * target.cols;
  std::map<int, DetectedMarker> by_index;
  std::vector<int> repeated;
  int foreign = 0;
  // The reduced image first says whether there is anything to search: OpenCV's smallest candidate is
  // a fixed fraction of the image's size, so a quadrilateral it would consider at full resolution is
  // one in the reduced image too. None there, decoded or not: a board-less large image is refused
  // without the full search (a one-grey 100 MP image: 3.3 s of CPU for nothing).
  ArucoSearch search = FindArucoTags(image, cv::aruco::DICT_APRILTAG_36h11, kAprilGridBorderCells, MarkerSearch::kReduced);
  if (search.factor > 1 && !(search.tags.empty() && search.undecoded_sides_px.empty())) {
    search = FindArucoTags(image, cv::aruco::DICT_APRILTAG_36h11, kAprilGridBorderCells, MarkerSearch::kFullResolution);
  }
  for (const ArucoTag& tag : search.tags) {
    if (tag.id >= num_tags) {
      ++foreign;
      continue;
    }
    DetectedMarker m{tag.id, {}};
    for (int k = 0; k < 4; ++k) m.pixels[kQuadCorner[k]] = tag.corners[k];
    if (!by_index.emplace(tag.id, m).second) repeated.push_back(tag.id);
  }
  for (const int index : repeated) by_index.erase(index);  // a tag seen twice: neither can be trusted
  Detection d;
  if (by_index.empty()) {
    if (foreign > 0) {
      d.reason = std::to_string(foreign) + " tag36h11 tags, none of this aprilgrid's ids 0 … " + std::to_string(num_tags - 1);
      return d;
    }
    // A vstcal apriltag-grid (libapriltag's one-cell border) is not read with a two-cell border.
    const size_t one_cell = FindArucoTags(image, cv::aruco::DICT_APRILTAG_36h11, 1, MarkerSearch::kReduced).tags.size();
    if (one_cell > 0) {
      d.status = DetectionStatus::kRejected;
      d.reason = "another target type: " + std::to_string(one_cell) +
                 " tag36h11 tags with a one-cell black border, none with the two-cell border of Kalibr's aprilgrid; "
                 "the board looks like an apriltag-grid: set the target's type to apriltag-grid";
    } else {
      d.reason = "no tag36h11 tag with the two-cell black border of Kalibr's aprilgrid";
      if (std::string hint = MissHint(image, options, TooSmallMarkers(search.undecoded_sides_px, kAprilGridCells, "tag")); !hint.empty()) d.reason += "; " + hint;
    }
    return d;
  }
  std::vector<DetectedMarker> markers;
  for (const auto& [index, m] : by_index) markers.push_back(m);
  if (std::string mismatch = LayoutMismatch(CheckMarkerLayout(MarkerQuads(target), markers), markers, "tags", "rows and cols");
      !mismatch.empty()) {
    d.status = DetectionStatus::kRejected;
    d.reason = std::move(mismatch);
    return d;
  }
  // The symmetric disc in tag sides (see kWindowOfSymmetricDisc).
  const double symmetric = std::min(target.tag_spacing, std::sqrt(2.0) * kAprilGridBorderCells / kAprilGridCells);
  std::vector<double> blur;
  double smallest_radius = kMaxWindowPx;
  for (const DetectedMarker& m : markers) {
    const double side_px = SidePx(m.pixels);
    const double radius = std::min(kMaxWindowPx, kWindowOfSymmetricDisc * symmetric * side_px);
    smallest_radius = std::min(smallest_radius, radius);
    for (int q = 0; q < 4; ++q) {
      Eigen::Vector2d corner = m.pixels[q];
      if (options.refiner == CornerRefiner::kSymmetry && radius >= 2) {
        const auto refined = RefineCornerBySymmetry(image, corner, radius);
        if (!refined) continue;
        // Farther than half the gap from where OpenCV put it, it has reached the junction square's
        // other corner — the neighbouring tag's — and would be numbered as this one: dropped.
        if ((refined->corner - corner).norm() > 0.5 * target.tag_spacing * side_px) continue;
        corner = refined->corner;
        // Not an X-junction (occluded, in shadow, or a misdecoded tag's corner): dropped.
        const auto asymmetry = Asymmetry(image, corner, radius);
        if (!asymmetry || *asymmetry > kMaxAsymmetry) continue;
      }
      d.corners.push_back({CornerId(target, m.index, q), corner});
    }
    // Across the tag's edges: the black border is two cells wide and the white gap g.
    const double reach = 0.4 * std::min(target.tag_spacing, double(kAprilGridBorderCells) / kAprilGridCells) * side_px;
    for (int q = 0; q < 4; ++q) {
      if (const auto s = EdgeBlur(image, m.pixels[q], m.pixels[(q + 1) % 4], reach)) blur.push_back(*s);
    }
  }
  if (options.refiner == CornerRefiner::kCornerSubPix && !d.corners.empty()) {
    // One window for all corners, as RefineXCorners: the smallest.
    const int half = std::clamp(static_cast<int>(std::lround(smallest_radius)), 2, 10);
    std::vector<cv::Point2f> points;
    for (const DetectedCorner& c : d.corners) points.emplace_back(static_cast<float>(c.pixel.x()), static_cast<float>(c.pixel.y()));
    const cv::Mat gray(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
    cv::cornerSubPix(gray, points, cv::Size(half, half), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 40, 0.001));
    for (size_t k = 0; k < points.size(); ++k) d.corners[k].pixel = Eigen::Vector2d(points[k].x, points[k].y);
  }
  DropCornersOffTheirPlace(target, &d.corners);
  std::sort(d.corners.begin(), d.corners.end(), [](const DetectedCorner& a, const DetectedCorner& b) { return a.id < b.id; });
  ConcludeFound(options, std::move(blur), &d);
  return d;
}

}  // namespace vstcal
