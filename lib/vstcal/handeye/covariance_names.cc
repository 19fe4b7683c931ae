#include "vstcal/handeye/covariance_names.h"

namespace vstcal {

// Declared once: the solver names its covariance with it, handeye@1 writes it, err-sim reads it.
const std::vector<std::string>& HandEyeCovarianceNames() {
  static const std::vector<std::string> names = {
      "hmd_from_camera.rx",    "hmd_from_camera.ry",    "hmd_from_camera.rz",    "hmd_from_camera.tx",    "hmd_from_camera.ty",
      "hmd_from_camera.tz",    "tracker_from_board.rx", "tracker_from_board.ry", "tracker_from_board.rz", "tracker_from_board.tx",
      "tracker_from_board.ty", "tracker_from_board.tz", "time_offset"};
  return names;
}

const std::vector<std::string>& HandEyeNoiseCovarianceNames() {
  static const std::vector<std::string> names = {"tracker_noise.rotation", "tracker_noise.translation"};
  return names;
}

}  // namespace vstcal
