// Averages of rotations (docs/math/stereo.md#rotation-average): the start of a stereo solve takes
// right_from_left's rotation as the average of the per-view relative rotations, not one view's.
#pragma once

#include <span>

#include <Eigen/Core>

namespace vstcal {

// The chordal L2 mean: argmin_R Σ ‖R − R_v‖²_F over SO(3), the SVD projection of Σ R_v onto SO(3)
// (U diag(1, 1, det UVᵀ) Vᵀ). Needs at least one rotation.
Eigen::Matrix3d ChordalMeanRotation(std::span<const Eigen::Matrix3d> rotations);

// The geodesic L1 mean (the median of rotations): argmin_R Σ ∠(R, R_v), by Weiszfeld steps on SO(3)
// from the chordal mean, R ← R Exp(Σ_v w_v log(RᵀR_v) / Σ_v w_v), w_v = 1/∠(R, R_v). At most
// `iterations` steps; stops when a step turns R by less than 1e-12 rad. An outlying view moves it
// far less than the L2 mean.
Eigen::Matrix3d GeodesicL1MeanRotation(std::span<const Eigen::Matrix3d> rotations, int iterations = 20);

}  // namespace vstcal
