#include "support/handeye_scenes.h"

#include "vstcal/handeye/synthetic.h"

namespace vstcal::testing {

namespace {

Camera TestCamera() { return Camera::FromK((Eigen::Matrix3d() << 600, 0, 319.5, 0, 600, 239.5, 0, 0, 1).finished(), ImageSize{640, 480}); }

HandEyeSpec Spec(double delta, double noise_px, uint64_t seed, bool one_axis, int views) {
  HandEyeSpec spec;
  spec.hmd_from_camera = kHmdFromCamera;
  spec.tracker_from_board = kTrackerFromBoard;
  spec.time_offset = delta;
  spec.noise_px = noise_px;
  spec.seed = seed;
  spec.one_axis = one_axis;
  spec.views = views;
  return spec;
}

}  // namespace

HandEyeRigRecording RecordHandEyeRig(double delta, double noise_px, uint64_t seed, int views) {
  HandEyeRigRecording r;
  r.left.camera = r.rig.right = TestCamera();
  HandEyeSpec spec = Spec(delta, noise_px, seed, false, views);
  spec.right_from_left = kRightFromLeft;
  vstcal::HandEyeRecording made = SynthesizeHandEye(r.left.camera, spec);
  r.left.log = std::move(made.log);
  r.left.views = std::move(made.views);
  r.rig.right_from_left = kRightFromLeft;
  r.rig.views = std::move(made.right_views);
  return r;
}

HandEyeSpec HandEyeTestSpec(double delta, double noise_px, uint64_t seed) { return Spec(delta, noise_px, seed, false, 30); }

HandEyeRecording RecordHandEye(const HandEyeSpec& spec) {
  HandEyeRecording r;
  r.camera = TestCamera();
  vstcal::HandEyeRecording made = SynthesizeHandEye(r.camera, spec);
  r.log = std::move(made.log);
  r.views = std::move(made.views);
  return r;
}

HandEyeRecording RecordHandEye(double delta, double noise_px, uint64_t seed, bool one_axis, int views) {
  return RecordHandEye(Spec(delta, noise_px, seed, one_axis, views));
}

}  // namespace vstcal::testing
