#include "support/vst_scenes.h"

namespace vstcal::testing {

namespace {
Rigid3d Pose(double rx, double ry, double rz, double tx, double ty, double tz) {
  return Rigid3d::FromRotvec(Eigen::Vector3d(rx, ry, rz), Eigen::Vector3d(tx, ty, tz));
}
}  // namespace

Eigen::Vector3d WorldFromHmdPoint(const Eigen::Vector3d& point_in_hmd) {
  return point_in_hmd - Eigen::Vector3d(0, 0, 2000);
}

ChainGeometry ParallelRig(std::vector<Eigen::Vector3d> points_in_world, double focal, double baseline) {
  ChainGeometry g;
  g.length_unit = LengthUnit::kMillimetre;
  // hmd_from_world = translation (0, 0, 2000): the tracker is an arbitrary frame in between.
  g.tracker_from_world = Pose(0.3, -0.2, 0.1, 150, -400, 900);
  g.hmd_from_tracker = Pose(0, 0, 0, 0, 0, 2000) * g.tracker_from_world.inverse();
  for (int e = 0; e < kNumEyes; ++e) {
    g.camera_from_hmd[e] = Rigid3d{Eigen::Matrix3d::Identity(), Eigen::Vector3d((e == 0 ? 0.5 : -0.5) * baseline, 0, 0)};
    Eigen::Matrix3d K;
    K << focal, 0, 639.5, 0, focal, 359.5, 0, 0, 1;
    g.cameras[e] = Camera::FromK(K, {1280, 720});
  }
  g.world_from_virtual = Pose(0.05, 0.02, -0.03, 10, 20, -30);
  g.world_from_object = Pose(-0.1, 0.2, 0.05, 300, 0, 100);
  g.display.ipd = baseline;
  g.display.eye_centre_in_hmd = Eigen::Vector3d::Zero();
  g.display.inverse_image_distance = 0;  // collimated: the closed forms that do not need the optics
  for (size_t i = 0; i < points_in_world.size(); ++i) {
    g.test_points.push_back({std::string("p").append(std::to_string(i)), points_in_world[i], std::nullopt});
  }
  return g;
}

}  // namespace vstcal::testing
