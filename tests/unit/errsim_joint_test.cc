// A rig's joint covariance as one correlated draw (docs/math/vst-chain.md#joint-draw): both
// cameras' lens parameters and right_from_left's tangent, with their cross-covariances, drawn
// together. Checked against the covariance itself, not the code: the drawn parameters' sample
// covariance is the file's within its Monte Carlo error (for a calib-stereo solve of noisy
// synthetic views, read through "rig"); perfectly correlated cx's give no disparity error and move
// a point on the cyclopean axis sideways by Z·δcx/f only; with camera_intrinsic switched off the
// right camera's pose keeps its variance given the lenses (Σ_pp − Σ_pl Σ_ll⁻¹ Σ_lp). Bad input
// names the field and the fix; runs keep their bits whatever the thread count or shard split.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/scenes.h"
#include "support/stereo_rigs.h"
#include "support/vst_scenes.h"
#include "vstcal/calib/stereo_solve.h"
#include "vstcal/core/error.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/sampler.h"
#include "vstcal/errsim/simulation.h"
#include "vstcal/formats/errsim/chain_reader.h"
#include "vstcal/formats/errsim/chain_writer.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/json/json_reader.h"

namespace vstcal {
namespace {

const Provenance kJointProvenance{"errsim_joint_test", {}, std::nullopt};
constexpr double kJointFocal = 700.0, kJointDepth = 1500.0;

OrderedJson JointNormal(double sigma) { return testing::ChainNormal(sigma); }
OrderedJson CovarianceJson(const ParameterCovariance& c) { return {{"parameters", c.parameters}, {"matrix", MatrixToJson(c.matrix)}}; }

// A parallel orthostereo rig (pinhole, fx = 700, 63 mm), the hmd at the world origin, a point on
// the cyclopean axis at kJointDepth and one off it; `joint` the chain's joint_covariance.
OrderedJson ParallelChain(const OrderedJson& joint, const OrderedJson& sources = OrderedJson::object()) {
  return testing::ParallelRigChain(sources, kJointFocal, kJointDepth, joint);
}

ChainModel ModelIn(const OrderedJson& chain, const std::filesystem::path& dir = ".") {
  return BuildChainModel(ChainSpecFromJson(JsonDocument::Parse(chain.dump(), "chain.json"), dir));
}

std::string ErrorIn(const OrderedJson& chain, const std::filesystem::path& dir = ".") {
  try {
    ModelIn(chain, dir);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// The parameters' errors as the chain reads them (couplings applied), for n draws of err-sim's sampler.
template <typename Visit>
void ForEachDraw(const ChainModel& model, size_t n, Visit visit) {
  const ThetaSampler sampler(model, 23);
  std::vector<double> theta(sampler.size()), coupled(sampler.size());
  for (size_t i = 0; i < n; ++i) {
    sampler.Fill(i, 1, theta.data());
    ApplyCouplings(model, theta.data(), coupled.data());
    visit(theta, coupled);
  }
}

// The θ slot of a joint covariance's parameter.
int SlotOf(const ChainModel& model, const std::string& name) {
  const auto& tangents = RelativePoseTangentNames();
  for (int i = 0; i < 6; ++i) {
    if (name == tangents[i]) return model.layout.Offset(i < 3 ? Term::kCameraRotation : Term::kCameraTranslation, 1) + i % 3;
  }
  for (int e = 0; e < kNumEyes; ++e) {
    const auto names = LensModelParamNames(model.renderer[e].model);
    for (size_t i = 0; i < names.size(); ++i) {
      if (name == JointCovarianceName(e, names[i])) return model.layout.Offset(Term::kLens, e) + static_cast<int>(i);
    }
  }
  ADD_FAILURE() << "no slot for " << name;
  return 0;
}

// Sample covariance of the drawn parameters against Σ: each entry within 5 standard errors,
// SE(Σ̂_ab) = √((Σ_aa Σ_bb + Σ_ab²)/N) for normal draws.
void ExpectMoments(const ChainModel& model, const ParameterCovariance& cov, size_t n) {
  const int m = static_cast<int>(cov.parameters.size());
  std::vector<int> slots;
  for (const std::string& p : cov.parameters) slots.push_back(SlotOf(model, p));
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(m, m);
  ForEachDraw(model, n, [&](const std::vector<double>&, const std::vector<double>& x) {
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b) sum(a, b) += x[slots[a]] * x[slots[b]];
  });
  const Eigen::MatrixXd sample = sum / static_cast<double>(n);  // the mean is 0
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b < m; ++b) {
      const double se = std::sqrt((cov.matrix(a, a) * cov.matrix(b, b) + cov.matrix(a, b) * cov.matrix(a, b)) / n);
      EXPECT_NEAR(sample(a, b), cov.matrix(a, b), 5 * se) << cov.parameters[a] << ", " << cov.parameters[b];
    }
  }
}

class ErrSimJoint : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) / ("errsim_joint_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

// calib-stereo solve's joint covariance of a ZED-like rig seen in 10 noisy views: its blocks are
// the marginals it writes beside it, the file reads back byte for byte, and a chain drawing from it
// ("joint_covariance": "rig") draws the lens parameters and right_from_left with its moments —
// cross-covariances between the cameras and with the pose included.
TEST_F(ErrSimJoint, TheJointDrawReproducesTheSolvedRigsCovariance) {
  StereoRig truth = testing::ZedLikeRig();
  truth.left.camera.params.back() = truth.right.camera.params.back() = 0;  // k3: the solve estimates k1, k2, p1, p2
  testing::StereoViews views = testing::SyntheticStereoViews(truth, 10, 7);
  views.left = testing::WithNoise(views.left, 0.3, 1);
  views.right = testing::WithNoise(views.right, 0.3, 2);
  const StereoSolveResult solved = SolveStereo(views.left, views.right, StereoSolveOptions{});
  ASSERT_EQ(solved.exit_code, ExitCode::kOk) << solved.message;
  const StereoRig& rig = solved.rig;
  ASSERT_TRUE(rig.joint_covariance && rig.left.covariance && rig.right.covariance && rig.covariance);
  const ParameterCovariance& joint = *rig.joint_covariance;
  for (const auto& [prefix, marginal] : {std::pair{std::string("left."), &*rig.left.covariance},
                                         std::pair{std::string("right."), &*rig.right.covariance},
                                         std::pair{std::string(), &*rig.covariance}}) {
    for (size_t a = 0; a < marginal->parameters.size(); ++a) {
      for (size_t b = 0; b < marginal->parameters.size(); ++b) {
        // One product against another of the same numbers: equal to rounding.
        EXPECT_NEAR(joint.matrix(*joint.Find(prefix + marginal->parameters[a]), *joint.Find(prefix + marginal->parameters[b])),
                    marginal->matrix(a, b), 1e-12 * std::sqrt(marginal->matrix(a, a) * marginal->matrix(b, b)))
            << prefix << marginal->parameters[a] << ", " << marginal->parameters[b];
      }
    }
  }
  // The cameras' lens errors are correlated with each other and with the pose (one problem).
  EXPECT_GT(std::abs(joint.matrix(*joint.Find("left.cx"), *joint.Find("right.cx"))),
            1e-3 * std::sqrt(joint.matrix(*joint.Find("left.cx"), *joint.Find("left.cx")) * joint.matrix(*joint.Find("right.cx"), *joint.Find("right.cx"))));
  const std::string written = DumpJson(StereoRigToJson(rig, kJointProvenance));
  std::ofstream(dir_ / "rig.json") << written;
  EXPECT_EQ(DumpJson(StereoRigToJson(ReadStereoRig(dir_ / "rig.json"), kJointProvenance)), written);

  OrderedJson chain = ParallelChain("rig");
  chain.erase("cameras");
  chain["frames"]["camera_from_hmd"].erase("right");
  chain["frames"]["hmd_from_tracker"] = testing::ChainPose(0, 0, 600);
  chain["test_points"] = {{{"name", "a"}, {"world", {0, 0, 0}}}, {{"name", "b"}, {"world", {60, -40, 150}}}};
  chain["rig"] = {{"file", "rig.json"}};
  const ChainModel model = ModelIn(chain, dir_);
  ExpectMoments(model, joint, 40000);
  // Every jointly drawn slot says where it came from.
  EXPECT_EQ(model.parameters[SlotOf(model, "right.cx")].origin, (DistributionOrigin{"rig.json", "vstcal/stereo@1"}));
  EXPECT_EQ(model.parameters[SlotOf(model, "right_from_left.tz")].origin, (DistributionOrigin{"rig.json", "vstcal/stereo@1"}));
  // A chain that references it is written back as it was read.
  const ChainSpec spec = ChainSpecFromJson(JsonDocument::Parse(chain.dump(), "chain.json"), dir_);
  EXPECT_EQ(ChainSpecToJson(spec, kJointProvenance)["joint_covariance"], "rig");
}

// An inline joint covariance with cross terms everywhere (a random positive definite matrix over
// both cx's, fx's, k1's and three tangents): the same moments.
TEST(JointDraw, AnInlineCovarianceIsDrawnWithItsMoments) {
  const std::vector<std::string> names = {"left.fx", "left.cx", "right.fx", "right.cx", "right_from_left.ry",
                                          "right_from_left.tx", "right_from_left.tz"};
  const int m = static_cast<int>(names.size());
  Eigen::MatrixXd A(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) A(i, j) = std::sin(1.3 * i + 0.7 * j + 0.4 * i * j);
  const Eigen::VectorXd scale = (Eigen::VectorXd(m) << 2.0, 1.0, 2.0, 1.0, 1e-3, 0.3, 0.5).finished();
  ParameterCovariance cov;
  cov.parameters = names;
  cov.matrix = scale.asDiagonal() * (A * A.transpose() / m) * scale.asDiagonal();
  const ChainModel model = ModelIn(ParallelChain(CovarianceJson(cov)));
  ExpectMoments(model, cov, 40000);
  EXPECT_EQ(model.parameters[SlotOf(model, "left.cx")].origin, DistributionOrigin{});  // typed in: assumed
}

// cx perfectly correlated between the cameras (Σ = σ²[[1, 1], [1, 1]]) is one draw: no disparity
// error, and the point on the cyclopean axis moves sideways by Z·δcx/f, not in depth — the
// closed form of a shared cx error.
TEST(JointDraw, PerfectlyCorrelatedCxGivesNoDisparityError) {
  ParameterCovariance cov;
  cov.parameters = {"left.cx", "right.cx"};
  cov.matrix = Eigen::Matrix2d::Constant(1.0);
  const ChainModel model = ModelIn(ParallelChain(CovarianceJson(cov)));
  const ChainEvaluator chain(model);
  const int left_cx = model.layout.Offset(Term::kLens, 0) + 2;
  ChainSample<double> sample(chain.num_points());
  double largest_disparity = 0, largest_depth = 0, largest_lateral_error = 0, sum_squares = 0;
  const size_t n = 4000;
  ForEachDraw(model, n, [&](const std::vector<double>& theta, const std::vector<double>& x) {
    chain.Evaluate(theta.data(), &sample);
    const PointSample<double>& axis = sample.points[0];
    ASSERT_TRUE(axis.valid());
    const Eigen::Vector3d misregistration = axis.overlay - axis.seen;
    const double dcx = x[left_cx];
    largest_disparity = std::max(largest_disparity, std::abs(axis.pixel_error[0].x() - axis.pixel_error[1].x()));
    largest_depth = std::max(largest_depth, std::abs(misregistration.z()));
    largest_lateral_error = std::max(largest_lateral_error, std::abs(misregistration.x() - kJointDepth * dcx / kJointFocal));
    sum_squares += axis.pixel_error[1].x() * axis.pixel_error[1].x();
  });
  EXPECT_LT(largest_disparity, 1e-9);
  EXPECT_LT(largest_depth, 1e-9 * kJointDepth);
  EXPECT_LT(largest_lateral_error, 1e-9 * kJointDepth);
  EXPECT_NEAR(sum_squares / n, 1.0, 5 * std::sqrt(2.0 / n));  // σ 1 px in the right eye too
  EXPECT_TRUE(model.parameters[model.layout.Offset(Term::kLens, 1) + 2].distribution.IsConstant());  // nothing of its own
}

// The order of the factor is the attribution: with camera_intrinsic off, right_from_left.ry keeps
// its variance given left.cx, Σ_pp − Σ_pl²/Σ_ll; with camera_extrinsic off, cx keeps all of its own.
TEST(JointDraw, WhatTheLensesExplainOfThePoseMovesWithCameraIntrinsic) {
  ParameterCovariance cov;
  cov.parameters = {"left.cx", "right_from_left.ry"};
  const double sl = 1.5, sp = 2e-3, rho = 0.8;
  cov.matrix = (Eigen::Matrix2d() << sl * sl, rho * sl * sp, rho * sl * sp, sp * sp).finished();
  const ChainModel model = ModelIn(ParallelChain(CovarianceJson(cov)));
  std::array<bool, kNumSources> no_intrinsic, no_extrinsic;
  no_intrinsic.fill(true);
  no_extrinsic.fill(true);
  no_intrinsic[static_cast<int>(Source::kCameraIntrinsic)] = false;
  no_extrinsic[static_cast<int>(Source::kCameraExtrinsic)] = false;
  const size_t n = 40000;
  const int pose = SlotOf(model, "right_from_left.ry"), cx = SlotOf(model, "left.cx");
  double pp = 0, cc = 0;
  ForEachDraw(model.WithSources(no_intrinsic), n, [&](const std::vector<double>&, const std::vector<double>& x) { pp += x[pose] * x[pose]; });
  ForEachDraw(model.WithSources(no_extrinsic), n, [&](const std::vector<double>&, const std::vector<double>& x) { cc += x[cx] * x[cx]; });
  const double conditional = sp * sp * (1 - rho * rho);
  EXPECT_NEAR(pp / n, conditional, 5 * std::sqrt(2.0 / n) * conditional);
  EXPECT_NEAR(cc / n, sl * sl, 5 * std::sqrt(2.0 / n) * sl * sl);
}

TEST(JointDraw, RunsKeepTheirBitsAndAWrittenChainReadsBack) {
  ParameterCovariance cov;
  cov.parameters = {"left.cx", "right.cx", "right_from_left.tx"};
  cov.matrix = (Eigen::Matrix3d() << 1.0, 0.9, 0.1, 0.9, 1.0, -0.1, 0.1, -0.1, 0.25).finished();
  const OrderedJson chain = ParallelChain(CovarianceJson(cov), {{"tracking", {{"translation", JointNormal(1.0)}}}});
  const ChainModel model = ModelIn(chain);
  testing::ExpectTheSameBitsWhateverThreadsAndShards(model);
  const ChainSpec spec = ChainSpecFromJson(JsonDocument::Parse(chain.dump(), "chain.json"), ".");
  const OrderedJson written = ChainSpecToJson(spec, kJointProvenance);
  EXPECT_EQ(ChainDigest(ModelIn(written)), ChainDigest(model));
  EXPECT_EQ(ChainSpecToJson(ChainSpecFromJson(JsonDocument::Parse(written.dump(), "chain.json"), "."), kJointProvenance).dump(), written.dump());
  OrderedJson independent = chain;
  independent.erase("joint_covariance");
  EXPECT_NE(ChainDigest(ModelIn(independent)), ChainDigest(model));
}

TEST(JointDraw, BadInputNamesTheFieldAndTheFix) {
  auto joint = [](std::vector<std::string> names, const Eigen::MatrixXd& m) {
    return OrderedJson{{"parameters", names}, {"matrix", MatrixToJson(m)}};
  };
  const Eigen::Matrix2d not_psd = (Eigen::Matrix2d() << 1.0, 2.0, 2.0, 1.0).finished();
  const std::string psd = ErrorIn(ParallelChain(joint({"left.cx", "right.cx"}, not_psd)));
  EXPECT_TRUE(psd.starts_with("chain.json: joint_covariance.matrix: not positive semi-definite: eigenvalue -1 < ")) << psd;
  EXPECT_EQ(ErrorIn(ParallelChain(joint({"left.cx", "right.cx", "left.fx"}, Eigen::Matrix2d::Identity()))),
            "chain.json: joint_covariance.matrix: expected 3 items, got 2; give exactly 3");
  EXPECT_EQ(ErrorIn(ParallelChain(joint({"left.cx", "right.k1"}, Eigen::Matrix2d::Identity()))),
            "chain.json: joint_covariance.parameters[1]: unknown parameter \"right.k1\"; a rig's joint covariance is over "
            "left.<lens parameter>, right.<lens parameter> (fx, fy, cx, cy, s and each camera's distortion terms) and "
            "right_from_left.rx … .tz");
  EXPECT_EQ(ErrorIn(ParallelChain(joint({"left.cx", "right.cx"}, Eigen::Matrix2d::Identity()),
                                  {{"camera_intrinsic", {{"both", {{"cx", JointNormal(1.0)}}}}}})),
            "chain.json: joint_covariance: draws left.cx, which sources.camera_intrinsic.both.cx also gives; give each error "
            "once: delete it from sources.camera_intrinsic.both.cx, or from joint_covariance");
  EXPECT_EQ(ErrorIn(ParallelChain(joint({"left.cx", "right_from_left.tx"}, Eigen::Matrix2d::Identity()),
                                  {{"camera_extrinsic", {{"right", {{"translation", JointNormal(1.0)}}}}}})),
            "chain.json: joint_covariance: draws right_from_left's error (the right camera's pose), which "
            "sources.camera_extrinsic.right.translation also gives; give each error once: delete it from "
            "sources.camera_extrinsic.right.translation, or from joint_covariance");
  EXPECT_EQ(ErrorIn(ParallelChain("rig")),
            "chain.json: joint_covariance: the chain references no rig; add \"rig\": {\"file\": \"<stereo@1 file>\"}, or give "
            "the covariance inline");
  EXPECT_TRUE(ErrorIn(ParallelChain("camera")).starts_with("chain.json: joint_covariance: unknown value \"camera\"; write \"rig\""));
}

// A stereo@1 joint covariance whose block is not the marginal beside it is two answers.
TEST_F(ErrSimJoint, ARigsJointBlockMustBeItsMarginal) {
  StereoRig rig = testing::ZedLikeRig();
  rig.covariance = testing::SampleRelativePoseCovariance();
  ParameterCovariance joint;
  joint.parameters.assign(RelativePoseTangentNames().begin(), RelativePoseTangentNames().end());
  joint.matrix = rig.covariance->matrix;
  joint.matrix(2, 2) *= 1.5;
  rig.joint_covariance = joint;
  std::ofstream(dir_ / "rig.json") << DumpJson(StereoRigToJson(rig, kJointProvenance));
  try {
    ReadStereoRig(dir_ / "rig.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("joint_covariance.matrix: its entry (right_from_left.rz, right_from_left.rz) = "),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("disagrees with covariance's"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vstcal
