#include "vstcal/scene/calibrated_camera.h"

#include <cmath>

namespace vstcal {

Matrix34d ProjectionMatrix(const Eigen::Matrix3d& K, const Rigid3d& camera_from_world) {
  return NormalizeProjectionScale(K * camera_from_world.matrix3x4());
}

Matrix34d NormalizeProjectionScale(const Matrix34d& P, double sign) {
  const Eigen::Vector3d r = P.row(2).head<3>();
  double norm = r.norm();
  // World coordinates of 1e±300 make this row tiny or huge: its square would underflow or
  // overflow. Scaled by its largest entry first there (elsewhere the plain norm keeps its bits).
  if (!(norm > 1e-150 && norm < 1e150)) {
    const double largest = r.cwiseAbs().maxCoeff();
    if (largest > 0 && std::isfinite(largest)) norm = (r / largest).norm() * largest;
  }
  return P * (sign / norm);
}

}  // namespace vstcal
