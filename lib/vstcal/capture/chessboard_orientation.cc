#include "vstcal/capture/chessboard_orientation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "vstcal/image/image_sampling.h"
#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal {
namespace {

// Squares darker than the others by less than this (grey levels) do not tell the colours apart.
constexpr double kMinContrast = 8;

// The eight symmetries of a grid: (r, c) of the numbering → (r, c) of the detected grid. The
// four that transpose exist only for square grids.
std::array<int, 2> Map(int symmetry, int r, int c, int rows, int cols) {
  switch (symmetry) {
    case 0: return {r, c};
    case 1: return {r, cols - 1 - c};
    case 2: return {rows - 1 - r, c};
    case 3: return {rows - 1 - r, cols - 1 - c};
    case 4: return {c, r};
    case 5: return {c, rows - 1 - r};
    case 6: return {cols - 1 - c, r};
    default: return {cols - 1 - c, rows - 1 - r};
  }
}

// Mean grey of a quadrilateral's centre: 3 × 3 bilinear samples at 30, 50 and 70 % of its sides.
double QuadMean(const GrayImage& image, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                const Eigen::Vector2d& d) {
  double sum = 0;
  for (const double s : {0.3, 0.5, 0.7}) {
    for (const double t : {0.3, 0.5, 0.7}) {
      const Eigen::Vector2d p = (1 - s) * (1 - t) * a + s * (1 - t) * b + s * t * c + (1 - s) * t * d;
      sum += SampleBilinear(image, p);
    }
  }
  return sum / 9;
}

double AngleDeg(const Eigen::Vector2d& v) { return RadToDeg(std::atan2(v.y(), v.x())); }

}  // namespace

GridOrientation OrientChessboard(const GrayImage& image, const Target& target, const std::vector<Eigen::Vector2d>& grid,
                                 bool refuse_ambiguous, double ambiguity_deg) {
  const int rows = target.rows, cols = target.cols;
  VSTCAL_CHECK(static_cast<int>(grid.size()) == rows * cols, "grid size does not match the target");
  auto at = [&](int symmetry, int r, int c) -> const Eigen::Vector2d& {
    const auto [dr, dc] = Map(symmetry, r, c, rows, cols);
    return grid[static_cast<size_t>(dr) * cols + dc];
  };
  struct Candidate {
    int symmetry;
    double x_axis_deg;
  };
  // Every square of the detected grid read once; a numbering only decides which are "even".
  std::vector<double> square_mean(static_cast<size_t>(rows - 1) * (cols - 1));
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = 0; c + 1 < cols; ++c) {
      const auto g = [&](int rr, int cc) -> const Eigen::Vector2d& { return grid[static_cast<size_t>(rr) * cols + cc]; };
      square_mean[static_cast<size_t>(r) * (cols - 1) + c] = QuadMean(image, g(r, c), g(r, c + 1), g(r + 1, c + 1), g(r + 1, c));
    }
  }
  std::vector<Candidate> candidates;
  double best_contrast = 0;
  for (int symmetry = 0; symmetry < (rows == cols ? 8 : 4); ++symmetry) {
    const Eigen::Vector2d x_axis = at(symmetry, 0, cols - 1) - at(symmetry, 0, 0);
    const Eigen::Vector2d y_axis = at(symmetry, rows - 1, 0) - at(symmetry, 0, 0);
    if (x_axis.x() * y_axis.y() - x_axis.y() * y_axis.x() <= 0) continue;  // mirrored
    double even = 0, odd = 0;
    int n_even = 0, n_odd = 0;
    for (int r = 0; r + 1 < rows; ++r) {
      for (int c = 0; c + 1 < cols; ++c) {
        // This numbering's square (r, c)–(r + 1, c + 1) is the detected square between the images
        // of those two corners.
        const auto a = Map(symmetry, r, c, rows, cols), b = Map(symmetry, r + 1, c + 1, rows, cols);
        const double mean = square_mean[static_cast<size_t>(std::min(a[0], b[0])) * (cols - 1) + std::min(a[1], b[1])];
        ((r + c) % 2 == 0 ? even : odd) += mean;
        ++((r + c) % 2 == 0 ? n_even : n_odd);
      }
    }
    const double contrast = odd / n_odd - even / n_even;  // CheckTarget: at least 2 × 3 corners, both colours inside
    best_contrast = std::max(best_contrast, std::abs(contrast));
    if (contrast < kMinContrast) continue;
    candidates.push_back({symmetry, AngleDeg(x_axis)});
  }
  GridOrientation out;
  if (candidates.empty()) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "orientation ambiguous: black and white squares differ by %.0f grey levels only", best_contrast);
    out.problem = buf;
    return out;
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::abs(a.x_axis_deg) != std::abs(b.x_axis_deg) ? std::abs(a.x_axis_deg) < std::abs(b.x_axis_deg) : a.symmetry < b.symmetry;
  });
  const Candidate& best = candidates.front();
  if (candidates.size() > 1 && refuse_ambiguous) {
    // The boundary lies halfway between the two numberings' X axes.
    const double boundary = 0.5 * (std::abs(best.x_axis_deg) + std::abs(candidates[1].x_axis_deg));
    if (boundary - std::abs(best.x_axis_deg) < ambiguity_deg) {
      char buf[240];
      std::snprintf(buf, sizeof buf,
                    "orientation ambiguous: the board looks the same turned by %s, and its rows run at %.0f° in the image, "
                    "within %.0f° of the %.0f° where the numbering flips",
                    candidates.size() > 2 ? "quarter turns" : "a half turn", best.x_axis_deg, ambiguity_deg, boundary);
      out.problem = buf;
      return out;
    }
  }
  out.x_axis_deg = best.x_axis_deg;
  out.detected_index.resize(static_cast<size_t>(rows) * cols);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const auto [dr, dc] = Map(best.symmetry, r, c, rows, cols);
      out.detected_index[static_cast<size_t>(r) * cols + c] = dr * cols + dc;
    }
  }
  return out;
}

}  // namespace vstcal
