#include "support/stereo_rigs.h"

namespace vstcal::testing {

StereoRig ZedLikeRig(bool distorted) {
  StereoRig rig;
  rig.method = "assembled";
  rig.length_unit = LengthUnit::kMillimetre;
  Eigen::Matrix3d Kl, Kr;
  Kl << 700.5, 0, 641.3, 0, 698.2, 362.9, 0, 0, 1;
  Kr << 701.75, 0, 637.9, 0, 699.1, 358.4, 0, 0, 1;
  const double dl[5] = {-0.171, 0.028, 7e-4, -4e-4, -2.1e-3};
  const double dr[5] = {-0.168, 0.026, -3e-4, 5e-4, -1.9e-3};
  rig.left.name = "left";
  rig.right.name = "right";
  rig.left.method = rig.right.method = "synthetic";
  rig.left.camera = distorted ? Camera::FromK(Kl, {1280, 720}, RadialTangentialModel{}, dl) : Camera::FromK(Kl, {1280, 720});
  rig.right.camera = distorted ? Camera::FromK(Kr, {1280, 720}, RadialTangentialModel{}, dr) : Camera::FromK(Kr, {1280, 720});
  rig.right_from_left = Rigid3d::FromRotvec(Eigen::Vector3d(0.002, -0.004, 0.001), Eigen::Vector3d(-63.0, 0.2, -0.4));
  return rig;
}

ParameterCovariance SampleRelativePoseCovariance() {
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Identity();
  const double s[6] = {8.7e-4, 8.7e-4, 8.7e-4, 0.2, 0.1, 0.3};
  A(3, 0) = 0.3;
  A(5, 1) = -0.2;
  A(4, 3) = 0.1;
  for (int i = 0; i < 6; ++i) A.row(i) *= s[i];
  ParameterCovariance c;
  const auto& names = RelativePoseTangentNames();
  c.parameters.assign(names.begin(), names.end());
  c.matrix = A * A.transpose();
  return c;
}

}  // namespace vstcal::testing
