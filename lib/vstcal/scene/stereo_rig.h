// A stereo rig: two calibrated cameras and the rigid transform between them — the content of a
// vstcal/stereo@1 file (DESIGN.md "Stereo rig", docs/formats.md#stereo).
//
// Frames: `left` and `right` are the two camera frames (x right, y down, z forward). The rig is
// right_from_left: x_right = R x_left + t, t in the rig's length unit. The baseline is the
// distance between the camera centres, |−Rᵀt| = |t|. A pose of the left camera in any frame gives
// the right one's by composition (seed 000 §4.3): right_from_world = right_from_left · left_from_world.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/scene/fit.h"
#include "vstcal/scene/view_keys.h"
#include "vstcal/core/units.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

// How well a rig fits the stereo views it was solved from: the symmetric epipolar distance of
// matched pixels (docs/math/stereo.md#epipolar), px, overall and per view.
struct StereoViewFit {
  std::string name;
  ResidualStats epipolar;
};
struct StereoFit {
  ResidualStats epipolar;
  std::vector<StereoViewFit> views;
};

// OpenCV's stereoRectify of the rig (docs/math/stereo.md#rectification). Rotations take each
// camera's frame to its rectified frame, in which both cameras share one orientation and the
// baseline lies along x: left_rect_from_left = R1, right_rect_from_right = R2 in OpenCV's names.
// P_left, P_right project rectified-frame points to rectified pixels; Q maps (u, v, disparity, 1)
// to homogeneous left-rectified points.
struct Rectification {
  double alpha = -1;            // OpenCV's free scaling: −1 its default, 0 valid pixels only … 1 all pixels
  bool zero_disparity = true;   // CALIB_ZERO_DISPARITY: both principal points at the same pixel
  Eigen::Matrix3d left_rect_from_left = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d right_rect_from_right = Eigen::Matrix3d::Identity();
  Matrix34d P_left = Matrix34d::Zero();
  Matrix34d P_right = Matrix34d::Zero();
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  std::array<int, 4> valid_roi_left{};   // x, y, width, height of the all-valid rectangle, px
  std::array<int, 4> valid_roi_right{};
};

struct StereoRig {
  LengthUnit length_unit = LengthUnit::kMillimetre;
  std::string method;          // "assembled" (two cameras and a known right_from_left), ...
  CalibratedCamera left, right;  // intrinsics only: no pose, no views (the pose between them is below)
  Rigid3d right_from_left;
  std::optional<StereoFit> fit;  // absent for an assembled rig: no data was fitted
  // Covariance of right_from_left's tangent, named RelativePoseTangentNames() (left perturbation
  // in the right camera's frame, docs/conventions.md#poses-in-optimisation).
  std::optional<ParameterCovariance> covariance;
  std::optional<Rectification> rectification;
  // How the solve paired the two cameras' views (given or derived from their names); later pairings
  // of correspondences with this rig use it. Absent: by name.
  std::optional<ViewPairing> view_pairing;
  // The joint covariance of both cameras' lens parameters and right_from_left's tangent, with their
  // cross-covariances (calib-stereo solve: one problem estimated them together). Names
  // JointCovarianceName(): "left.fx" …, "right.fx" …, then "right_from_left.rx" … ".tz"; its
  // blocks are left.covariance, right.covariance and covariance. err-sim draws a rig's errors
  // from it as one correlated draw (docs/formats.md#vst-chain-joint).
  std::optional<ParameterCovariance> joint_covariance;

  double baseline() const { return right_from_left.t.norm(); }
};

// A joint covariance's name of camera `eye`'s (0 left, 1 right) lens parameter: "left.fx".
std::string JointCovarianceName(int eye, std::string_view lens_parameter);

// "right_from_left.rx", … ".tz": ω (radians) then ρ (length unit).
const std::array<std::string, 6>& RelativePoseTangentNames();

// First-order σ of the baseline |t| from the covariance Σ of (ω, ρ): a left perturbation moves t to
// Exp(ω)t + ρ, and rotating t about the origin keeps its length, so σ² = t̂ᵀ Σ_ρρ t̂ with t̂ = t/|t|
// (docs/math/stereo.md#baseline-sigma). nullopt without a covariance.
std::optional<double> BaselineSigma(const StereoRig& rig);
// σ of each component of ω (radians), the relative rotation's uncertainty; nullopt without a covariance.
std::optional<Eigen::Vector3d> RelativeRotationSigma(const StereoRig& rig);

// A camera reduced to what a rig holds: image size, lens, name, method, and its intrinsics'
// covariance marginalized to the lens parameters (the sub-block: a Gaussian's marginal). Poses,
// views, P and fit are dropped.
CalibratedCamera IntrinsicsOnly(const CalibratedCamera& camera);

// A rig from two cameras, `*_name`s used in messages (e.g. their files). right_from_left is the
// one given (its translation in `length_unit`), else derived from the cameras' poses in one common
// frame (both camera_from_world: right_from_left = right_from_world · world_from_left; their length
// units must agree). Throws InputError when the units of the poses differ, when there is no way to
// know right_from_left, or when the cameras coincide (baseline 0). The cameras are reduced by
// IntrinsicsOnly, which leaves them without lengths, so they take the rig's unit; they are named
// "left" and "right" when they have no name.
struct AssembleInput {
  CalibratedCamera left, right;
  std::string left_name = "left", right_name = "right";
  std::optional<Rigid3d> right_from_left;
  LengthUnit length_unit = LengthUnit::kMillimetre;  // of a given right_from_left
};
StereoRig AssembleRig(const AssembleInput& input);

// Fails (InputError) unless right_from_left separates the cameras: a baseline of 0 (or not finite)
// has no stereo geometry. `where` names the file or field.
void CheckBaseline(const Rigid3d& right_from_left, std::string_view where);

}  // namespace vstcal
