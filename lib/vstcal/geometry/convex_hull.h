// The convex hull of a 3-D point set as the intersection of its facets' half-spaces, to tell
// whether a point lies inside the volume a point set spans (seed 000 §4.2: registration error
// inside vs outside the volume the calibration points span). Computed by Qhull (libqhull_r,
// Debian's libqhull-dev; Barber, Dobkin & Huhdanpaa 1996); docs/math/report-statistics.md#hull.
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

}  // namespace vstcal
