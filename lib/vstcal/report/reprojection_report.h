// The reprojection and registration-error report of one or more cameras against one set of
// correspondences (reproj-report, docs/tools/reproj-report.md; the file is vstcal/reproj-report@1,
// docs/formats.md#reproj-report; the math in docs/math/report-statistics.md).
//
// For every observation and test point, with the point X_c = camera_from_<frame> · X in the camera
// frame, its projection p̂ and its measured pixel m:
//   residual r = p̂ − m (px);
//   angular error θ = ∠(X_c, ray(m)), the visual angle between where the camera model puts the
//   point and where it was seen;
//   lateral error at the point's depth: the offset Δ from X_c to where the ray through m crosses the
//   plane through X_c normal to the line of sight, Holloway's lateral term |Δ × ℓ| of
//   geometry/registration_error.h (= d·tan θ at distance d = |X_c|), in the correspondences' length unit;
//   normalized residual z = √(rᵀ Σ_r⁻¹ r) where the camera carries a covariance and σ̂:
//   Σ_r = σ̂²/w·I − Σ_p for the points the camera was fit to (the residual of a least-squares fit
//   is smaller than the noise by the projection's own uncertainty Σ_p), Σ_r = σ̂²·I + Σ_p for
//   test points (independent of the fit). E[z²] = 2 when the camera is consistent with its
//   covariance, so chi2_per_dof = mean(z²)/2 ≈ 1.
// A point that cannot be measured is excluded and counted under its reason, never silently.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/scene/correspondences.h"
#include "vstcal/scene/measured_volume.h"
#include "vstcal/report/statistics.h"
#include "vstcal/core/enum_names.h"

namespace vstcal {

// A camera as the report takes it: the file it came from (for messages and the report), the
// camera, and σ̂ (the camera file's refinement.sigma_px) when it has one.
struct ReportCamera {
  std::string file;
  CalibratedCamera camera;
  std::optional<double> sigma_px;
};

struct ReprojReportOptions {
  int grid_cols = 8, grid_rows = 6;  // image cells of the per-region statistics
};

// Why a point has no error: it is left out of every statistic and counted.
enum class Exclusion { kNone, kBehindCamera, kNoPose, kNotMeasured, kNoRay };
inline constexpr EnumNames<Exclusion, 5> kExclusionNames = {{{Exclusion::kNone, "none"}, {Exclusion::kBehindCamera, "behind-camera"}, {Exclusion::kNoPose, "no-pose"}, {Exclusion::kNotMeasured, "not-measured"}, {Exclusion::kNoRay, "no-ray"}}};
std::string_view ExclusionName(Exclusion e);  // "behind-camera", "no-pose", "not-measured", "no-ray"

struct PointError {
  Eigen::Vector2d measured = Eigen::Vector2d::Zero();  // px (test points: when measured)
  std::optional<Eigen::Vector2d> predicted;            // px, when in front of the camera and posed
  Exclusion excluded = Exclusion::kNone;
  double depth = 0;    // |X_c|, length unit (when posed)
  double z = 0;        // X_c's depth along the optical axis, length unit (when posed)
  double error_px = 0;  // |r|
  double lateral = 0;   // length unit
  double angular_rad = 0;
  std::optional<double> normalized;  // z, when the camera has a covariance and σ̂ and Σ_r > 0

  double angular_deg() const;  // as files and pages show it (one conversion for all of them)
};

struct ViewReport {
  std::string name;
  std::vector<PointError> points;      // in the order of the correspondences
  std::optional<ErrorStats> error_px;  // nullopt when no point of the view is measured
};

struct TestPointReport {
  std::string name;
  Eigen::Vector3d point_in_world;
  PointError error;
  std::optional<bool> inside_volume;  // inside the calibration points' convex hull; nullopt without a hull
};

// Statistics of one error measure over a set of points.
struct MeasureStats {
  std::optional<ErrorStats> error_px, lateral, angular_deg;
};

// A lens parameter as the camera file gives it: its value and, when the file's covariance names
// it, its 1σ.
struct ParameterEstimate {
  std::string name;  // "fx", "k1", … in the model's layout order
  double value = 0;
  std::optional<double> sigma;
};

struct CameraReport {
  std::string file, name, method;
  std::vector<ParameterEstimate> parameters;  // every lens parameter, in layout order
  std::vector<ViewReport> views;
  MeasureStats overall;  // calibration points
  std::optional<ErrorStats> normalized;
  std::optional<double> chi2_per_dof;
  std::string normalization;  // how z was formed, or why it was not ("no covariance", …)
  std::vector<std::optional<ErrorStats>> grid;  // |r| per image cell, row-major
  std::vector<TestPointReport> test_points;
  MeasureStats test_inside, test_outside;
  std::optional<ErrorStats> test_normalized;
  size_t n_behind_camera = 0, n_no_pose = 0, n_no_ray = 0;  // calibration points excluded, by reason
  // mrcal's show-projection-uncertainty: the 1-σ major semi-axis (px) of the projection of the
  // point at each grid cell's centre and the calibration points' median z, tied to the
  // calibration object (ProjectionUncertaintyKind::kWithPoses), row-major; nullopt for a cell
  // without a ray. Empty when the camera has no covariance.
  std::vector<std::optional<double>> uncertainty_px;
  double uncertainty_depth = 0;  // length unit
};

// Camera `camera` against the first camera: how far their predictions of the same points lie
// apart, and how their statistics differ.
struct CameraDifference {
  size_t camera = 0, reference = 0;
  std::optional<ErrorStats> prediction_shift_px;  // |p̂_camera − p̂_reference| over points both predict
  std::optional<double> rms_change_px, median_change_px, p95_change_px;  // camera − reference
};

struct ReprojReport {
  std::string correspondences_file;
  Correspondences correspondences;  // as read (its views give the measured pixels and names)
  ImageGrid grid;
  MeasuredVolume volume;  // the calibration points' convex hull
  std::vector<CameraReport> cameras;
  std::vector<CameraDifference> differences;  // cameras 1.. against camera 0
};

// Throws InputError naming the camera file and field when a camera does not go with the
// correspondences: another image size or length unit, a volume camera without camera_from_world,
// a planar-views camera without views.
ReprojReport BuildReprojReport(std::span<const ReportCamera> cameras, Correspondences correspondences,
                               std::string correspondences_file, const ReprojReportOptions& options = {});

// What the statistics leave out, one line a camera that left out calibration points: how many of
// how many, and why ("<camera file>: 8 of 60 points left out of the statistics: 8 in views the
// camera has no pose for (view3, view7)"); nothing is dropped in silence. Empty when none was.
std::vector<std::string> ExclusionNotes(const ReprojReport& report);

}  // namespace vstcal
