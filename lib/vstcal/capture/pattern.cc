#include "vstcal/capture/pattern.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

// A pixel footprint has 4 vertices; each of the rectangle's four sides can add at most as many
// vertices as the polygon has crossings with it, so 32 is ample for any quadrilateral.
constexpr int kMaxVertices = 32;
using Polygon = std::array<Eigen::Vector2d, kMaxVertices>;

// Keeps the part of `in` (n vertices) where s·(p[axis] − limit) ≥ 0 (Sutherland–Hodgman).
int ClipHalfPlane(const Eigen::Vector2d* in, int n, int axis, double limit, double s, Eigen::Vector2d* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = in[i];
    const Eigen::Vector2d& b = in[(i + 1) % n];
    const double da = s * (a[axis] - limit), db = s * (b[axis] - limit);
    if (da >= 0) out[m++] = a;
    if ((da >= 0) != (db >= 0)) {
      const double f = da / (da - db);
      Eigen::Vector2d p = a + f * (b - a);
      p[axis] = limit;  // exactly on the side, whatever the rounding of f
      out[m++] = p;
    }
    VSTCAL_CHECK(m <= kMaxVertices - 2, "clipped polygon has too many vertices");
  }
  return m;
}

std::array<double, 4> Bounds(std::span<const Eigen::Vector2d> polygon) {
  std::array<double, 4> b = {polygon[0].x(), polygon[0].y(), polygon[0].x(), polygon[0].y()};
  for (const Eigen::Vector2d& p : polygon) {
    b[0] = std::min(b[0], p.x()), b[1] = std::min(b[1], p.y());
    b[2] = std::max(b[2], p.x()), b[3] = std::max(b[3], p.y());
  }
  return b;
}

bool Contains(const Rect& r, const std::array<double, 4>& b) { return b[0] >= r.x0 && b[1] >= r.y0 && b[2] <= r.x1 && b[3] <= r.y1; }
bool Disjoint(const Rect& r, const std::array<double, 4>& b) { return b[2] <= r.x0 || b[0] >= r.x1 || b[3] <= r.y0 || b[1] >= r.y1; }

// Merges rectangles of one row that touch end to end (bit cells of a marker row).
std::vector<Rect> MergeRuns(std::vector<Rect> rects) {
  std::sort(rects.begin(), rects.end(), [](const Rect& a, const Rect& b) {
    return a.y0 != b.y0 ? a.y0 < b.y0 : a.y1 != b.y1 ? a.y1 < b.y1 : a.x0 < b.x0;
  });
  std::vector<Rect> merged;
  for (const Rect& r : rects) {
    if (!merged.empty() && merged.back().y0 == r.y0 && merged.back().y1 == r.y1 && merged.back().x1 == r.x0) {
      merged.back().x1 = r.x1;
    } else {
      merged.push_back(r);
    }
  }
  return merged;
}

}  // namespace

double SignedArea(std::span<const Eigen::Vector2d> polygon) {
  double twice = 0;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % n];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

double ClippedArea(std::span<const Eigen::Vector2d> polygon, const Rect& rect) {
  VSTCAL_CHECK(polygon.size() >= 3 && polygon.size() <= 8, "polygon must have 3 to 8 vertices");
  Polygon a, b;
  int n = static_cast<int>(polygon.size());
  std::copy(polygon.begin(), polygon.end(), a.begin());
  n = ClipHalfPlane(a.data(), n, 0, rect.x0, +1, b.data());
  if (n < 3) return 0;
  n = ClipHalfPlane(b.data(), n, 0, rect.x1, -1, a.data());
  if (n < 3) return 0;
  n = ClipHalfPlane(a.data(), n, 1, rect.y0, +1, b.data());
  if (n < 3) return 0;
  n = ClipHalfPlane(b.data(), n, 1, rect.y1, -1, a.data());
  if (n < 3) return 0;
  return std::abs(SignedArea(std::span<const Eigen::Vector2d>(a.data(), n)));
}

Pattern::Pattern(Rect sheet, std::vector<Rect> black) : sheet_(sheet), black_(MergeRuns(std::move(black))) {
  VSTCAL_CHECK(sheet_.width() > 0 && sheet_.height() > 0, "empty sheet");
  double smallest = std::max(sheet_.width(), sheet_.height());
  for (const Rect& r : black_) {
    VSTCAL_CHECK(r.width() > 0 && r.height() > 0, "empty black rectangle");
    VSTCAL_CHECK(r.x0 >= sheet_.x0 && r.y0 >= sheet_.y0 && r.x1 <= sheet_.x1 && r.y1 <= sheet_.y1,
                 "black rectangle off the sheet");
    smallest = std::min({smallest, r.width(), r.height()});
  }
  // Cells about the size of the smallest rectangle, at most 2048 a side (4 M cells).
  cell_ = std::max(smallest, std::max(sheet_.width(), sheet_.height()) / 2048);
  grid_cols_ = std::max(1, static_cast<int>(std::ceil(sheet_.width() / cell_)));
  grid_rows_ = std::max(1, static_cast<int>(std::ceil(sheet_.height() / cell_)));
  cells_.assign(static_cast<size_t>(grid_cols_) * grid_rows_, {});
  auto clamp_col = [&](double x) { return std::clamp(static_cast<int>(std::floor((x - sheet_.x0) / cell_)), 0, grid_cols_ - 1); };
  auto clamp_row = [&](double y) { return std::clamp(static_cast<int>(std::floor((y - sheet_.y0) / cell_)), 0, grid_rows_ - 1); };
  for (size_t k = 0; k < black_.size(); ++k) {
    const Rect& r = black_[k];
    for (int j = clamp_row(r.y0); j <= clamp_row(r.y1); ++j) {
      for (int i = clamp_col(r.x0); i <= clamp_col(r.x1); ++i) cells_[static_cast<size_t>(j) * grid_cols_ + i].push_back(static_cast<int>(k));
    }
  }
}

double Pattern::SheetArea(std::span<const Eigen::Vector2d> polygon) const {
  const auto b = Bounds(polygon);
  if (Disjoint(sheet_, b)) return 0;
  if (Contains(sheet_, b)) return std::abs(SignedArea(polygon));
  return ClippedArea(polygon, sheet_);
}

double Pattern::BlackArea(std::span<const Eigen::Vector2d> polygon) const {
  const auto b = Bounds(polygon);
  if (Disjoint(sheet_, b)) return 0;
  auto col = [&](double x) { return std::clamp(static_cast<int>(std::floor((x - sheet_.x0) / cell_)), 0, grid_cols_ - 1); };
  auto row = [&](double y) { return std::clamp(static_cast<int>(std::floor((y - sheet_.y0) / cell_)), 0, grid_rows_ - 1); };
  const int i0 = col(b[0]), i1 = col(b[2]), j0 = row(b[1]), j1 = row(b[3]);
  double area = 0;
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      for (const int k : cells_[static_cast<size_t>(j) * grid_cols_ + i]) {
        const Rect& r = black_[k];
        // A rectangle listed in several cells counts once: in the cell holding the top-left corner
        // of its overlap with the polygon's bounding box.
        if (col(std::max(b[0], r.x0)) != i || row(std::max(b[1], r.y0)) != j) continue;
        if (Disjoint(r, b)) continue;
        if (Contains(r, b)) return std::abs(SignedArea(polygon));  // rectangles are disjoint
        area += ClippedArea(polygon, r);
      }
    }
  }
  return area;
}

}  // namespace vstcal
