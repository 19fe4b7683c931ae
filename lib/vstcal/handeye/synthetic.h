// A synthetic hand-eye recording with known truth (calib-synth --rig handeye; the tests): a headset
// carrying the camera moves in front of a fixed board for `duration` seconds, turning about all
// three axes (or, for the degenerate case, about the board's normal only); the tracker reports
// tracker_from_hmd at `rate_hz` on its clock, the camera takes `views` images whose times are δ
// behind (a view at camera time t shows the pose at tracker time t + δ).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "vstcal/camera/camera.h"
#include "vstcal/handeye/refine.h"

namespace vstcal {

struct HandEyeSpec {
  Rigid3d hmd_from_camera = Rigid3d::FromRotvec(Eigen::Vector3d(0.1, -0.2, 0.3), Eigen::Vector3d(30, -20, 50));
  Rigid3d tracker_from_board = Rigid3d::FromRotvec(Eigen::Vector3d(0.5, 0.1, -1.0), Eigen::Vector3d(1000, 200, 1500));
  int grid_cols = 9, grid_rows = 6;
  double spacing = 30;         // length unit
  double distance = 600;       // the camera's typical distance from the board
  double duration = 10;        // s
  double rate_hz = 100;        // the tracker's
  int views = 30;              // images, spread evenly over [0.05, 0.95] of the duration
  double time_offset = 0.03;   // δ, s
  // A camera clock not locked to the tracker's: each view's time is moved later by a uniform draw
  // in [0, view_jitter) s. With 0 every view keeps its place between the tracker's reports (the
  // evenly spread times fall on one phase of the report interval, as with a genlocked camera).
  double view_jitter = 0;
  double noise_px = 0;         // corners
  double tracker_noise_deg = 0, tracker_noise = 0;  // per axis, on each report (rotation, length unit)
  bool one_axis = false;
  uint64_t seed = 1;
  // A stereo rig: a second camera (the same lens) at right_from_left, taking its views at the same
  // times as the left one; the views are then named left-frame-N and right-frame-N.
  std::optional<Rigid3d> right_from_left;
};

struct HandEyeRecording {
  std::vector<TrackedPose> log;
  std::vector<TimedView> views;  // corners inside the image only
  std::vector<Rigid3d> camera_from_board;  // each view's true pose (for rendering its image)
  // With a rig: the right camera's views (its corners' noise drawn apart from the left's).
  std::vector<TimedView> right_views;
  std::vector<Rigid3d> right_camera_from_board;
};

// Throws InputError for a spec that cannot be recorded (non-positive sizes, rates or duration,
// fewer than 2 views, no corner in the image).
HandEyeRecording SynthesizeHandEye(const Camera& camera, const HandEyeSpec& spec);

}  // namespace vstcal
