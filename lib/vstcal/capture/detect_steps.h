// The steps every detector of detect.h shares once a library has found candidate corners:
// refinement, the blur measure, the symmetry check that a corner really is an X-junction, and the
// marker-layout check that markers sit where the target file puts them. Internal to the capture
// module (tested through DetectTarget and directly in tests/unit/capture_detect_test.cc).
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/capture/detect.h"

namespace vstcal {

// The distance from each corner to its nearest detected grid neighbour (ids r·cols + c, one
// step along a row or a column), px; `corners` by increasing id. Infinity where none is detected.
std::vector<double> NeighbourSpacing(const Target& target, const std::vector<DetectedCorner>& corners);

// Refines X-junction corners in place with `refiner`; a window of `window_fraction` × the local
// spacing (at most 8 px). Corners whose refinement fails are removed (and counted in the return
// value). kCornerSubPix uses one window for all corners: the smallest.
int RefineXCorners(const GrayImage& image, const Target& target, CornerRefiner refiner, double window_fraction,
                   std::vector<DetectedCorner>* corners);

// Removes corners around which the image is not point-symmetric (not an X-junction: a
// corner interpolated from markers that are not where the target says, or a corner in shadow):
// RMS of L(c + p) − L(c − p) above 25 % of the window's contrast. Returns how many were removed.
int DropAsymmetricCorners(const GrayImage& image, const Target& target, double window_fraction,
                          std::vector<DetectedCorner>* corners);

// Median edge blur σ over about 20 grid edges between detected neighbours (chessboard and
// ChArUco), profiles reaching reach_fraction × the edge, at most 8 px; NaN when none was measured.
double MedianGridEdgeBlur(const GrayImage& image, const Target& target, const std::vector<DetectedCorner>& corners,
                          double reach_fraction);

// A detected square marker: its id on the board (0-based index into `board_quads`) and its four
// image corners in the order of its board quad (top-left, top-right, bottom-right, bottom-left).
struct DetectedMarker {
  int index = 0;
  std::array<Eigen::Vector2d, 4> pixels;
};
// Markers whose neighbours (board distance ≤ 1.6 pitches) are not where the marker's own
// homography puts them, to within a quarter of the marker's size in the image. A layout that
// does not match the board (rows and cols swapped, another board) fails nearly every marker.
// Returns how many of the markers that have a neighbour disagree, and how many have one.
std::pair<int, int> InconsistentMarkers(const std::vector<std::array<Eigen::Vector2d, 4>>& board_quads,
                                        const std::vector<DetectedMarker>& markers);

// Status from the corners found: rejected with too few corners or too much blur; found otherwise.
void Conclude(const DetectorOptions& options, Detection* detection);

}  // namespace vstcal
