// The VST registration chain of seed 001 (§3.2, Fig. 5, Eq. 8) as data: the nominal geometry of
// both eyes, and the parameter vector θ that perturbs it, one block per error source
// (docs/math/vst-chain.md). chain.h evaluates it; chain_io.h reads it from vstcal/vst-chain@1.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vstcal/camera/camera.h"
#include "vstcal/core/units.h"
#include "vstcal/errsim/sources.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/sensitivity/distribution.h"

namespace vstcal::errsim {

inline constexpr int kNumEyes = 2;
inline constexpr std::array<std::string_view, kNumEyes> kEyeNames = {"left", "right"};

// The renderer's (virtual) camera uses the radial–tangential layout whatever the physical lens:
// it is a superset of every model, and an estimate may carry distortion the true lens lacks.
using VirtualLens = RadialTangentialModel;
inline constexpr int kNumLensParams = VirtualLens::kNumParams;

struct TestPoint {
  std::string name;
  Eigen::Vector3d point_in_world = Eigen::Vector3d::Zero();
  // For the occlusion decision (rendering): camera depth of the real surface seen behind the point
  // minus the point's own depth, length unit. > 0: the overlay is in front of the real surface
  // and must be drawn; < 0: a real surface hides it. Absent: no occlusion figure for the point.
  std::optional<double> surface_behind;
};

// Nominal (true) geometry. Frames as docs/conventions.md: x_a = a_from_b · x_b.
struct ChainGeometry {
  LengthUnit length_unit = LengthUnit::kMillimetre;
  Rigid3d tracker_from_world;
  Rigid3d hmd_from_tracker;  // the head pose at the instant the video frame is captured
  std::array<Rigid3d, kNumEyes> camera_from_hmd;
  Rigid3d world_from_virtual;  // the virtual-world alignment: where the engine's origin sits in the cell
  Rigid3d world_from_object;   // the physical object (robot base); its virtual twin has the same nominal pose
  std::array<Camera, kNumEyes> cameras;  // the physical cameras' true intrinsics
  // The viewer: eyes at eye_centre ∓ ipd/2 along hmd x (left at −x); each eye sees its camera's image
  // with the camera's field of view, along the camera's nominal axes (an orthoscopic display).
  double ipd = 0;
  Eigen::Vector3d eye_centre_in_hmd = Eigen::Vector3d::Zero();
  // Head motion for the dynamic errors: body rates in the hmd frame.
  Eigen::Vector3d head_angular_velocity = Eigen::Vector3d::Zero();  // rad/s
  Eigen::Vector3d head_linear_velocity = Eigen::Vector3d::Zero();   // length unit / s
  std::vector<TestPoint> test_points;

  // Distance between the two camera centres (length unit).
  double CameraBaseline() const;
};

using sensitivity::Distribution;

// The distribution of s·θ, for θ ~ d (halving a source is Scaled(d, 0.5)); s ≥ 0.
Distribution Scaled(const Distribution& d, double s);

struct ChainParameter {
  std::string name;  // "tracking.rotation.x", "camera_intrinsic.left.fx", …
  Source source = Source::kTrackerAlignment;
  Distribution distribution = Distribution::MakeFixed(0);  // internal units
  std::string file_unit;               // unit in files and reports: "deg", "mm", "s", "px", "1"
  double file_per_internal = 1;        // 180/π for angles, 1 otherwise
};

// Offsets of each source's block in θ. Every block is always present (an inactive parameter is
// fixed at 0), so the chain reads fixed offsets and never branches on configuration.
struct ParameterLayout {
  // tracker_alignment: left perturbation of tracker_from_virtual in the tracker frame.
  static constexpr int kTrackerAlignmentSize = 6;  // ω (rad), ρ (length)
  // tracking: left perturbation of the measured hmd_from_tracker in the hmd frame, and the age of the
  // pose the renderer uses relative to the video frame.
  static constexpr int kTrackingSize = 7;  // ω, ρ, latency (s)
  // camera_extrinsic: per eye a left perturbation of camera_from_hmd in the camera frame, then the
  // baseline error (length, the estimated cameras further apart), then the rig's mount error: one
  // perturbation (ω, ρ) shared by both cameras, camera_from_hmd_e · (Exp(ω), ρ), hmd frame (a
  // factory-calibrated stereo head is rigid; its placement on the HMD is what is uncertain).
  static constexpr int kCameraExtrinsicSize = 2 * 6 + 1 + 6;
  // camera_intrinsic: per eye 10 values mapped to lens-parameter errors by ChainModel::intrinsic_mixing.
  static constexpr int kCameraIntrinsicSize = 2 * kNumLensParams;
  // rendering: render latency (s), then one disparity error (px) per test point.
  // display: per eye eyepoint offset (3, hmd frame), screen shift (2, px), magnification error (1),
  // lens residual k1 (1); then the IPD error (length) and the display latency (s).
  static constexpr int kDisplayPerEye = 7;
  static constexpr int kDisplaySize = 2 * kDisplayPerEye + 2;
  // virtual_object_alignment: ω, ρ of virtual_from_object (virtual frame), or 3 per fiducial
  // (localization errors of the measured fiducials, virtual frame, length).

  int tracker_alignment = 0;
  int tracking = 0;
  int camera_extrinsic = 0;
  int camera_intrinsic = 0;
  int rendering = 0;
  int display = 0;
  int virtual_object_alignment = 0;
  int size = 0;

  // Layout for `num_test_points` and `num_fiducials` (0: the pose form of object alignment).
  static ParameterLayout For(size_t num_test_points, size_t num_fiducials);
  int Begin(Source source) const;
  int End(Source source) const;
};

struct ChainModel {
  ChainGeometry geometry;
  // Fiducial layout in the object frame. Empty: virtual_object_alignment is given as pose errors.
  std::vector<Eigen::Vector3d> fiducials_in_object;
  // Lens-parameter error of eye e = intrinsic_mixing[e] · θ-block of e. Identity when σ's are given
  // per parameter; the Cholesky factor of a calibration's covariance when θ holds standard normals.
  std::array<Eigen::Matrix<double, kNumLensParams, kNumLensParams>, kNumEyes> intrinsic_mixing;
  ParameterLayout layout;
  std::vector<ChainParameter> parameters;  // size layout.size, in θ order
  uint64_t samples = 0;
  uint64_t seed = 0;

  // A model with every parameter at fixed 0 and their names set (chain_io fills distributions).
  static ChainModel WithZeroErrors(ChainGeometry geometry, std::vector<Eigen::Vector3d> fiducials_in_object = {});

  // Nominal θ (every parameter's mean) and a copy with some sources switched off (fixed 0) or
  // scaled (every draw multiplied by `factor`).
  std::vector<double> MeanTheta() const;
  ChainModel WithSources(const std::array<bool, kNumSources>& active) const;
  ChainModel WithSourceScaled(Source source, double factor) const;
  bool SourceActive(Source source) const;  // some parameter of the source is not fixed at 0
};

}  // namespace vstcal::errsim
