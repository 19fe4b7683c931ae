// Square markers found by OpenCV's ArUco module with a given black border: ChArUco boards' markers
// (detect_charuco.cc), Kalibr's aprilgrid (tag36h11 with a two-cell border, detect_aprilgrid.cc) and the hint that a board read as one
// type looks like another (detect_apriltag.cc). Internal to the capture module.
#pragma once

#include <array>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vstcal/image/image.h"

namespace vstcal {

struct ArucoTag {
  int id = 0;
  // OpenCV's order: the marker's top-left, top-right, bottom-right, bottom-left as drawMarker draws
  // it, whatever its rotation in the image; px, (0, 0) the centre of the top-left pixel.
  std::array<Eigen::Vector2d, 4> corners;
};

// Where the markers are searched: in the image reduced to at most 1 MP (search_image.h), the
// corners then mapped back to full resolution up to half a reduction factor off, for the caller to
// refine there (bounded time on large images: ChArUco's markers); or in the full image (Kalibr's
// aprilgrid: its corner refinement needs OpenCV's full-resolution corners — from the reduced image
// it found 1 to 27 of 96 corners on 1,600–4,000 px views, and at 4,000 px 17 corners a cell off,
// where the full image gives 84–92, none off; OpenCV takes 0.3 s on a 12 MP view). The reduced
// search still tells it whether there is anything to search.
enum class MarkerSearch { kReduced, kFullResolution };

// The markers of OpenCV's predefined dictionary `dictionary` (cv::aruco::PREDEFINED_DICTIONARY_NAME)
// whose black border is `border_cells` cells wide; OpenCV's own corners, not refined.
struct ArucoSearch {
  std::vector<ArucoTag> tags;
  // The mean side, px, of each quadrilateral OpenCV took for a marker and could not decode (its
  // rejected candidates): what miss_diagnosis.h judges too small.
  std::vector<double> undecoded_sides_px;
  // The reduction of the image searched: 1 when searched at full resolution.
  int factor = 1;
};
ArucoSearch FindArucoTags(const GrayImage& image, int dictionary, int border_cells, MarkerSearch where);

// OpenCV's dictionary of a libapriltag family ("tag36h11" → DICT_APRILTAG_36h11); −1 when none.
int ArucoDictionaryOfAprilTagFamily(std::string_view family);

}  // namespace vstcal
