// The input of binocular registration (seed 000 §4.1 "embedding and tracking"): the embedded points
// that define the world frame, the virtual points to overlay, and per video frame the pixels where
// the embedded points were tracked — the content of a vstcal/tracks@1 file (docs/formats.md#tracks).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/camera/camera.h"
#include "vstcal/core/units.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

struct NamedPoint {
  std::string name;
  Eigen::Vector3d point_in_world;  // length unit
};

// One video frame: per embedded point (same order) its tracked pixel, nullopt when the tracker
// lost it. `right` is empty when the right image was not tracked.
struct TrackedFrame {
  std::string name;
  std::vector<std::optional<Eigen::Vector2d>> left, right;
  std::optional<Rigid3d> truth_left_from_world;  // synthetic sequences: the true pose, for accuracy
};

struct Tracks {
  LengthUnit length_unit = LengthUnit::kMillimetre;
  ImageSize left_image_size;
  std::optional<ImageSize> right_image_size;  // present when some frame has right pixels
  std::vector<NamedPoint> embedded;           // at least 4 (kMinPnpPoints)
  std::vector<NamedPoint> virtual_points;     // projected into both images
  std::vector<TrackedFrame> frames;
};

}  // namespace vstcal
