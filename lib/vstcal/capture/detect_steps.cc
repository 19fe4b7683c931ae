#include "vstcal/capture/detect_steps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "vstcal/capture/corner_refinement.h"
#include "vstcal/estimators/homography.h"

namespace vstcal {
namespace {

constexpr double kStepsMaxWindowPx = 6;
constexpr double kStepsMaxAsymmetry = 0.25;

// corner id → index into `corners`, −1 where not detected.
std::vector<int> IndexById(const Target& target, const std::vector<DetectedCorner>& corners) {
  std::vector<int> index(NumCorners(target), -1);
  for (size_t k = 0; k < corners.size(); ++k) index[corners[k].id] = static_cast<int>(k);
  return index;
}

}  // namespace

std::vector<double> NeighbourSpacing(const Target& target, const std::vector<DetectedCorner>& corners) {
  const std::vector<int> index = IndexById(target, corners);
  std::vector<double> spacing(corners.size(), std::numeric_limits<double>::infinity());
  for (size_t k = 0; k < corners.size(); ++k) {
    const int id = corners[k].id, r = id / target.cols, c = id % target.cols;
    for (const auto& [dr, dc] : {std::pair{0, 1}, {0, -1}, {1, 0}, {-1, 0}}) {
      const int rr = r + dr, cc = c + dc;
      if (rr < 0 || cc < 0 || rr >= target.rows || cc >= target.cols) continue;
      const int j = index[rr * target.cols + cc];
      if (j >= 0) spacing[k] = std::min(spacing[k], (corners[j].pixel - corners[k].pixel).norm());
    }
  }
  return spacing;
}

int RefineXCorners(const GrayImage& image, const Target& target, CornerRefiner refiner, double window_fraction,
                   std::vector<DetectedCorner>* corners) {
  if (refiner == CornerRefiner::kNone || corners->empty()) return 0;
  const std::vector<double> spacing = NeighbourSpacing(target, *corners);
  if (refiner == CornerRefiner::kCornerSubPix) {
    const double smallest = *std::min_element(spacing.begin(), spacing.end());
    const int half = std::clamp(static_cast<int>(std::lround(window_fraction * (std::isfinite(smallest) ? smallest : 10))), 2, 10);
    std::vector<cv::Point2f> points;
    for (const DetectedCorner& c : *corners) points.emplace_back(static_cast<float>(c.pixel.x()), static_cast<float>(c.pixel.y()));
    const cv::Mat gray(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
    cv::cornerSubPix(gray, points, cv::Size(half, half), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 40, 0.001));
    for (size_t k = 0; k < points.size(); ++k) (*corners)[k].pixel = Eigen::Vector2d(points[k].x, points[k].y);
    return 0;
  }
  std::vector<DetectedCorner> kept;
  kept.reserve(corners->size());
  for (size_t k = 0; k < corners->size(); ++k) {
    const double radius = std::min(kStepsMaxWindowPx, window_fraction * (std::isfinite(spacing[k]) ? spacing[k] : 10));
    if (radius < 2) {  // squares of 5 px or less: nothing to refine with
      kept.push_back((*corners)[k]);
      continue;
    }
    if (const auto refined = RefineCornerBySymmetry(image, (*corners)[k].pixel, radius)) {
      kept.push_back({(*corners)[k].id, refined->corner});
    }
  }
  const int dropped = static_cast<int>(corners->size() - kept.size());
  *corners = std::move(kept);
  return dropped;
}

int DropAsymmetricCorners(const GrayImage& image, const Target& target, double window_fraction,
                          std::vector<DetectedCorner>* corners) {
  const std::vector<double> spacing = NeighbourSpacing(target, *corners);
  std::vector<DetectedCorner> kept;
  for (size_t k = 0; k < corners->size(); ++k) {
    const double radius = std::min(kStepsMaxWindowPx, window_fraction * (std::isfinite(spacing[k]) ? spacing[k] : 10));
    const auto asymmetry = Asymmetry(image, (*corners)[k].pixel, std::max(radius, 2.0));
    if (asymmetry && *asymmetry <= kStepsMaxAsymmetry) kept.push_back((*corners)[k]);
  }
  const int dropped = static_cast<int>(corners->size() - kept.size());
  *corners = std::move(kept);
  return dropped;
}

double MedianGridEdgeBlur(const GrayImage& image, const Target& target, const std::vector<DetectedCorner>& corners,
                          double reach_fraction) {
  const std::vector<int> index = IndexById(target, corners);
  std::vector<std::pair<int, int>> edges;
  for (const DetectedCorner& c : corners) {
    const int r = c.id / target.cols, col = c.id % target.cols;
    if (col + 1 < target.cols && index[c.id + 1] >= 0) edges.emplace_back(index[c.id], index[c.id + 1]);
    if (r + 1 < target.rows && index[c.id + target.cols] >= 0) edges.emplace_back(index[c.id], index[c.id + target.cols]);
  }
  // 20 edges spread over the board, profiles reaching at most 8 px each side: enough for the
  // σ ≈ 4 px blur of a view to be rejected, at a fraction of the detection's cost.
  std::vector<double> blur;
  const size_t step = std::max<size_t>(1, edges.size() / 20);
  for (size_t k = 0; k < edges.size(); k += step) {
    const Eigen::Vector2d& a = corners[edges[k].first].pixel;
    const Eigen::Vector2d& b = corners[edges[k].second].pixel;
    if (const auto s = EdgeBlur(image, a, b, std::min(8.0, reach_fraction * (b - a).norm()))) blur.push_back(*s);
  }
  if (blur.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(blur.begin(), blur.begin() + blur.size() / 2, blur.end());
  return blur[blur.size() / 2];
}

std::string LostOuterLine(const Target& t, const std::vector<DetectedCorner>& corners) {
  if (corners.empty()) return {};
  std::vector<int> per_row(static_cast<size_t>(t.rows), 0), per_col(static_cast<size_t>(t.cols), 0);
  for (const DetectedCorner& c : corners) {
    ++per_row[static_cast<size_t>(c.id / t.cols)];
    ++per_col[static_cast<size_t>(c.id % t.cols)];
  }
  std::string line;
  if (per_row.front() == 0 || per_row.back() == 0) line = "an outer row";
  if (per_col.front() == 0 || per_col.back() == 0) line = "an outer column";
  if (line.empty()) return {};
  return "grid off the board: " + line + " of the grid found has no corner of the board (part of the board is outside the image, and "
         "its edge was taken for a row of corners); left out rather than numbered wrongly";
}

MarkerLayoutCheck CheckMarkerLayout(const std::vector<std::array<Eigen::Vector2d, 4>>& board_quads, const std::vector<DetectedMarker>& markers) {
  auto centre = [](const std::array<Eigen::Vector2d, 4>& q) { return 0.25 * (q[0] + q[1] + q[2] + q[3]); };
  double pitch = std::numeric_limits<double>::infinity();
  for (size_t i = 1; i < board_quads.size(); ++i) pitch = std::min(pitch, (centre(board_quads[i]) - centre(board_quads[0])).norm());
  MarkerLayoutCheck check;
  for (size_t m = 0; m < markers.size(); ++m) {
    const Eigen::Vector2d here = centre(board_quads[markers[m].index]);
    std::vector<Observation> around;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (size_t n = 0; n < markers.size(); ++n) {
      if (n == m || (centre(board_quads[markers[n].index]) - here).norm() > 2.1 * pitch) continue;
      for (int k = 0; k < 4; ++k) {
        const Eigen::Vector2d& b = board_quads[markers[n].index][k];
        around.push_back({Eigen::Vector3d(b.x(), b.y(), 0), markers[n].pixels[k], 1.0});
        mean += b;
      }
    }
    const auto H = EstimateHomography(around);
    if (!H) continue;
    ++check.checkable;
    mean /= static_cast<double>(around.size());
    double spread2 = 0;
    for (const Observation& o : around) spread2 += (o.point.head<2>() - mean).squaredNorm();
    const double spread = std::sqrt(spread2 / static_cast<double>(around.size()));
    const std::array<Eigen::Vector2d, 4>& pixels = markers[m].pixels;
    const double size_px = std::sqrt(std::max(0.0, 0.5 * std::abs((pixels[2] - pixels[0]).x() * (pixels[3] - pixels[1]).y() -
                                                                  (pixels[2] - pixels[0]).y() * (pixels[3] - pixels[1]).x())));
    double error = 0;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p = *H * board_quads[markers[m].index][k].homogeneous();
      error += 0.25 * (p.hnormalized() - pixels[k]).norm();
    }
    const double tolerance = 0.25 * size_px * std::max(1.0, (here - mean).norm() / std::max(spread, 1e-12));
    if (!(error <= tolerance)) check.inconsistent.push_back({static_cast<int>(m), error, tolerance});
  }
  std::sort(check.inconsistent.begin(), check.inconsistent.end(),
            [](const auto& a, const auto& b) { return a.error_px / a.tolerance_px > b.error_px / b.tolerance_px; });
  return check;
}

std::string DescribeDisagreements(const MarkerLayoutCheck& check, const std::vector<DetectedMarker>& markers, size_t shown) {
  std::string text = check.inconsistent.size() == 1 ? "id " : "ids ";
  char buf[96];
  for (size_t i = 0; i < std::min(shown, check.inconsistent.size()); ++i) {
    const auto& d = check.inconsistent[i];
    std::snprintf(buf, sizeof buf, "%s%d (%.1f px off, tolerance %.1f px)", i == 0 ? "" : ", ", markers[static_cast<size_t>(d.marker)].index,
                  d.error_px, d.tolerance_px);
    text += buf;
  }
  if (check.inconsistent.size() > shown) text += " and " + std::to_string(check.inconsistent.size() - shown) + " more";
  return text;
}

std::string LayoutMismatch(const MarkerLayoutCheck& check, const std::vector<DetectedMarker>& markers, const std::string& kind,
                           const std::string& fields) {
  if (check.checkable == 0 || 2 * check.inconsistent.size() <= static_cast<size_t>(check.checkable)) return {};
  return "layout mismatch: " + kind + " not where the target file puts them (" + std::to_string(check.inconsistent.size()) + " of " +
         std::to_string(check.checkable) + " disagree with their neighbours: " + DescribeDisagreements(check, markers) + "); the target's " +
         fields + " do not match the board";
}

void ConcludeFound(const DetectorOptions& options, std::vector<double> edge_blurs, Detection* d) {
  if (!edge_blurs.empty()) {
    std::nth_element(edge_blurs.begin(), edge_blurs.begin() + static_cast<long>(edge_blurs.size() / 2), edge_blurs.end());
    d->blur_px = edge_blurs[edge_blurs.size() / 2];
  }
  d->status = DetectionStatus::kFound;
  Conclude(options, d);
}

void Conclude(const DetectorOptions& options, Detection* d) {
  if (d->status != DetectionStatus::kFound) return;
  char buf[200];
  if (static_cast<int>(d->corners.size()) < options.min_corners) {
    std::snprintf(buf, sizeof buf, "too few corners: %zu, fewer than %d", d->corners.size(), options.min_corners);
    d->status = DetectionStatus::kRejected;
    d->reason = buf;
  } else if (d->blur_px > options.max_blur_px) {
    std::snprintf(buf, sizeof buf, "blurred: edges blurred over σ = %.2f px, more than %.2f px", d->blur_px, options.max_blur_px);
    d->status = DetectionStatus::kRejected;
    d->reason = buf;
  }
}

}  // namespace vstcal
