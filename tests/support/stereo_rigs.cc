#include "support/stereo_rigs.h"

#include <cmath>
#include <tuple>

#include "vstcal/geometry/rotation.h"
#include "vstcal/random/philox.h"

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

StereoViews SyntheticStereoViews(const StereoRig& rig, int views, uint64_t seed) {
  StereoViews out;
  for (auto [c, camera] : {std::pair{&out.left, &rig.left}, std::pair{&out.right, &rig.right}}) {
    c->camera = camera->name;
    c->image_size = camera->camera.image_size;
    c->length_unit = rig.length_unit;
    c->rig = Rig::kPlanarViews;
  }
  const CounterRng rng(seed, 0x57E2u);
  const Eigen::Vector3d centre(4 * 30.0, 2.5 * 30.0, 0);
  for (int k = 0; k < views; ++k) {
    const auto a = rng.Uniform2(static_cast<uint64_t>(k), 0), b = rng.Uniform2(static_cast<uint64_t>(k), 1);
    const double tilt = DegToRad(30.0) * a[0], axis = 2 * kPi * a[1], roll = DegToRad(40.0 * (b[0] - 0.5));
    const Eigen::Matrix3d R = RotationFromRotvec(Eigen::Vector3d(tilt * std::cos(axis), tilt * std::sin(axis), 0)) *
                              RotationFromRotvec(Eigen::Vector3d(0, 0, roll));
    const Rigid3d left_from_board{R, Eigen::Vector3d(30.0, 0, 450.0 + 300.0 * b[1]) - R * centre};
    out.left_from_board.push_back(left_from_board);
    for (auto [c, camera, from_board] : {std::tuple{&out.left, &rig.left, left_from_board},
                                         std::tuple{&out.right, &rig.right, rig.right_from_left * left_from_board}}) {
      View view;
      view.name = "view" + std::to_string(k);
      for (int row = 0; row < 6; ++row) {
        for (int col = 0; col < 9; ++col) {
          const Eigen::Vector3d X(30.0 * col, 30.0 * row, 0);
          const auto px = camera->camera.Project(from_board * X);
          if (px && camera->camera.InImage(*px)) view.observations.push_back({X, *px, 1.0});
        }
      }
      c->views.push_back(std::move(view));
    }
  }
  return out;
}

}  // namespace vstcal::testing
