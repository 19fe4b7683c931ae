// The 3-D registration error of a stereo rig against both cameras' correspondences of the same
// target (reproj-report RIG LEFT RIGHT, docs/tools/reproj-report.md#a-stereo-rig; seed 000 Figs.
// 9–10, seed 001 Fig. 2; the math in docs/math/stereo.md#triangulated-error).
//
// Views are matched by name, as calib-stereo solve matches them; within a view, a left and a right
// observation are one point when their target coordinates are equal (both files list the same
// target's points). Per view, the left camera's pose left_from_<frame> is found by PnP from the
// left pixels alone (pose_refine.h SolvePnp: one pose for a volume, one per view for planar
// views), which puts the known point in the left frame: X = left_from_<frame> · X_target. The
// point the rig sees, P, is the midpoint of the closest approach of the two measured pixels' rays
// (TriangulateMidpoint, geometry/registration_error.h), the left ray from the origin and the right
// one from the right camera's centre c_r = −Rᵀt along Rᵀ·ray_r. Then, in the rig's length unit:
//   per axis    Δ = P − X, in the left camera's frame (x right, y down, z forward);
//   Holloway    linear, lateral, depth, angular of Δ seen from the cyclopean eye c = c_r/2
//               (RegistrationError, the one implementation err-sim uses).
// What the statistics summarize is a magnitude (|Δx|, |depth|, …); the signed means (`bias`) say
// which way the rig errs. A point that cannot be measured is excluded and counted by reason.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/scene/correspondences.h"
#include "vstcal/scene/measured_volume.h"
#include "vstcal/report/reprojection_report.h"
#include "vstcal/report/statistics.h"
#include "vstcal/scene/stereo_rig.h"
#include "vstcal/core/enum_names.h"

namespace vstcal {

// Why a point of a common view has no 3-D error.
enum class StereoExclusion {
  kNone,
  kLeftOnly,   // seen by the left camera only
  kRightOnly,  // seen by the right camera only
  kNoPose,     // the view's left pose could not be found (too few points, collinear, …)
  kNoRay,      // a measured pixel has no ray, or the rays are parallel
  kBehind,     // the rays meet behind the left camera
  kNotMeasured,  // a test point neither file gives a pixel for
};
inline constexpr EnumNames<StereoExclusion, 7> kStereoExclusionNames = {{{StereoExclusion::kNone, "none"}, {StereoExclusion::kLeftOnly, "left-only"}, {StereoExclusion::kRightOnly, "right-only"}, {StereoExclusion::kNoPose, "no-pose"}, {StereoExclusion::kNoRay, "no-ray"}, {StereoExclusion::kBehind, "behind"}, {StereoExclusion::kNotMeasured, "not-measured"}}};
std::string_view StereoExclusionName(StereoExclusion e);

struct StereoPointError {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  // the point in the target's frame (world or board)
  StereoExclusion excluded = StereoExclusion::kNone;
  Eigen::Vector3d truth = Eigen::Vector3d::Zero();         // X, left frame (when measured)
  Eigen::Vector3d triangulated = Eigen::Vector3d::Zero();  // P, left frame
  double linear = 0, lateral = 0, depth = 0, angular_rad = 0;  // depth signed, > 0 farther

  Eigen::Vector3d error() const { return triangulated - truth; }
  double angular_deg() const;  // as files show it
};

// Statistics of the magnitudes, and the signed means.
struct StereoStats {
  std::optional<ErrorStats> x, y, z, linear, lateral, depth, angular_deg;
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();  // mean Δ (x, y, z), length unit
  double depth_bias = 0;                           // mean signed depth term
};

// One camera's view of a common view reprojected through the rig, as the heat maps' cells count
// it (StereoReport::left_grid): p̂ through the view's left PnP pose, and right_from_left too for the
// right camera. `points` are its file's view's in order, each PointError with measured, predicted
// and error_px = |p̂ − m| only (no lateral or angular error): kNoPose without a left pose,
// kBehindCamera when p̂ does not exist.
struct StereoReprojection {
  size_t file_view = 0;  // the view's index in its camera's correspondences
  std::string image;     // the view's image as that file names it ("" for none)
  std::vector<PointError> points;
  std::optional<ErrorStats> error_px;  // nullopt when no point is reprojected
};

struct StereoViewReport {
  std::string name;
  std::string pose_status;  // "ok", or why the left pose failed (PoseStatusText)
  std::vector<StereoPointError> points;  // the left view's points in order, then the right-only ones
  StereoStats stats;
  StereoReprojection left, right;
};

// A test point of a volume (never used in a solve, seed 000 §4.2), matched between the files by
// name, triangulated from the two pixels where it was measured.
struct StereoTestPoint {
  std::string name;
  Eigen::Vector3d point_in_world = Eigen::Vector3d::Zero();
  StereoPointError error;  // kLeftOnly / kRightOnly: measured in one file only
  std::optional<bool> inside_volume;  // inside the measured volume (`volume`); nullopt without a hull
};

// A camera's image cells and the statistics of each (nullopt: no point in it).
struct StereoCameraGrid {
  ImageGrid grid;
  std::vector<std::optional<ErrorStats>> error_px;
  std::optional<ErrorStats> overall_px;  // every reprojected point of the camera (in some cell or not)
};

struct StereoReport {
  std::string rig_file, left_file, right_file;
  LengthUnit length_unit = LengthUnit::kMillimetre;
  Rig rig_kind = Rig::kVolume;
  double baseline = 0;
  std::vector<StereoViewReport> views;  // views both cameras saw, in the left file's order
  std::vector<std::string> left_only_views, right_only_views;
  StereoStats overall;
  size_t n_left_only = 0, n_right_only = 0, n_no_pose = 0, n_no_ray = 0, n_behind = 0;  // points, by reason
  // Volumes only (planar views' boards share no world frame): the left file's test points in order,
  // then the right file's that the left does not name.
  std::vector<StereoTestPoint> test_points;
  StereoStats test_stats;  // every measured test point
  // The convex hull of both files' calibration points (one world frame), and the measured test
  // points inside it (or on its boundary) and outside it, as reproj-report splits a camera's (seed
  // 000 §4.2); both empty without a hull.
  MeasuredVolume volume;
  StereoStats test_inside, test_outside;
  // Where in each image the rig mispredicts: per cell of its camera's grid (row-major), the statistics of the
  // reprojection error |p̂ − m| (px) of the points of each common view with a left pose whose
  // measured pixel m lies in the cell, p̂ = left.Project(left_from_<frame> · X) for the left camera
  // (the PnP pose: its own fit), right.Project(right_from_left · left_from_<frame> · X) for the right
  // one (the rig's relative pose too). A point projecting behind a camera is in no cell.
  StereoCameraGrid left_grid, right_grid;
};

struct StereoReportOptions {
  // Views match when their keys are equal: the name, or given this pattern the first group of its
  // match in the name (calib-stereo solve's --match-views: "([0-9]+)$" pairs left01 with right01);
  // the report names views by their keys. Empty: the rig's own view_pairing, else by name.
  std::string view_key_pattern;
  int grid_cols = 8, grid_rows = 6;  // image cells of the per-region reprojection statistics
};

// Throws InputError naming the file and field when the inputs do not go together: a rig camera
// and its correspondences of different image sizes, a length unit differing from the rig's, one
// file a volume and the other planar views, a view key twice in one file, a target point twice in
// one view, no view seen by both cameras, a key pattern that is bad or does not match a name.
StereoReport BuildStereoReport(const StereoRig& rig, Correspondences left, Correspondences right,
                               const std::string& rig_file, const std::string& left_file,
                               const std::string& right_file, const StereoReportOptions& options = {});

// What the 3-D statistics leave out, as ExclusionNotes(ReprojReport) does: the points of the common
// views not triangulated, by reason, and the views one camera saw. Empty when nothing was.
std::vector<std::string> ExclusionNotes(const StereoReport& report);

}  // namespace vstcal
