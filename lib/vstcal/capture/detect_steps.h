// The steps every detector of detect.h shares once a library has found candidate corners:
// refinement, the blur measure, the symmetry check that a corner really is an X-junction, and the
// marker-layout check that markers sit where the target file puts them. Internal to the capture
// module (tested through DetectTarget and directly in tests/unit/capture_detect_test.cc).
#pragma once

#include <array>
#include <string>
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

// Why a refined chessboard grid cannot be numbered, or empty. Where a row of the board is outside
// the image, OpenCV's finders can return a full grid that takes the board's outer edge (its black
// squares against the white margin) for the missing row: the refinement drops those points, which
// are no X-junctions, and the colour rule — the grid one row off — has numbered the rest turned by
// a half. An outer row or column that lost every corner while the rest kept theirs is that grid.
std::string LostOuterLine(const Target& target, const std::vector<DetectedCorner>& corners);

// A detected square marker: its id on the board (0-based index into `board_quads`) and its four
// image corners in the order of its board quad (top-left, top-right, bottom-right, bottom-left).
struct DetectedMarker {
  int index = 0;
  std::array<Eigen::Vector2d, 4> pixels;
};
// The markers' layout against the board: each marker's corners predicted from its neighbours'
// alone (markers within 2.1 pitches on the board: a homography fitted to all their corners,
// leaving the marker out), and compared with where the marker was found. Interpolated from the
// markers around it, the prediction is good to a fraction of a pixel whatever the marker's
// size; predicted from one marker's own four corners (the check before), a marker half the square
// extrapolated its raw corners' pixel errors by its distance over its size, and OpenCV's tutorial
// boards failed (docs/experiments/corners.md#charuco). The tolerance is a quarter of the marker's
// size in the image, widened in proportion when the prediction extrapolates (the marker farther
// from its neighbours' centre than their own spread). A layout that does not match the board (rows
// and cols swapped, another board) fails nearly every marker; a marker whose id was misread fails
// alone.
struct MarkerLayoutCheck {
  int checkable = 0;  // markers with enough neighbours to predict them (4 points not on a line)
  struct Disagreement {
    int marker = 0;         // index into the markers given
    double error_px = 0;    // mean distance of its corners from the prediction
    double tolerance_px = 0;
  };
  std::vector<Disagreement> inconsistent;  // worst first
};
MarkerLayoutCheck CheckMarkerLayout(const std::vector<std::array<Eigen::Vector2d, 4>>& board_quads, const std::vector<DetectedMarker>& markers);
// "ids 7 (12.3 px off, tolerance 4.1 px), 12 (…) and 3 more", for a rejection's message: the
// worst `shown` of the disagreeing markers by their ids on the board (DetectedMarker::index).
std::string DescribeDisagreements(const MarkerLayoutCheck& check, const std::vector<DetectedMarker>& markers, size_t shown = 3);
// The view's rejection when most of the checkable markers disagree — "layout mismatch: <kind> not
// where the target file puts them (…, naming the worst); the target's <fields> do not match the
// board" — else empty. `kind`: "markers" or "tags".
std::string LayoutMismatch(const MarkerLayoutCheck& check, const std::vector<DetectedMarker>& markers, const std::string& kind,
                           const std::string& fields);

// A tag grid's view once its corners are in: the blur is the median of its tags' edge blurs (NaN
// when none could be measured), then Conclude.
void ConcludeFound(const DetectorOptions& options, std::vector<double> edge_blurs, Detection* detection);

// Status from the corners found: rejected with too few corners or too much blur; found otherwise.
void Conclude(const DetectorOptions& options, Detection* detection);

}  // namespace vstcal
