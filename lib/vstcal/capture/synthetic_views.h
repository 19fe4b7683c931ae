// Synthetic planar-view captures (a chessboard waved in front of the camera, as OpenCV and mrcal
// take them): a board of grid corners at N poses spread over the field of view, seen by a known
// camera (any lens model) with Gaussian pixel noise keyed by (seed, view, corner).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/scene/correspondences.h"
#include "vstcal/camera/camera.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

// Board frame: origin at corner (0, 0), X along columns, Y along rows, Z = 0 on the board (its
// normal pointing away from the camera at zero tilt) — OpenCV's object-point convention.
struct PlanarViewsSpec {
  int grid_cols = 10;
  int grid_rows = 7;
  double spacing = 30;      // length unit
  int num_views = 15;
  double distance = 600;    // typical depth of the board centre, length unit (views spread ±20 %)
  double max_tilt_deg = 40; // board tilts spread over [0.3, 1] × this, about varied axes
  double noise_px = 0;
  uint64_t seed = 1;
  LengthUnit length_unit = LengthUnit::kMillimetre;
  std::string camera_name;
};

struct SyntheticViews {
  Correspondences correspondences;         // rig planar-views; corners outside the image dropped
  std::vector<Rigid3d> camera_from_board;  // ground truth, one per view kept
  std::vector<std::string> warnings;       // views dropped for having too few visible corners
};

// The pose of view k: the board centre aimed at a point of a Halton (2, 3) sequence over the
// central 70 % of the image, at depth distance·(0.8 … 1.2), tilted and rolled by Philox draws.
Rigid3d PlanarViewPose(const Camera& camera, const PlanarViewsSpec& spec, int view);

// Throws InputError for impossible specs (non-positive sizes, a tilt ≥ 80°, no visible view, a
// length beyond limits::kMaxSyntheticScale, more views than limits::kMaxViews or points than
// limits::kMaxPoints).
SyntheticViews SynthesizePlanarViews(const Camera& camera, const PlanarViewsSpec& spec);

// The ground truth as a vstcal/camera@1 file holds it: the camera, one board pose per view kept
// (with its RMS against the noisy pixels), method "synthetic", and the fit of the true camera.
CalibratedCamera PlanarViewsTruthCamera(const Camera& camera, const PlanarViewsSpec& spec, const SyntheticViews& views);

}  // namespace vstcal
