// The convex hull of a 3-D point set as the intersection of its facets' half-spaces, to tell
// whether a test point lies inside the measured volume (seed 000 §4.2: registration error inside
// vs outside the volume the calibration points span). Computed by Qhull (libqhull_r, Debian's
// libqhull-dev; Barber, Dobkin & Huhdanpaa 1996); docs/math/report-statistics.md#hull.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace vstcal {

struct ConvexHullOutcome;

class ConvexHull3 {
 public:
  // The hull of `points` (any length unit). A status, not an exception, when the points span no
  // volume (fewer than four, or all on one plane or line): `why` says which.
  static ConvexHullOutcome Of(std::span<const Eigen::Vector3d> points);

  // Inside or on the boundary: n·p + d ≤ tolerance for every facet (n outward, unit), the
  // tolerance 1e-9 times the points' bounding-box diagonal, so that a point on a facet, rounded,
  // counts as inside.
  bool Contains(const Eigen::Vector3d& point) const;
  // The largest n·p + d over the facets: > 0 outside (the distance beyond the farthest facet plane).
  double SignedDistance(const Eigen::Vector3d& point) const;

  size_t num_facets() const { return facets_.size(); }
  size_t num_vertices() const { return num_vertices_; }

 private:
  std::vector<Eigen::Vector4d> facets_;  // (n, d), |n| = 1
  size_t num_vertices_ = 0;
  double tolerance_ = 0;
};

struct ConvexHullOutcome {
  std::optional<ConvexHull3> hull;
  std::string why;  // empty when `hull` is set
};

struct Correspondences;

// The measured volume of a report (reproj-report's `volume`, for cameras and for a rig): the convex
// hull of the calibration points, with its status as the report writes it.
struct MeasuredVolume {
  std::optional<ConvexHull3> hull;
  std::string status;  // "ok", or why there is no hull: the points span no volume, or planar views
  size_t vertices = 0, facets = 0;
};

// The hull of every view's points of every file in `files` (a volume's files share its world
// frame: a rig's two cameras' correspondences of one target). Planar views have no common frame:
// no hull, whatever the files hold.
MeasuredVolume MeasuredVolumeOf(std::span<const Correspondences* const> files);

}  // namespace vstcal
