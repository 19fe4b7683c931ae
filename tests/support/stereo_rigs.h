// Stereo rigs for tests and benchmarks.
#pragma once

#include <cstdint>

#include "vstcal/scene/correspondences.h"
#include "vstcal/scene/stereo_rig.h"

namespace vstcal::testing {

// A ZED-mini-like rig (seed 001): two 1280×720 cameras with fx ≈ 700 px, slightly different
// intrinsics and radial–tangential distortion (`distorted`), the right camera 63 mm to the right
// (t = (−63, 0.2, −0.4) mm) and turned by about 0.3° — not a perfect parallel rig. Lengths in mm.
StereoRig ZedLikeRig(bool distorted = true);

// A covariance of right_from_left's tangent: σ 0.05° per rotation axis, (0.2, 0.1, 0.3) mm per
// translation axis, with some correlation — positive definite.
ParameterCovariance SampleRelativePoseCovariance();

// A chessboard of 9 × 6 inner corners at 30 mm (the opencv-doc stereo sample's board) seen by both
// cameras of `rig` in `views` poses: view k ("view<k>") 0.45–0.75 m in front of the left camera,
// tilted by up to 30° about a random axis in the board plane and rolled by up to ±20°, from Philox
// draws keyed by (seed, k). Corners outside a camera's image are left out of that camera's view.
// Noise-free: add noise with WithNoise (support/scenes.h).
struct StereoViews {
  Correspondences left, right;
  std::vector<Rigid3d> left_from_board;
};
StereoViews SyntheticStereoViews(const StereoRig& rig, int views, uint64_t seed);

}  // namespace vstcal::testing
