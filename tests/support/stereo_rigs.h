// Stereo rigs for tests and benchmarks.
#pragma once

#include "vstcal/stereo/stereo_rig.h"

namespace vstcal::testing {

// A ZED-mini-like rig (seed 001): two 1280×720 cameras with fx ≈ 700 px, slightly different
// intrinsics and radial–tangential distortion (`distorted`), the right camera 63 mm to the right
// (t = (−63, 0.2, −0.4) mm) and turned by about 0.3° — not a perfect parallel rig. Lengths in mm.
StereoRig ZedLikeRig(bool distorted = true);

// A covariance of right_from_left's tangent: σ 0.05° per rotation axis, (0.2, 0.1, 0.3) mm per
// translation axis, with some correlation — positive definite.
ParameterCovariance SampleRelativePoseCovariance();

}  // namespace vstcal::testing
