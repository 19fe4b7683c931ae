// calib-capture plan: what a capture will look like and what calibration it will give, before
// anything is captured (docs/tools/calib-capture.md#plan, docs/math/capture-plan.md).
//
// Geometry per template position (volume, seed 000 §4.1) or board pose (planar views): the image
// fraction the printed pattern covers (over the whole image and a 3 × 3 grid of regions), the
// shortest projected square side, the corners outside the image, the foreshortening, and
// warnings with the fix. Prediction: the Fisher information of the planned corners at a stated
// pixel noise through CovarianceAt (estimators/information.h), the code the solvers' covariance uses,
// with the free parameters of the solve the user will run; then the projection uncertainty at
// test points through estimators/uncertainty.h.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/estimators/information.h"
#include "vstcal/estimators/refine_options.h"
#include "vstcal/capture/synthetic_views.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/capture/target.h"

namespace vstcal {

// The smallest square side (px) at which the compare-detectors experiment found every view of
// every condition (docs/experiments/corners.md: 12 px was its smallest size, 10/10 found with
// vstcal's pipeline); smaller squares are untested and warned about.
inline constexpr double kSmallestReliableSquarePx = 12;
// Beyond this angle between the board normal and the line of sight, warned as too oblique: the
// experiment tilted boards by up to 35°; corners of boards beyond 60° shrink to under half width.
inline constexpr double kMaxReliableObliquityDeg = 60;

struct PlanRequest {
  Camera camera;  // the true (nominal) camera the plan is evaluated at
  Target target;  // its length unit is the plan's
  Rig rig = Rig::kVolume;
  // Volume: near, far, interval, camera_distance, tilt_deg, tilt_direction_deg, roll_deg are used;
  // the grid fields are replaced by the target's corners.
  VolumeSpec volume;
  // Planar views: num_views, distance, max_tilt_deg, seed are used (the pose pattern of
  // PlanarViewPose); the grid fields are replaced by the target's.
  PlanarViewsSpec views;
  double pixel_sigma = 0.1;  // σ of a detected corner's u and v, px
  RefineOptions options;     // the free parameters of the solve the user will run
  std::string method = "dlt";  // "dlt" or "tsai": tsai with one plane holds fx/fy and (cx, cy) as calib-tsai does
  // Where depth of field is acceptable (length unit, along the optical axis): positions whose
  // corners lie outside are warned about as defocused. Absent: not checked.
  std::optional<double> sharp_near, sharp_far;
  std::vector<TestPoint> test_points;            // volume: world points (default seed 000's five)
  std::vector<Eigen::Vector3d> pixel_points;     // U, V (px), depth (length unit)
};

struct PositionPlan {
  std::string name;                  // "z=400" (volume) or "view 3"
  std::optional<double> plane_offset;  // volume
  Rigid3d camera_from_board;
  double coverage = 0;                  // image fraction inside the projected pattern outline
  Eigen::Matrix3d region_coverage;      // (row, col) of a 3 × 3 grid: each region's fraction
  double smallest_square_px = 0;        // shortest projected side between neighbouring corners
  int corners = 0, corners_outside = 0;  // outside the image or behind the camera
  double outside_px = 0;                // how far the farthest corner lies beyond the border
  double obliquity_deg = 0;             // board normal vs the line of sight to the board centre
  double depth_min = 0, depth_max = 0;  // of the corners, along the optical axis
  bool used = true;                     // its corners enter the prediction (detectable)
  std::vector<std::string> warnings;    // one line each, with the fix
};

struct ParameterSigma {
  std::string name;
  double value = 0;
  double sigma = 0;
};

struct PointUncertainty {
  std::string name;
  std::optional<Eigen::Vector3d> point_in_world;  // volume test point
  std::optional<Eigen::Vector3d> pixel_depth;     // U, V, depth
  double with_poses_px = 0;       // 1-σ major axis, the point tied to the calibration object
  double intrinsics_only_px = 0;  // 1-σ major axis, the point fixed in the camera frame
};

struct CapturePlan {
  PlanRequest request;
  std::vector<PositionPlan> positions;
  Rigid3d camera_from_world;  // volume
  int used_corners = 0;
  // The noise-free corners the prediction is the information of (the positions `used`), and the
  // poses it is taken at: camera_from_world (volume) or each used view's camera_from_board.
  Correspondences corners;
  std::vector<Rigid3d> poses;
  CalibrationCovariance prediction;
  std::vector<ParameterSigma> sigmas;      // empty when not observable
  std::vector<PointUncertainty> points;    // empty when not observable
  std::vector<std::string> warnings;       // plan-wide
};

// Throws InputError for an impossible request (the field named as calib-capture plan's flag).
CapturePlan PlanCapture(const PlanRequest& request);

}  // namespace vstcal
