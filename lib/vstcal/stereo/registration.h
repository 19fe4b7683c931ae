// Binocular registration (seed 000 §4.3): the pose of the rig in the world for each video frame,
// and the virtual points projected into both images (docs/math/stereo.md#registration).
//
// Three ways, so that a user can compare them on their own data:
//  - "left" (seed 000): PnP on the left image alone; the right pose by composition,
//    right_from_world = right_from_left · left_from_world (seed 000's R_r^w = R_l^w · R_r^l).
//  - "per-eye": each eye registered on its own (two PnPs), as a system without stereo calibration
//    would; the two poses need not agree with the rig.
//  - "joint": one pose of the rig from both eyes' pixels (right_from_left held), the maximum-
//    likelihood estimate when the rig is exact.
// Each PnP starts from the closed form (pnp.h) or, when given, from a pose (the previous frame's:
// tracking) and is refined by Levenberg–Marquardt (pose_refine.h).
#pragma once

#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "vstcal/scene/fit.h"
#include "vstcal/estimators/pnp.h"
#include "vstcal/estimators/pose_refine.h"
#include "vstcal/scene/stereo_rig.h"
#include "vstcal/scene/tracks.h"
#include "vstcal/core/enum_names.h"

namespace vstcal {

enum class RegistrationMode { kLeft, kPerEye, kJoint };
inline constexpr EnumNames<RegistrationMode, 3> kRegistrationModeNames = {{{RegistrationMode::kLeft, "left"}, {RegistrationMode::kPerEye, "per-eye"}, {RegistrationMode::kJoint, "joint"}}};
std::string_view RegistrationModeName(RegistrationMode mode);  // "left", "per-eye", "joint"
std::optional<RegistrationMode> RegistrationModeFromName(std::string_view name);

struct FrameRegistration {
  PoseStatus status = PoseStatus::kNoSolution;
  std::string failed_eye;  // "left" or "right" when status is not kOk
  Rigid3d left_from_world, right_from_world;
  // Reprojection of the tracked embedded points through each eye's pose (the right one also in
  // "left" mode when right pixels exist: how well the composed pose agrees with the right image).
  std::optional<ResidualStats> left_fit, right_fit;
  int iterations = 0;  // Levenberg–Marquardt iterations, summed over the eyes' solves
  // The virtual points in each image; nullopt behind the camera.
  std::vector<std::optional<Eigen::Vector2d>> virtual_left, virtual_right;
};

// One frame. `start` (left_from_world) replaces the closed-form start when given. Requires the
// frame's pixel vectors to have one entry per embedded point (right may be empty, except in
// per-eye mode, where a missing right eye fails the frame with kTooFewPoints).
FrameRegistration RegisterFrame(const StereoRig& rig, std::span<const Eigen::Vector3d> embedded, const TrackedFrame& frame,
                                std::span<const Eigen::Vector3d> virtual_points, RegistrationMode mode,
                                const std::optional<Rigid3d>& start = std::nullopt,
                                const PoseRefineOptions& refine = {});

struct RegistrationOptions {
  RegistrationMode mode = RegistrationMode::kLeft;
  // Start each frame from the previous frame's pose when it was registered (tracking) instead of
  // the closed form.
  bool warm_start = false;
  PoseRefineOptions refine;
};

// Every frame in order. The tracks must agree with the rig (CheckTracksAgainstRig).
std::vector<FrameRegistration> RegisterSequence(const StereoRig& rig, const Tracks& tracks,
                                                const RegistrationOptions& options);

// Throws InputError (naming the files) when the tracks and the rig disagree: length units, image
// sizes, right pixels without a right image size; DegenerateError when the embedded points are
// collinear (no frame could be registered).
void CheckTracksAgainstRig(const StereoRig& rig, const Tracks& tracks, std::string_view rig_name,
                           std::string_view tracks_name);

}  // namespace vstcal
