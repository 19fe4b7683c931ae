// The hand-eye tests' recording (unit, CLI, benchmark): SynthesizeHandEye (handeye/synthetic.h) with
// a 640×480 pinhole camera (f 600) ~600 mm from a 9×6 board of 30 mm squares for 10 s, the tracker
// at 100 Hz.
#pragma once

#include <cstdint>
#include <vector>

#include "vstcal/camera/camera.h"
#include "vstcal/handeye/refine.h"
#include "vstcal/handeye/synthetic.h"

namespace vstcal::testing {

inline const Rigid3d kHmdFromCamera = Rigid3d::FromRotvec(Eigen::Vector3d(0.1, -0.2, 0.3), Eigen::Vector3d(30, -20, 50));
inline const Rigid3d kTrackerFromBoard = Rigid3d::FromRotvec(Eigen::Vector3d(0.5, 0.1, -1.0), Eigen::Vector3d(1000, 200, 1500));

struct HandEyeRecording {
  Camera camera;  // 640×480 pinhole, f 600
  std::vector<TrackedPose> log;
  std::vector<TimedView> views;
};

// `one_axis`: the headset only turns about the board's normal (degenerate).
HandEyeRecording RecordHandEye(double delta, double noise_px, uint64_t seed, bool one_axis = false, int views = 30);

// The recording above as a spec to vary (tracker noise, grid, views), and its recording.
HandEyeSpec HandEyeTestSpec(double delta, double noise_px, uint64_t seed);
HandEyeRecording RecordHandEye(const HandEyeSpec& spec);

// A stereo rig on the headset: the right camera (the same lens) 64 mm to the left camera's right,
// toed in by 1.5°, both taking their views at the same times (left-frame-N, right-frame-N).
inline const Rigid3d kRightFromLeft = Rigid3d::FromRotvec(Eigen::Vector3d(0.004, -0.026, 0.003), Eigen::Vector3d(-64, 0.4, 0.8));
struct HandEyeRigRecording {
  HandEyeRecording left;
  HandEyeRig rig;
};
HandEyeRigRecording RecordHandEyeRig(double delta, double noise_px, uint64_t seed, int views = 30);

}  // namespace vstcal::testing
