// Cameras of every lens model, shared by the interop tests: realistic values, and coefficients
// as small as 1e-12 that a printf("%f") writer would lose.
#pragma once

#include <vector>

#include "vstcal/scene/calibrated_camera.h"

namespace vstcal::testing {

// One camera per lens model ("none", "radial-tangential" with and without k3, "rational"), no
// skew (OpenCV and mrcal have none), with a pose unless `with_pose` is false.
std::vector<CalibratedCamera> InteropCameras(bool with_pose = true);

}  // namespace vstcal::testing
