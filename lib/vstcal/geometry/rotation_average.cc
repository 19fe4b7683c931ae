#include "vstcal/geometry/rotation_average.h"

#include <Eigen/SVD>

#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal {

Eigen::Matrix3d ChordalMeanRotation(std::span<const Eigen::Matrix3d> rotations) {
  VSTCAL_CHECK(!rotations.empty(), "a mean of no rotations");
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const Eigen::Matrix3d& R : rotations) sum += R;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

Eigen::Matrix3d GeodesicL1MeanRotation(std::span<const Eigen::Matrix3d> rotations, int iterations) {
  Eigen::Matrix3d R = ChordalMeanRotation(rotations);
  // A rotation closer than this to R is R itself: Weiszfeld's weight 1/∠ would be unbounded there.
  constexpr double kCoincident = 1e-12;
  for (int it = 0; it < iterations; ++it) {
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    double weights = 0;
    for (const Eigen::Matrix3d& Rv : rotations) {
      const Eigen::Vector3d r = RotvecFromRotation(R.transpose() * Rv);
      const double angle = r.norm();
      if (angle < kCoincident) continue;
      weighted += r / angle;
      weights += 1 / angle;
    }
    if (weights == 0) break;
    const Eigen::Vector3d step = weighted / weights;
    R = R * RotationFromRotvec(step);
    if (step.norm() < kCoincident) break;
  }
  return R;
}

}  // namespace vstcal
