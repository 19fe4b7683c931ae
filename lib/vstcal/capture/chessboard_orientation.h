// Which detected chessboard corner is which: OpenCV's detectors return a rows × cols grid in an
// order of their own, possibly mirrored or turned by a half (a quarter, for square boards) turn
// from one image to the next. This numbers the grid in the target's board frame
// (docs/tools/calib-capture.md#orientation):
//  1. handedness: a board seen from the front keeps its frame's handedness in the image, so the
//     numbering must have cross(X axis, Y axis) > 0 in pixel coordinates (v down);
//  2. colour: the squares with r + c even (between corners (r, c) and (r + 1, c + 1)) are black
//     (the top-left square of the target is black), so they must be darker than the others;
//  3. what is left is the board's own symmetry: a half turn when rows + cols is even, a quarter
//     turn too when rows = cols. Only the view can pick then: the numbering whose X axis points
//     closest to +u (right in the image). A view whose X axis lies within `ambiguity_deg` of the
//     boundary between two such numberings is ambiguous: a calibration volume (one world frame
//     for every view) refuses it, planar views (one pose per view) take the closest numbering.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/image/image.h"
#include "vstcal/capture/target.h"

namespace vstcal {

struct GridOrientation {
  // corner id (r·cols + c) → index into the detected grid; empty when `problem` is set.
  std::vector<int> detected_index;
  std::string problem;  // why no numbering can be trusted (e.g. "orientation ambiguous: …")
  double x_axis_deg = 0;  // direction of the chosen X axis in the image, from +u towards +v
};

// `grid`: rows·cols pixels in the detector's order (row-major, `cols` to a row). `refuse_ambiguous`
// for views that share one world frame (a calibration volume).
GridOrientation OrientChessboard(const GrayImage& image, const Target& target, const std::vector<Eigen::Vector2d>& grid,
                                 bool refuse_ambiguous, double ambiguity_deg = 15);

}  // namespace vstcal
