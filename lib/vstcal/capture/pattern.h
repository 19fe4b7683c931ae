// A printed target as geometry: a white sheet with black axis-aligned rectangles on it, in the
// board frame (length unit; X right, Y down as printed, docs/formats.md#target). Every target
// vstcal prints — chessboard squares, ArUco and AprilTag bit cells — is such a set, so drawing
// (SVG, PNG at a DPI) and rendering through a camera share this one description.
//
// Coverage queries are exact areas: a polygon (a pixel's footprint on the board) is clipped
// against each rectangle it overlaps (Sutherland–Hodgman) and the shoelace formula gives the
// area (docs/math/rendering.md#coverage).
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

namespace vstcal {

struct Rect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // x0 < x1, y0 < y1
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
};

class Pattern {
 public:
  // `black` must be pairwise disjoint (they may share edges) and lie on the sheet; adjacent
  // cells of one row are merged into one rectangle here.
  Pattern(Rect sheet, std::vector<Rect> black);

  const Rect& sheet() const { return sheet_; }
  const std::vector<Rect>& black() const { return black_; }

  // Areas (length unit²) of a simple polygon's intersection with the black rectangles and with the
  // sheet. The polygon may be non-convex (a footprint seen nearly edge-on); vertices in order.
  double BlackArea(std::span<const Eigen::Vector2d> polygon) const;
  double SheetArea(std::span<const Eigen::Vector2d> polygon) const;

 private:
  Rect sheet_;
  std::vector<Rect> black_;
  // A uniform grid over the sheet: each cell lists the black rectangles that overlap it.
  double cell_ = 1;
  int grid_cols_ = 1, grid_rows_ = 1;
  std::vector<std::vector<int>> cells_;
};

// Signed area of a polygon (shoelace), positive for counter-clockwise vertices in a y-up frame.
double SignedArea(std::span<const Eigen::Vector2d> polygon);
// Area of polygon ∩ rect (absolute), by clipping against the rectangle's four sides.
double ClippedArea(std::span<const Eigen::Vector2d> polygon, const Rect& rect);

}  // namespace vstcal
