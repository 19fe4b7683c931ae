#include "vstcal/capture/miss_diagnosis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "vstcal/capture/corner_refinement.h"
#include "vstcal/capture/saddle_lattice.h"
#include "vstcal/capture/search_image.h"

namespace vstcal {
namespace {

constexpr int kEdgesMeasured = 200;
constexpr int kMinEdges = 20;
constexpr int kGridCell = 16;               // search-image px: one edge candidate per cell
constexpr double kMinGradient = 4;           // grey levels a search pixel: weaker is texture or noise
constexpr size_t kMinUndecoded = 4;          // candidates before the markers are called too small

}  // namespace

std::optional<EdgeSharpness> SharpestEdgeBlur(const GrayImage& image, double reach_px) {
  const cv::Mat gray(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
  const SearchImage search = ReduceForSearch(gray);
  cv::Mat gx, gy;
  cv::Sobel(search.image, gx, CV_32F, 1, 0, 3, 1.0 / 8);  // 1/8: grey levels a pixel
  cv::Sobel(search.image, gy, CV_32F, 0, 1, 3, 1.0 / 8);
  struct Candidate {
    float strength;
    int x, y;
  };
  std::vector<Candidate> candidates;
  for (int y0 = 1; y0 + 1 < search.image.rows; y0 += kGridCell) {
    for (int x0 = 1; x0 + 1 < search.image.cols; x0 += kGridCell) {
      Candidate best{0, 0, 0};
      for (int y = y0; y < std::min(y0 + kGridCell, search.image.rows - 1); ++y) {
        for (int x = x0; x < std::min(x0 + kGridCell, search.image.cols - 1); ++x) {
          const float g = std::hypot(gx.at<float>(y, x), gy.at<float>(y, x));
          if (g > best.strength) best = {g, x, y};
        }
      }
      if (best.strength >= kMinGradient) candidates.push_back(best);
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.strength != b.strength ? a.strength > b.strength : (a.y != b.y ? a.y < b.y : a.x < b.x);
  });
  if (candidates.size() > static_cast<size_t>(kEdgesMeasured)) candidates.resize(kEdgesMeasured);
  std::vector<double> blur;
  for (const Candidate& c : candidates) {
    const Eigen::Vector2d p = ToFullResolution(search.factor, c.x, c.y);
    // EdgeBlur takes two points on the edge: along it, perpendicular to the gradient.
    const Eigen::Vector2d along = Eigen::Vector2d(-gy.at<float>(c.y, c.x), gx.at<float>(c.y, c.x)).normalized();
    if (const auto s = EdgeBlur(image, p - along, p + along, reach_px)) blur.push_back(*s);
  }
  if (blur.size() < static_cast<size_t>(kMinEdges)) return std::nullopt;
  std::sort(blur.begin(), blur.end());
  return EdgeSharpness{blur[blur.size() / 10], static_cast<int>(blur.size())};
}

std::string TooSmallMarkers(std::vector<double> undecoded_sides_px, int cells, std::string_view what) {
  if (cells <= 0 || undecoded_sides_px.size() < kMinUndecoded) return {};
  std::nth_element(undecoded_sides_px.begin(), undecoded_sides_px.begin() + static_cast<long>(undecoded_sides_px.size() / 2),
                   undecoded_sides_px.end());
  const double median = undecoded_sides_px[undecoded_sides_px.size() / 2], needed = kMinPxPerCell * cells;
  if (median >= needed) return {};
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "the %ss look too small: %zu %s-like quadrilaterals were not decoded, of %.1f px a side (median), and a %s of %d "
                "cells needs about %.0f px (%.0f px a cell); move the camera closer, or print a larger board",
                std::string(what).c_str(), undecoded_sides_px.size(), std::string(what).c_str(), median, std::string(what).c_str(), cells,
                needed, kMinPxPerCell);
  return buf;
}

std::string TooSmallSquares(const GrayImage& image, int search_factor) {
  const double needed = kMinSquareSearchPx * search_factor;
  // Links reach 1.5 × the squares read: the short axis of a board tilted 60° (foreshortened by
  // half) links a board just under the limit; the cost grows with the reach squared.
  const auto lattice = FindSaddleLattice(image, 1.5 * needed);
  if (!lattice || lattice->spacing_px >= needed) return {};
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "the squares look too small: a lattice of %d chessboard corners, squares of about %.1f px, and the chessboard finders need "
                "about %.0f px a square%s; move the camera closer, or print a larger board",
                lattice->corners, lattice->spacing_px, needed,
                search_factor > 1 ? (" in an image this large (searched reduced by " + std::to_string(search_factor) + ")").c_str() : "");
  return buf;
}

std::string MissHint(const GrayImage& image, const DetectorOptions& options, std::string too_small) {
  if (!too_small.empty()) return too_small;
  char buf[320];
  // The profile reaches far enough to see a σ somewhat above the limit (2.563 σ is the 10–90 % rise).
  if (const auto sharp = SharpestEdgeBlur(image, std::clamp(4 * options.max_blur_px, 8.0, 24.0)); sharp && sharp->sigma_px > options.max_blur_px) {
    std::snprintf(buf, sizeof buf,
                  "the image looks blurred: its sharpest edges are blurred over σ = %.2f px (the sharpest tenth of %d strong edges), "
                  "more than max_blur_px %.2f px; refocus the camera on the board, or steady it",
                  sharp->sigma_px, sharp->edges, options.max_blur_px);
    return buf;
  }
  return {};
}

}  // namespace vstcal
