// Projection uncertainty of a calibrated camera from its parameter covariance: the 1-σ ellipse of
// where a point lands in the image when the calibration is redone with fresh pixel noise.
// Linear propagation Σ_q = J Σ_θ Jᵀ through the one projection (docs/math/uncertainty.md#projection).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "vstcal/scene/calibrated_camera.h"

namespace vstcal {

struct Ellipse {
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  // px²
  double sigma_major_px = 0;
  double sigma_minor_px = 0;
  double angle_deg = 0;  // of the major axis, from +u towards +v, in (−90, 90]
};

Ellipse EllipseFromCovariance(const Eigen::Matrix2d& covariance);

// Which uncertainty an ellipse describes. Two different questions, not to be read for each other:
enum class ProjectionUncertaintyKind {
  // The point tied to the calibration object, mrcal's definition: through camera_from_world
  // (volume rigs), or carried through every board's camera_from_board and averaged (planar
  // views). The intrinsics and the poses vary, with their correlations. What reprojecting the
  // calibration scene itself is uncertain by.
  kWithPoses,
  // The point fixed in the camera frame, only the intrinsics vary (their marginal covariance):
  // what a user who moves the camera elsewhere, and poses it anew, inherits from this calibration.
  kIntrinsicsOnly,
};

// At a world point, through the intrinsics and camera_from_world (volume rigs). nullopt when the
// camera has no covariance or no camera_from_world, or the point is behind the camera.
std::optional<Ellipse> ProjectionUncertaintyAtWorldPoint(
    const CalibratedCamera& camera, const Eigen::Vector3d& point_in_world,
    ProjectionUncertaintyKind kind = ProjectionUncertaintyKind::kWithPoses);

// At a pixel and a depth (length unit, along the optical axis): the point depth·Unproject(pixel)
// in the camera frame, tied to the calibration object as `kind` says. nullopt without covariance
// or outside the model's domain.
std::optional<Ellipse> ProjectionUncertaintyAtPixel(const CalibratedCamera& camera, const Eigen::Vector2d& pixel,
                                                    double depth,
                                                    ProjectionUncertaintyKind kind = ProjectionUncertaintyKind::kWithPoses);

struct UncertaintyCell {
  Eigen::Vector2d pixel;
  Ellipse ellipse;
};

// ∂q/∂θ at a camera-frame point: 2 × (the covariance's parameters), the intrinsics' columns filled
// and the poses' zero — for a joint test over many points, whose rows are stacked and weighed with
// PropagateCovariance (calib-compare --cross-validate). nullopt without a covariance or outside
// the model's domain.
std::optional<Eigen::MatrixXd> IntrinsicsJacobianAt(const CalibratedCamera& camera, const Eigen::Vector3d& p_cam);

// A cols × rows grid of pixel-cell centres over the image at one depth (cells where the model
// has no ray are left out).
std::vector<UncertaintyCell> ProjectionUncertaintyGrid(const CalibratedCamera& camera, double depth, int cols, int rows,
                                                       ProjectionUncertaintyKind kind = ProjectionUncertaintyKind::kWithPoses);

}  // namespace vstcal
