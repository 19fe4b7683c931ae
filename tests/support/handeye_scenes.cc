#include "support/handeye_scenes.h"

#include "vstcal/handeye/synthetic.h"

namespace vstcal::testing {

HandEyeRecording RecordHandEye(double delta, double noise_px, uint64_t seed, bool one_axis, int views) {
  HandEyeRecording r;
  r.camera = Camera::FromK((Eigen::Matrix3d() << 600, 0, 319.5, 0, 600, 239.5, 0, 0, 1).finished(), ImageSize{640, 480});
  HandEyeSpec spec;
  spec.hmd_from_camera = kHmdFromCamera;
  spec.tracker_from_board = kTrackerFromBoard;
  spec.time_offset = delta;
  spec.noise_px = noise_px;
  spec.seed = seed;
  spec.one_axis = one_axis;
  spec.views = views;
  vstcal::HandEyeRecording made = SynthesizeHandEye(r.camera, spec);
  r.log = std::move(made.log);
  r.views = std::move(made.views);
  return r;
}

}  // namespace vstcal::testing
