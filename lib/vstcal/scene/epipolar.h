// Epipolar geometry of a rig (docs/math/stereo.md#epipolar). A left point x_l and its right image
// x_r = R x_l + t are coplanar with t, so x_rᵀ [t]× R x_l = 0 for normalized coordinates
// (x/z, y/z, 1) of the two cameras, and u_rᵀ F u_l = 0 for undistorted homogeneous pixels.
#pragma once

#include <Eigen/Core>

#include "vstcal/scene/stereo_rig.h"

namespace vstcal {

// E = [t]× R of right_from_left (OpenCV's stereoCalibrate convention; E's scale is |t|).
Eigen::Matrix3d EssentialMatrix(const Rigid3d& right_from_left);

// F = K_right⁻ᵀ E K_left⁻¹ for undistorted pixels (skew included), scaled to F[2][2] = 1 as
// OpenCV's stereoCalibrate returns it; left unscaled when F[2][2] = 0 (epipole at infinity in a
// way that puts the principal points on each other's epipolar lines).
Eigen::Matrix3d FundamentalMatrix(const StereoRig& rig);

}  // namespace vstcal
