// Closed-form initialization of planar-view calibration (Zhang, "A flexible new technique for
// camera calibration", PAMI 2000, §3.1): per-view homographies → the image of the absolute conic
// B = K⁻ᵀK⁻¹ → K (zero skew imposed) → each board's pose. Followed by Refine() for the maximum-
// likelihood estimate with distortion. Derivation: docs/math/zhang.md.
#pragma once

#include <string>
#include <vector>

#include "vstcal/scene/correspondences.h"
#include "vstcal/camera/camera.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

struct ZhangResult {
  bool ok = false;
  std::string message;                // why not, when !ok
  Camera camera;                      // pinhole K with zero skew
  std::vector<Rigid3d> camera_from_board;  // one per view of the input
  std::vector<std::string> warnings;  // views skipped, ...
};

// `c` must be a planar-views rig in which every view has at least kMinPointsPerPlanarView points
// (callers drop the others with a warning: see DropSparseViews) and a well-conditioned homography;
// at least two views are needed (zero skew is imposed).
ZhangResult ZhangInitialization(const Correspondences& c);

// Removes views with fewer than `min_points` observations; returns a warning naming each.
std::vector<std::string> DropSparseViews(Correspondences* c, size_t min_points);

}  // namespace vstcal
