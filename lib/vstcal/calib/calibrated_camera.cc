#include "vstcal/calib/calibrated_camera.h"

namespace vstcal {

Matrix34d ProjectionMatrix(const Eigen::Matrix3d& K, const Rigid3d& camera_from_world) {
  return NormalizeProjectionScale(K * camera_from_world.matrix3x4());
}

Matrix34d NormalizeProjectionScale(const Matrix34d& P, double sign) {
  return P * (sign / P.row(2).head<3>().norm());
}

}  // namespace vstcal
