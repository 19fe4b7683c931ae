// The printed pattern of a target (target.h): its black rectangles on the white sheet, with the
// marker bits taken from the libraries that detect them (OpenCV's ArUco dictionaries, libapriltag's
// families), so that what vstcal prints and renders is what those detectors decode.
#pragma once

#include <vector>

#include "vstcal/capture/pattern.h"
#include "vstcal/capture/target.h"

namespace vstcal {

// A square marker as cells, row-major from its top-left cell, true = black: ArUco marker `id`
// of an OpenCV dictionary with its 1-bit black border ((bits + 2)² cells), or AprilTag `id` of a
// libapriltag family from its black border inwards ((bits + 2)² cells, the white ring left out).
struct MarkerCells {
  int side = 0;
  std::vector<bool> black;
};
MarkerCells ArucoMarkerCells(std::string_view dictionary, int id);
MarkerCells AprilTagCells(std::string_view family, int id);
// Tag `id` of Kalibr's aprilgrid as printed: OpenCV's DICT_APRILTAG_36h11 marker with a 2-cell
// black border (kAprilGridCells² cells) turned half a turn (target.h).
MarkerCells AprilGridTagCells(int id);

// The target's pattern. The target must pass CheckTarget.
Pattern TargetPattern(const Target& target);

// Adds a marker's black cells to `black`, its top-left cell's corner at (x0, y0), cells of side `cell`.
void AddMarkerCells(const MarkerCells& marker, double x0, double y0, double cell, std::vector<Rect>* black);

}  // namespace vstcal
