// A vstcal/vst-chain@1 file as read (docs/formats.md#vst-chain): every value as the file gives it,
// in file units, transforms in their written form, referenced camera and rig files by their path
// (with what they hold), defaults made explicit. The reader (chain_reader.h) checks every field and
// fills it; the writer (chain_writer.h) writes it back in one canonical layout, so that reading a
// written chain gives the same ChainSpec and writing it again the same bytes; BuildChainModel
// turns it into the model the simulation runs.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/camera/camera.h"
#include "vstcal/core/units.h"
#include "vstcal/errsim/chain_model.h"
#include "vstcal/errsim/schema.h"
#include "vstcal/handeye/refine.h"
#include "vstcal/handeye/tracker_noise.h"
#include "vstcal/json/json_writer.h"

namespace vstcal {

inline constexpr std::string_view kChainFormat = "vstcal/vst-chain@1";

// {"R": 3×3, "t": [3]} or {"rotvec_deg": [3], "t": [3]}, as written; `value` the transform.
struct TransformSpec {
  std::optional<Eigen::Matrix3d> R;  // as written (the transform uses its nearest rotation)
  Eigen::Vector3d rotvec_deg = Eigen::Vector3d::Zero();  // when R is absent
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Rigid3d value;

  static TransformSpec Identity() { return TransformSpec{}; }
};

struct CameraSpec {
  std::string file;  // as written, relative to the chain's folder; empty for an inline camera
  Camera camera;     // image_size, K and distortion (the file's or the inline ones)
  std::optional<ParameterCovariance> covariance;
};

// One distribution of a term, per component, in the file's units (docs/formats.md#vst-chain-distributions).
struct DistributionSpec {
  enum class Kind { kNormal, kUniform, kFixed };
  Kind kind = Kind::kFixed;
  // normal: mean, sigma; uniform: min, max (half_width h is read as −h, h); fixed: value (second unused).
  std::vector<double> first, second;
};

// A term's distribution where the file puts it: sources.<source>[.<eye_key>][.<group>].<key>.
// "both": each eye draws its own value from it; "shared": one draw serves both eyes.
struct TermSpec {
  Term term;
  std::string eye_key;  // "", "left", "right", "both" or "shared"
  std::string key;      // the file key ("rotation_deg"; a lens parameter name for kLens)
  DistributionSpec distribution;
  // Empty: typed into the chain. Else the word written in its place, naming the measurement the
  // distribution was made from (docs/formats.md#vst-chain-measured): "tracker_noise" or "handeye"
  // (tracking's rotation_deg and translation: the tracker-noise file's σ's or those the handeye
  // file's joint solve estimated), "handeye" or "handeye-uncorrected" (tracking's latency_s).
  std::string from;
};

// sources.<source>.correlation.<key>: the correlation ρ between the left and the right eye's
// draw of a per-eye term, per component (docs/math/vst-chain.md#correlated-eyes).
struct CorrelationSpec {
  Term term;
  std::string key;          // the file key ("screen_shift_px"; a lens parameter name for kLens)
  std::vector<double> rho;  // one per component, each in [−1, 1]
};

// "rig": {"file": "<stereo@1 path>"}: a calib-stereo rig gives both cameras (their intrinsics and
// covariances) and camera_from_hmd's relative part: camera_from_hmd.right = right_from_left ·
// camera_from_hmd.left (docs/formats.md#vst-chain-rig).
struct RigSpec {
  std::string file;  // as written, relative to the chain's folder
  Rigid3d right_from_left;
  std::optional<ParameterCovariance> covariance;  // over RelativePoseTangentNames(): ω rad, ρ length unit
  std::optional<ParameterCovariance> joint_covariance;  // the rig's (StereoRig::joint_covariance)
};

// camera_extrinsic.right.covariance: "rig" (the rig file's) or an inline covariance over
// right_from_left.rx … .tz. A left perturbation of right_from_left in the right camera's frame is
// one of camera_from_hmd.right (the left camera held), so it is the right eye's camera_extrinsic
// rotation and translation, correlated.
struct ExtrinsicCovarianceSpec {
  bool from_rig = false;
  ParameterCovariance covariance;  // the inline one (from_rig: the rig's)
};

// camera_intrinsic.<eye_key>.covariance: "camera" (the camera file's) or an inline covariance.
struct IntrinsicCovarianceSpec {
  std::string eye_key;
  bool from_camera = false;
  ParameterCovariance covariance;  // the inline one (from_camera: each eye's camera file's)
};

// "handeye": {"file": "<handeye@1 path>"}: calib-handeye solve's X = hmd_from_camera, Z =
// tracker_from_board and δ with their covariance. It gives frames.camera_from_hmd.left = X⁻¹ and
// frames.tracker_from_world = Z (the chain's world is the calibration board's frame), and the
// sources that name "handeye" take their distributions from it (docs/math/vst-chain.md#measured-chain).
struct HandEyeReference {
  std::string file;  // as written, relative to the chain's folder
  HandEyeSolution measured;  // covariance empty for a file without one (a calib-synth truth)
  std::optional<double> measured_bootstrap_time_offset_sigma;  // the file's bootstrap σ_δ, when it has one
};

// "tracker_noise": {"file": "<tracker-noise@1 path>"}: calib-handeye noise's σ's, which
// tracking's rotation_deg and translation take when they say "tracker_noise".
struct TrackerNoiseReference {
  std::string file;
  TrackerNoise measured;
};

// sources.camera_extrinsic.rig.covariance (the camera head's mount) and
// sources.tracker_alignment.covariance: "handeye" (the handeye file's X or Z block) or inline over
// hmd_from_camera.rx … .tz or tracker_from_board.rx … .tz — the handeye file's names and tangent
// (left perturbation of X, hmd frame; of Z, tracker frame; ω rad, ρ length unit).
struct PoseCovarianceSpec {
  bool from_handeye = false;
  ParameterCovariance covariance;  // 6×6 in the names' order (from_handeye: the file's block)
};

// "joint_covariance": "rig" (the rig file's joint_covariance) or inline {"parameters", "matrix"}
// over left.<lens parameter>, right.<lens parameter> and right_from_left.rx … .tz: both cameras'
// lens errors and the right camera's pose error as one correlated draw, factored in that order
// (docs/math/vst-chain.md#joint-draw).
struct JointCovarianceSpec {
  bool from_rig = false;
  ParameterCovariance covariance;  // the inline one (from_rig: the rig's)
};

// display.field_of_view_deg of one eye: the angle the camera's image spans on the display,
// horizontally and (when given) vertically, each in (0°, 180°). Without a vertical angle the
// display keeps the camera's pixel aspect (docs/math/vst-chain.md#display-fov).
struct DisplayFieldOfView {
  double horizontal_deg = 0;
  std::optional<double> vertical_deg;
  bool operator==(const DisplayFieldOfView&) const = default;
};

struct ChainSpec {
  std::string file;  // the chain file's name as given, for messages
  std::string name;  // free text
  LengthUnit length_unit = LengthUnit::kMillimetre;
  uint64_t samples = 0;
  uint64_t seed = 0;
  TransformSpec tracker_from_world, hmd_from_tracker, world_from_virtual, world_from_object;
  std::array<TransformSpec, kNumEyes> camera_from_hmd;
  std::array<CameraSpec, kNumEyes> cameras;  // with a rig: its cameras (file empty)
  std::optional<RigSpec> rig;                 // with it, camera_from_hmd[1] is derived, not written
  double ipd = 0;
  Eigen::Vector3d eye_centre = Eigen::Vector3d::Zero();  // hmd frame (default: the cameras' midpoint)
  std::optional<double> camera_baseline;                  // documents the baseline when given
  double virtual_image_distance = 0;                      // length unit; 0 stands for "infinity"
  Eigen::Vector3d angular_velocity_deg_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();
  std::vector<ChainTestPoint> test_points;
  std::vector<TermSpec> terms;  // in kTerms order, then eye key and key
  std::vector<CorrelationSpec> correlations;  // in kTerms order, then key
  std::vector<IntrinsicCovarianceSpec> intrinsic_covariances;
  std::optional<ExtrinsicCovarianceSpec> extrinsic_covariance;  // the right eye's
  std::vector<Eigen::Vector3d> fiducials;  // the fiducial form of virtual_object_alignment (empty: pose form)
  double fle_rms = 0;
  // The file's own provenance, kept as written: a normalised chain says the same as its input.
  std::optional<OrderedJson> provenance;
  std::optional<HandEyeReference> handeye;
  std::optional<TrackerNoiseReference> tracker_noise;
  std::optional<PoseCovarianceSpec> mount_covariance;      // sources.camera_extrinsic.rig.covariance
  std::optional<PoseCovarianceSpec> alignment_covariance;  // sources.tracker_alignment.covariance
  std::optional<JointCovarianceSpec> joint_covariance;
  std::array<std::optional<DisplayFieldOfView>, kNumEyes> display_field_of_view;  // absent: the camera's

  // The renderer's lens model of each eye: the camera's, or the smallest model of the variant
  // that also holds every lens parameter the chain names for that eye.
  std::array<AnyLensModel, kNumEyes> RendererLenses() const;
};

// The default virtual image distance: 1.5 m in the chain's length unit (docs/math/vst-chain.md#display:
// fixed-focus consumer HMDs put it at 1.3–2 m).
double DefaultVirtualImageDistance(LengthUnit unit);

// The model of a chain: geometry from the frames, cameras, display and test points, the θ layout
// from the shape, every term's distribution converted to internal units, the covariance mixing.
// InputError naming the file and field for geometry the simulation cannot use (a test point the
// error-free chain does not see).
ChainModel BuildChainModel(const ChainSpec& spec);

}  // namespace vstcal
