// err-sim reading a stereo@1 rig (docs/formats.md#vst-chain-rig): a chain that references a rig
// and its covariance is the same chain as the one written out by hand (same digest, same Monte
// Carlo bits); the covariance reaches the right camera's pose with the rig's covariance (closed
// forms of the baseline's and the relative rotation's σ from the matrix, and the mixed slots
// through the chain itself).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/stereo_rigs.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/formats/errsim/chain_reader.h"
#include "vstcal/formats/errsim/report_format.h"
#include "vstcal/errsim/sampler.h"
#include "vstcal/errsim/simulation.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/stereo/stereo_io.h"

namespace vstcal {
namespace {


const Provenance kProvenance{"errsim_rig_test", {}, std::nullopt};

OrderedJson Pose(double tx, double ty, double tz) { return {{"rotvec_deg", {0.0, 0.0, 0.0}}, {"t", {tx, ty, tz}}}; }
OrderedJson Normal(double sigma) { return {{"distribution", "normal"}, {"sigma", sigma}}; }

// A ZED-like rig (63 mm, slightly turned right camera) with a correlated right_from_left covariance.
StereoRig RigWithCovariance() {
  StereoRig rig = testing::ZedLikeRig();
  rig.covariance = testing::SampleRelativePoseCovariance();
  return rig;
}

// The chain around the rig: the hmd 1 m in front of the world origin, the left camera 31.5 mm left
// of the hmd origin, three test points, a left-camera pose error and tracking noise beside the
// rig's covariance. Without "rig" the caller adds cameras and camera_from_hmd.right.
OrderedJson ChainAroundRig() {
  OrderedJson c;
  c["format"] = "vstcal/vst-chain@1";
  c["length_unit"] = "mm";
  c["samples"] = 1000;
  c["seed"] = 11;
  c["frames"] = {{"tracker_from_world", Pose(0, 0, 0)},
                 {"hmd_from_tracker", Pose(0, 0, 1000)},
                 {"camera_from_hmd", {{"left", Pose(31.5, 0, 0)}}},
                 {"world_from_object", Pose(0, 0, 0)}};
  c["display"] = {{"ipd", 63.0}};
  c["test_points"] = {{{"name", "a"}, {"world", {0, 0, 0}}},
                      {{"name", "b"}, {"world", {100, -50, 200}}},
                      {{"name", "c"}, {"world", {-150, 80, -300}}}};
  c["sources"] = {{"tracking", {{"translation", Normal(1.0)}}},
                  {"camera_extrinsic", {{"left", {{"rotation_deg", Normal(0.02)}}}, {"right", {{"covariance", "rig"}}}}}};
  return c;
}

OrderedJson InlineCamera(const CalibratedCamera& c) {
  return {{"image_size", {c.camera.image_size.width, c.camera.image_size.height}},
          {"K", MatrixToJson(c.camera.K())},
          {"distortion", DistortionToJson(c.camera)}};
}

// The same chain written by hand: the rig's cameras inline, camera_from_hmd.right = right_from_left
// · camera_from_hmd.left as R and t, the covariance inline.
OrderedJson HandWrittenEquivalent(const StereoRig& rig) {
  OrderedJson c = ChainAroundRig();
  const Rigid3d right = rig.right_from_left * Rigid3d::FromRotvec(Eigen::Vector3d::Zero(), Eigen::Vector3d(31.5, 0, 0));
  c["frames"]["camera_from_hmd"]["right"] = {{"R", MatrixToJson(right.R)}, {"t", MatrixToJson(right.t)}};
  c["cameras"] = {{"left", InlineCamera(rig.left)}, {"right", InlineCamera(rig.right)}};
  c["sources"]["camera_extrinsic"]["right"]["covariance"] = {{"parameters", rig.covariance->parameters},
                                                             {"matrix", MatrixToJson(rig.covariance->matrix)}};
  return c;
}

class ErrSimRig : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) / ("errsim_rig_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "rig.json") << DumpJson(StereoRigToJson(rig_, kProvenance));
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  ChainModel Build(const OrderedJson& chain) const {
    return BuildChainModel(ChainSpecFromJson(JsonDocument::Parse(chain.dump(), "chain.json"), dir_));
  }
  OrderedJson WithRig() const {
    OrderedJson c = ChainAroundRig();
    c["rig"] = {{"file", "rig.json"}};
    return c;
  }

  StereoRig rig_ = RigWithCovariance();
  std::filesystem::path dir_;
};

// The report of a small run ("all" only: the budget's scenarios are the same chain with sources
// switched off or halved), as written.
std::string ReportOf(const ChainModel& model) {
  SimulationOptions options;
  options.samples = model.samples;
  options.budget = false;
  options.seed = model.seed;
  options.threads = 2;
  const RunDescription run{"chain.json", ChainDigest(model), {}, {}, options};
  const SimulationResult result = RunSimulation(MakeScenarios(model, false), options, run.digest);
  return DumpJson(ReportToJson(ChainEvaluator(model), result, run, kProvenance));
}

TEST_F(ErrSimRig, ChainFromARigIsTheHandWrittenChain) {
  const ChainModel from_rig = Build(WithRig());
  const ChainModel by_hand = Build(HandWrittenEquivalent(rig_));
  EXPECT_EQ(ChainDigest(from_rig), ChainDigest(by_hand));
  for (int e = 0; e < kNumEyes; ++e) {
    EXPECT_EQ(from_rig.geometry.camera_from_hmd[e].R, by_hand.geometry.camera_from_hmd[e].R);
    EXPECT_EQ(from_rig.geometry.camera_from_hmd[e].t, by_hand.geometry.camera_from_hmd[e].t);
    EXPECT_EQ(from_rig.geometry.cameras[e].params, by_hand.geometry.cameras[e].params);
  }
  // The right camera sits where the rig puts it: 63 mm (the rig's baseline) from the left one.
  EXPECT_NEAR(from_rig.geometry.CameraBaseline(), rig_.baseline(), 1e-12 * rig_.baseline());
  const std::string report = ReportOf(from_rig);
  EXPECT_EQ(report, ReportOf(by_hand));  // same seed: the same bits

  // The covariance matters: without it the report changes.
  OrderedJson without = WithRig();
  without["sources"]["camera_extrinsic"].erase("right");
  EXPECT_NE(ReportOf(Build(without)), report);
}

// θ's six right-eye slots are standard normals; the chain turns them into (ω, ρ) = M z. Over
// 20,000 draws the baseline |t'| of the estimated rig (Exp(ω) R, Exp(ω) t + ρ) has the σ of the
// closed form √(t̂ᵀ Σ_ρρ t̂) and ω_i the σ √Σ_ii, computed here from the matrix. The Monte Carlo
// standard error of a σ estimate is 1/√(2N) = 0.5 %: 3 % is six of them. The first-order baseline
// σ is exact to (σ_ρ⊥²/2|t|)/σ ≈ 0.2 % here (|t| = 63 mm, σ_ρ ≤ 0.3 mm).
TEST_F(ErrSimRig, CovarianceGivesTheRigsBaselineAndRotationSigma) {
  const ChainModel model = Build(WithRig());
  const Eigen::Matrix<double, 6, 6> sigma = rig_.covariance->matrix;  // parameters in rx … tz order
  ASSERT_EQ(rig_.covariance->parameters[0], "right_from_left.rx");
  ASSERT_EQ(rig_.covariance->parameters[5], "right_from_left.tz");
  const auto& mixing = model.extrinsic_mixing[1];
  EXPECT_LT((mixing * mixing.transpose() - sigma).norm(), 1e-12 * sigma.norm());
  EXPECT_TRUE(model.extrinsic_mixing[0].isIdentity(0.0));

  const Eigen::Vector3d t = rig_.right_from_left.t, t_hat = t.normalized();
  const double baseline_sigma = std::sqrt(t_hat.dot(sigma.bottomRightCorner<3, 3>() * t_hat));
  EXPECT_NEAR(*BaselineSigma(rig_), baseline_sigma, 1e-12 * baseline_sigma);

  const ThetaSampler sampler(model, model.seed);
  constexpr size_t kN = 20000;
  std::vector<double> theta(kN * sampler.size());
  sampler.Fill(0, kN, theta.data());
  const int rotation = model.layout.Offset(Term::kCameraRotation, 1), translation = model.layout.Offset(Term::kCameraTranslation, 1);
  double sum_b = 0, sum_b2 = 0;
  Eigen::Vector3d sum_w2 = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < kN; ++i) {
    const double* row = theta.data() + i * sampler.size();
    Eigen::Matrix<double, 6, 1> z;
    z << row[rotation], row[rotation + 1], row[rotation + 2], row[translation], row[translation + 1], row[translation + 2];
    const Eigen::Matrix<double, 6, 1> delta = mixing * z;
    const Eigen::Vector3d omega = delta.head<3>();
    const double b = (RotationFromRotvec(omega) * t + delta.tail<3>()).norm();
    sum_b += b;
    sum_b2 += b * b;
    sum_w2 += omega.cwiseAbs2();
  }
  const double mean_b = sum_b / kN;
  EXPECT_NEAR(std::sqrt(sum_b2 / kN - mean_b * mean_b), baseline_sigma, 0.03 * baseline_sigma);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(std::sqrt(sum_w2(a) / kN), std::sqrt(sigma(a, a)), 0.03 * std::sqrt(sigma(a, a)));
}

// The chain applies the mixing: evaluating z with the rig's mixing gives the pixels of the chain
// without mixing evaluated at (ω, ρ) = M z put straight into the slots.
TEST_F(ErrSimRig, ChainMixesTheRightCamerasPoseSlots) {
  const ChainModel mixed = Build(WithRig());
  ChainModel plain = mixed;
  plain.extrinsic_mixing[1].setIdentity();
  const ChainEvaluator with(mixed), without(plain);
  const int rotation = mixed.layout.Offset(Term::kCameraRotation, 1), translation = mixed.layout.Offset(Term::kCameraTranslation, 1);
  std::vector<double> z(mixed.layout.size(), 0.0);
  const double values[6] = {1.0, -0.5, 2.0, 0.3, -1.5, 0.8};
  for (int j = 0; j < 3; ++j) z[rotation + j] = values[j], z[translation + j] = values[3 + j];
  Eigen::Matrix<double, 6, 1> zv;
  zv << values[0], values[1], values[2], values[3], values[4], values[5];
  const Eigen::Matrix<double, 6, 1> delta = mixed.extrinsic_mixing[1] * zv;
  std::vector<double> direct(z.size(), 0.0);
  for (int j = 0; j < 3; ++j) direct[rotation + j] = delta(j), direct[translation + j] = delta(3 + j);
  std::vector<double> y_mixed(with.num_vector_outputs()), y_direct(without.num_vector_outputs());
  ASSERT_TRUE(with(z.data(), y_mixed.data()));
  ASSERT_TRUE(without(direct.data(), y_direct.data()));
  double largest = 0;
  for (size_t i = 0; i < y_mixed.size(); ++i) {
    EXPECT_NEAR(y_mixed[i], y_direct[i], 1e-9) << i;
    largest = std::max(largest, std::abs(y_mixed[i]));
  }
  EXPECT_GT(largest, 0.01);  // the right camera's pixels moved: the test compares something
}

}  // namespace
}  // namespace vstcal
