// The VST registration chain of seed 001 (§3.2, Fig. 5, Eq. 8) as data: the nominal geometry of
// both eyes' cameras, the display and the viewer, and the parameter vector θ that perturbs it
// (schema.h declares θ; docs/math/vst-chain.md derives the model). chain.h evaluates it;
// formats/chain_reader.h reads it from vstcal/vst-chain@1.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/camera/camera.h"
#include "vstcal/core/units.h"
#include "vstcal/errsim/schema.h"
#include "vstcal/errsim/sources.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/sensitivity/distribution.h"

namespace vstcal {

struct ChainTestPoint {
  std::string name;
  Eigen::Vector3d point_in_world = Eigen::Vector3d::Zero();
  // For the occlusion decision (rendering): camera depth of the real surface seen behind the point
  // minus the point's own depth, length unit. > 0: the overlay is in front of the real surface
  // and must be drawn; < 0: a real surface hides it. Absent: no occlusion figure for the point.
  std::optional<double> surface_behind;
};

// The viewer's side of a VST display (docs/math/vst-chain.md#display). The display shows eye e the
// video of camera e: pixel q at the point V_e(q) = E⁰_e + D·d_e(q) of a virtual image plane at
// distance D in front of the design eyepoint E⁰_e, d_e(q) the camera's ray through q (K⁻¹ of the
// true camera, along the camera's nominal axes; z component 1 in the camera frame).
struct DisplayGeometry {
  // Design IPD: the display's eyepoints are E⁰ = eye_centre ∓ ipd/2 along hmd x (left at −x).
  double ipd = 0;
  // Midpoint of the design eyepoints, hmd frame. An eyepoint is the eye's centre of rotation (the
  // point a fixating eye's lines of sight pass through; Vaissie & Rolland 2000). Away from the
  // cameras' midpoint it is the camera–eye offset: the seen world is displaced by it.
  Eigen::Vector3d eye_centre_in_hmd = Eigen::Vector3d::Zero();
  // 1/D, the inverse distance of the virtual image (0: a collimated display, image at infinity).
  double inverse_image_distance = 0;

  // The display's own focal lengths (fx, fy) of eye e, in the camera's pixels: the camera's image
  // spans the display's field of view, so pixel q is shown along ((q_u − c_x − s'·y)/fx, (q_v −
  // c_y)/fy, 1) with s' the camera's skew scaled by fx/f_x (docs/math/vst-chain.md#display-fov).
  // Absent: the camera's own (an orthoscopic display). A display wider than the camera magnifies.
  std::array<std::optional<Eigen::Vector2d>, kNumEyes> focal_px = {};

  Eigen::Vector3d DesignEyepoint(int eye) const {
    return eye_centre_in_hmd + Eigen::Vector3d((eye == 0 ? -0.5 : 0.5) * ipd, 0, 0);
  }
};

// Nominal (true) geometry. Frames as docs/conventions.md: x_a = a_from_b · x_b.
struct ChainGeometry {
  LengthUnit length_unit = LengthUnit::kMillimetre;
  Rigid3d tracker_from_world;
  Rigid3d hmd_from_tracker;  // the head pose at the instant the video frame is captured
  std::array<Rigid3d, kNumEyes> camera_from_hmd;
  Rigid3d world_from_virtual;  // the virtual-world alignment: where the engine's origin sits in the cell
  Rigid3d world_from_object;   // the physical object (robot base); its virtual twin has the same nominal pose
  std::array<Camera, kNumEyes> cameras;  // the physical cameras' true intrinsics, any lens model
  DisplayGeometry display;
  // Head motion for the dynamic errors: body rates in the hmd frame.
  Eigen::Vector3d head_angular_velocity = Eigen::Vector3d::Zero();  // rad/s
  Eigen::Vector3d head_linear_velocity = Eigen::Vector3d::Zero();   // length unit / s
  std::vector<ChainTestPoint> test_points;

  // Distance between the two camera centres (length unit).
  double CameraBaseline() const;
  // Midpoint of the camera centres, hmd frame.
  Eigen::Vector3d CameraCentre() const;
};


// The distribution of s·θ, for θ ~ d (halving a source is Scaled(d, 0.5)); s ≥ 0.
Distribution Scaled(const Distribution& d, double s);

// Where a parameter's distribution came from (issue 21 item 4; docs/formats.md#err-sim-report):
// typed into the chain ("assumed"), or a measurement's file — a camera@1 or stereo@1 covariance, a
// handeye@1 or tracker-noise@1 file ("measured").
struct DistributionOrigin {
  std::string file;    // as the chain names it; empty: assumed
  std::string format;  // "vstcal/camera@1", "vstcal/stereo@1", "vstcal/handeye@1", "vstcal/tracker-noise@1"
  bool measured() const { return !file.empty(); }
  bool operator==(const DistributionOrigin&) const = default;
};

// One slot of θ with its distribution (internal units; file units in `slot`).
struct ChainParameter {
  SlotInfo slot;
  Source source = Source::kTrackerAlignment;
  Distribution distribution = Distribution::MakeFixed(0);
  const std::string& name() const { return slot.name; }
  DistributionOrigin origin = {};  // assumed unless the chain reader says otherwise
};

struct ChainModel {
  ChainGeometry geometry;
  // Fiducial layout in the object frame. Empty: virtual_object_alignment is given as pose errors.
  std::vector<Eigen::Vector3d> fiducials_in_object;
  // The renderer's camera per eye: its lens model holds the true camera's (it may carry distortion
  // terms the true lens lacks, at 0 nominally) and its nominal parameters are the true camera's.
  std::array<Camera, kNumEyes> renderer;
  // Camera::ValidRadiusSquared of each renderer lens (its nominal parameters): a virtual point
  // beyond it is outside the lens's valid domain and the sample undefined there.
  std::array<double, kNumEyes> renderer_valid_radius2{};
  // Lens-parameter error of eye e = intrinsic_mixing[e] · θ's kLens block of e (square, the
  // renderer's parameter count). Identity when σ's are given per parameter; V Λ^½ of a
  // calibration's covariance when θ holds standard normals.
  std::array<Eigen::MatrixXd, kNumEyes> intrinsic_mixing;
  // Camera-pose error (ω, ρ) of eye e = extrinsic_mixing[e] · (θ's kCameraRotation, kCameraTranslation
  // blocks of e). Identity for σ's per component; V Λ^½ of a rig's right_from_left covariance
  // (camera_extrinsic.right.covariance) when those six slots hold standard normals.
  using Matrix6d = Eigen::Matrix<double, 6, 6>;
  std::array<Matrix6d, kNumEyes> extrinsic_mixing = {Matrix6d::Identity(), Matrix6d::Identity()};
  // Errors shared or correlated between the eyes (docs/math/vst-chain.md#correlated-eyes) and a
  // rig's joint covariance (#joint-draw): the chain reads slot `to` of θ as θ[to] + Σ alpha·θ[from]
  // over the couplings into it, each θ[from] as drawn (not itself coupled). A shared term has
  // alpha 1 from the left eye's slot and θ[right] fixed at 0; a correlation ρ has alpha =
  // ρ·σ_R/σ_L and θ[right] ~ N(μ_R − alpha·μ_L, σ_R·√(1 − ρ²)); a joint covariance Σ = L D Lᵀ
  // has alpha = L(j, k) from slot k to slot j and θ[k] ~ N(0, D_k). The slots of θ stay
  // independent (what Sobol indices and linear propagation assume) and the map is linear in θ, so
  // scaling a source scales the coupled error with it.
  struct SlotCoupling {
    int from = 0, to = 0;
    double alpha = 0;
  };
  std::vector<SlotCoupling> couplings;  // in (to, from) order
  ParameterLayout layout;
  std::vector<ChainParameter> parameters;  // size layout.size(), in θ order
  uint64_t samples = 0;
  uint64_t seed = 0;
  // The warnings of the measurement files the chain takes distributions from, each "<file>: <warning>"
  // (a handeye@1 file's `warnings`): a budget built on a σ its own file doubts says so.
  std::vector<std::string> measurement_warnings;

  // Pose errors of the whole camera head (θ's kRigRotation, kRigTranslation: the mount, hmd frame)
  // and of the tracker's alignment (kTrackerAlignmentRotation, kTrackerAlignmentTranslation) as
  // mixed from six standard normals: (ω, ρ) = M·z, M = V Λ^½ of a measured 6×6 covariance (a
  // handeye@1 file's X or Z block; docs/math/vst-chain.md#measured-chain). Identity: σ's per component.
  Matrix6d mount_mixing = Matrix6d::Identity();
  Matrix6d tracker_alignment_mixing = Matrix6d::Identity();

  // A model with every parameter at fixed 0. The renderer's lens of eye e is `renderer_lens[e]`
  // when given (it must hold the camera's parameters), else the camera's own model.
  static ChainModel WithZeroErrors(ChainGeometry geometry, std::vector<Eigen::Vector3d> fiducials_in_object = {},
                                   const std::optional<std::array<AnyLensModel, kNumEyes>>& renderer_lens = std::nullopt);

  // The parameter of a slot by name; nullptr if there is none.
  ChainParameter* Find(const std::string& name);
  // Nominal θ (every parameter's mean; the error-free θ is all 0), and copies with some sources
  // switched off (fixed 0) or scaled (every draw multiplied by `factor`).
  std::vector<double> MeanTheta() const;
  ChainModel WithSources(const std::array<bool, kNumSources>& active) const;
  ChainModel WithSourceScaled(Source source, double factor) const;
  bool SourceActive(Source source) const;  // some parameter of the source is not fixed at 0
};

// θ as the chain reads it: coupled[j] = θ[j] + Σ alpha·θ[from] over the couplings into j (the
// parameters' errors themselves, in internal units). `coupled` holds model.layout.size() values.
template <typename T>
void ApplyCouplings(const ChainModel& model, const T* theta, T* coupled) {
  const size_t n = model.parameters.size();
  for (size_t j = 0; j < n; ++j) coupled[j] = theta[j];
  for (const ChainModel::SlotCoupling& c : model.couplings) coupled[c.to] += T(c.alpha) * theta[c.from];
}

}  // namespace vstcal
