// The measured volume of a calibration (seed 000 §4.2: registration error inside vs outside the
// volume the calibration points span): the convex hull of the calibration points, with why there is
// none. One definition for camera files (`fit.volume`, `fit.test_points[].inside_volume`) and for
// the reports (reproj-report's `volume`, for cameras and for a rig); docs/math/report-statistics.md#hull.
#pragma once

#include <optional>
#include <span>
#include <string>

#include "vstcal/scene/correspondences.h"
#include "vstcal/geometry/convex_hull.h"

namespace vstcal {

struct MeasuredVolume {
  std::optional<ConvexHull3> hull;
  std::string status;  // "ok", or why there is no hull: the points span no volume, or planar views
  size_t vertices = 0, facets = 0;

  // Inside or on the hull (world frame, the files' length unit); nullopt without a hull: a point
  // is then neither inside nor outside.
  std::optional<bool> Contains(const Eigen::Vector3d& point_in_world) const {
    if (!hull) return std::nullopt;
    return hull->Contains(point_in_world);
  }
};

// The hull of every view's points of every file in `files` (a volume's files share its world
// frame: a rig's two cameras' correspondences of one target). Planar views have no common frame:
// no hull, whatever the files hold.
MeasuredVolume MeasuredVolumeOf(std::span<const Correspondences* const> files);

// "inside", "outside", or "no hull" (the calibration points span no volume), for text and charts.
const char* VolumeSideName(std::optional<bool> inside_volume);

}  // namespace vstcal
