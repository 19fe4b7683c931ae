#include "support/vst_scenes.h"

#include <gtest/gtest.h>

#include "vstcal/errsim/simulation.h"

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

OrderedJson ChainPose(double tx, double ty, double tz) { return {{"rotvec_deg", {0.0, 0.0, 0.0}}, {"t", {tx, ty, tz}}}; }
OrderedJson ChainNormal(double sigma) { return {{"distribution", "normal"}, {"sigma", sigma}}; }

OrderedJson ParallelRigChain(const OrderedJson& sources, double focal, double depth, const OrderedJson& joint) {
  const OrderedJson camera = {{"image_size", {1280, 720}},
                              {"K", {{focal, 0.0, 639.5}, {0.0, focal, 359.5}, {0.0, 0.0, 1.0}}},
                              {"distortion", {{"model", "none"}}}};
  OrderedJson c;
  c["format"] = "vstcal/vst-chain@1";
  c["length_unit"] = "mm";
  c["samples"] = 1000;
  c["seed"] = 5;
  c["frames"] = {{"tracker_from_world", ChainPose(0, 0, 0)},
                 {"hmd_from_tracker", ChainPose(0, 0, 0)},
                 {"camera_from_hmd", {{"left", ChainPose(31.5, 0, 0)}, {"right", ChainPose(-31.5, 0, 0)}}},
                 {"world_from_object", ChainPose(0, 0, 0)}};
  c["cameras"] = {{"left", camera}, {"right", camera}};
  c["display"] = {{"ipd", 63.0}, {"virtual_image_distance", "infinity"}};
  c["test_points"] = {{{"name", "axis"}, {"world", {0.0, 0.0, depth}}},
                      {{"name", "aside"}, {"world", {200.0, -100.0, 1200.0}}}};
  c["sources"] = sources;
  if (!joint.is_null()) c["joint_covariance"] = joint;
  return c;
}

void ExpectTheSameBitsWhateverThreadsAndShards(const ChainModel& model) {
  SimulationOptions one;
  one.samples = one.budget_samples = 3000;
  one.seed = 3;
  one.threads = 1;
  SimulationOptions two = one;
  two.threads = 2;
  two.shards = 2;
  const auto scenarios = MakeScenarios(model, true);
  const SimulationResult a = RunSimulation(scenarios, one, "d");
  SimulationResult b = RunSimulation(scenarios, two, "d");
  two.shard = 1;
  MergeSimulation(&b, RunSimulation(scenarios, two, "d"));
  for (size_t s = 0; s < a.summaries.size(); ++s) {
    for (size_t k = 0; k < a.summaries[s].plan().output_names.size(); ++k) {
      EXPECT_EQ(a.summaries[s].Statistics(k).rms, b.summaries[s].Statistics(k).rms);
      EXPECT_EQ(a.summaries[s].Statistics(k).max, b.summaries[s].Statistics(k).max);
    }
  }
}

}  // namespace vstcal::testing
