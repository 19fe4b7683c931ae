// Plane-to-image homography by the normalized DLT (Hartley & Zisserman Alg. 4.2): q ~ H (X, Y, 1)
// for board points (X, Y, 0). Used to initialize planar-view calibration (Zhang's method).
#pragma once

#include <optional>
#include <span>

#include <Eigen/Core>

#include "vstcal/scene/correspondences.h"

namespace vstcal {

// H scaled to ‖H‖_F = 1 with H(2,2) ≥ 0; nullopt for fewer than 4 points or a degenerate
// configuration (collinear board points or pixels: the second-smallest singular value of the
// normalized system is below 1e-6 of the largest).
std::optional<Eigen::Matrix3d> EstimateHomography(std::span<const Observation> board_observations);

}  // namespace vstcal
