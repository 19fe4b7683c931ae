// Golden numbers: calib-dlt on every shipped dataset against (1) the independent NumPy reference
// in datasets/golden/ (scripts/golden/dlt_reference.py) and (2) the ground truth the dataset was
// generated from, within 1e-8 for noise-free data and within 6σ of the Cramér–Rao bound for
// noisy data (the DLT reaches 1.0–1.1× the bound here: tests/unit/dlt_test.cc).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "support/crb.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"

namespace vstcal {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = VSTCAL_SOURCE_DIR;

Eigen::MatrixXd JsonMatrix(const nlohmann::json& j) {
  Eigen::MatrixXd m(j.size(), j[0].is_array() ? j[0].size() : 1);
  for (size_t r = 0; r < j.size(); ++r) {
    if (j[r].is_array()) {
      for (size_t c = 0; c < j[r].size(); ++c) m(r, c) = j[r][c].get<double>();
    } else {
      m(r, 0) = j[r].get<double>();
    }
  }
  return m;
}

struct Solved {
  CalibratedCamera camera;
  nlohmann::json json;
};

// Runs the calib-dlt binary like a user would and reads what it wrote.
Solved RunCalibDlt(const std::string& dataset) {
  std::string file_name = "vstcal-golden-";
  file_name.append(std::to_string(::getpid())).append("-").append(fs::path(dataset).parent_path().filename().string());
  file_name.append("-").append(fs::path(dataset).stem().string()).append(".json");
  const fs::path out = fs::temp_directory_path() / file_name;
  std::string command = "\"";  // appended piecewise: GCC 12's -Wrestrict misfires on chains of +
  command.append(VSTCAL_TOOLS_DIR).append("/calib-dlt\" -q \"").append((kRoot / dataset).string());
  command.append("\" -o \"").append(out.string()).append("\"");
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  Solved s;
  s.camera = ReadCamera(out);
  std::ifstream in(out);
  s.json = nlohmann::json::parse(in);
  fs::remove(out);
  return s;
}

nlohmann::json Golden(const std::string& name) {
  std::ifstream in(kRoot / "datasets/golden" / ("dlt-" + name + ".json"));
  return nlohmann::json::parse(in);
}

class GoldenDlt : public ::testing::TestWithParam<std::string> {};

TEST_P(GoldenDlt, MatchesNumpyReference) {
  const std::string name = GetParam();  // e.g. "seed000-noisy"
  const std::string dataset = "datasets/" + name.substr(0, name.find('-')) + "/" + name.substr(name.find('-') + 1) + ".json";
  const Solved s = RunCalibDlt(dataset);
  const nlohmann::json g = Golden(name);
  ASSERT_EQ(g["dataset"], dataset);
  const Eigen::MatrixXd P = JsonMatrix(s.json["P"]), Pg = JsonMatrix(g["P"]);
  EXPECT_LT((P - Pg).norm() / Pg.norm(), 1e-9);
  EXPECT_LT((s.camera.camera.K() - JsonMatrix(g["K"])).norm() / JsonMatrix(g["K"]).norm(), 1e-9);
  EXPECT_LT((s.camera.camera_from_world->R - JsonMatrix(g["R"])).norm(), 1e-9);
  const Eigen::VectorXd tg = JsonMatrix(g["t"]);
  EXPECT_LT((s.camera.camera_from_world->t - tg).norm() / tg.norm(), 1e-9);
  EXPECT_NEAR(s.json["fit"]["rms_px"].get<double>(), g["rms_px"].get<double>(), 1e-9);
  EXPECT_NEAR(s.json["fit"]["max_px"].get<double>(), g["max_px"].get<double>(), 1e-9);
  EXPECT_NEAR(s.json["dlt"]["normalized_system"]["sigma_11"].get<double>(), g["sigma_11"].get<double>(),
              1e-9 * g["sigma_11"].get<double>());
  ASSERT_EQ(s.json["fit"]["test_points"].size(), g["test_points"].size());
  for (size_t i = 0; i < g["test_points"].size(); ++i) {
    EXPECT_EQ(s.json["fit"]["test_points"][i]["name"], g["test_points"][i]["name"]);
    EXPECT_NEAR(s.json["fit"]["test_points"][i]["error_px"].get<double>(), g["test_points"][i]["error_px"].get<double>(),
                1e-9);
  }
}

TEST_P(GoldenDlt, RecoversGroundTruth) {
  const std::string name = GetParam();
  const std::string stem = "datasets/" + name.substr(0, name.find('-')) + "/" + name.substr(name.find('-') + 1);
  const Solved s = RunCalibDlt(stem + ".json");
  const CalibratedCamera truth = ReadCamera(kRoot / (stem + ".truth.json"));
  const Eigen::Matrix3d K = s.camera.camera.K(), Kt = truth.camera.K();
  const Rigid3d& pose = *s.camera.camera_from_world;
  const Rigid3d& pose_t = *truth.camera_from_world;
  if (name.ends_with("clean")) {
    EXPECT_LT((K - Kt).norm() / Kt.norm(), 1e-8);
    EXPECT_LT(AngleBetween(pose.R, pose_t.R), 1e-8);
    EXPECT_LT((pose.t - pose_t.t).norm() / pose_t.t.norm(), 1e-8);
    EXPECT_LT(s.json["fit"]["rms_px"].get<double>(), 1e-8);
    return;
  }
  // Noisy (σ = 0.2 px): within 6σ of the Cramér–Rao bound, parameter by parameter.
  const Correspondences c = ReadCorrespondences(kRoot / (stem + ".json"));
  const std::vector<Observation> obs = AllObservations(c);
  const testing::Matrix11d crb = testing::PinholeCrb(truth.camera, pose_t, obs, 0.2);
  const double K_err[5] = {K(0, 0) - Kt(0, 0), K(1, 1) - Kt(1, 1), K(0, 2) - Kt(0, 2), K(1, 2) - Kt(1, 2), K(0, 1) - Kt(0, 1)};
  for (int i = 0; i < 5; ++i) EXPECT_LT(std::abs(K_err[i]), 6 * std::sqrt(crb(i, i))) << "K parameter " << i;
  // Pose error as a left perturbation in the camera frame (the CRB's parametrization).
  const Rigid3d delta = pose * pose_t.inverse();
  const Eigen::Vector3d omega = RotvecFromRotation(delta.R);
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::abs(omega(i)), 6 * std::sqrt(crb(5 + i, 5 + i))) << "rotation " << i;
    EXPECT_LT(std::abs(delta.t(i)), 6 * std::sqrt(crb(8 + i, 8 + i))) << "translation " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedDatasets, GoldenDlt,
                         ::testing::Values("seed000-clean", "seed000-noisy", "zedmini-clean", "zedmini-noisy"));

}  // namespace
}  // namespace vstcal
