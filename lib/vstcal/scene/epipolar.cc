#include "vstcal/scene/epipolar.h"

#include "vstcal/geometry/rotation.h"

namespace vstcal {

Eigen::Matrix3d EssentialMatrix(const Rigid3d& right_from_left) { return Hat(right_from_left.t) * right_from_left.R; }

Eigen::Matrix3d FundamentalMatrix(const StereoRig& rig) {
  const Eigen::Matrix3d F = rig.right.camera.K().inverse().transpose() * EssentialMatrix(rig.right_from_left) *
                            rig.left.camera.K().inverse();
  return F(2, 2) != 0 ? Eigen::Matrix3d(F / F(2, 2)) : F;
}

}  // namespace vstcal
