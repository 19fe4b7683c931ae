// err-sim reading a hand-eye measurement (issue 22 item 3; docs/formats.md#vst-chain-measured): a
// chain that references a handeye@1 and a tracker-noise@1 file is the same chain as the one with
// their numbers typed in (same digest, same report to the bit); the measured covariances perturb
// the chain as calib-handeye's tangent says (checked against X and Z perturbed directly and
// projected here); the budget says which distribution was measured and from which file; every bad
// reference is one line naming the chain's file and field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "support/stereo_rigs.h"
#include "vstcal/core/error.h"
#include "vstcal/errsim/budget.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/simulation.h"
#include "vstcal/formats/errsim/chain_reader.h"
#include "vstcal/formats/errsim/chain_writer.h"
#include "vstcal/formats/errsim/report_format.h"
#include "vstcal/formats/handeye/handeye_io.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal {
namespace {

const Provenance kProvenance{"errsim_handeye_test", {}, std::nullopt};

OrderedJson Pose(const Rigid3d& p) { return {{"R", MatrixToJson(p.R)}, {"t", MatrixToJson(p.t)}}; }
OrderedJson Normal(double sigma, double mean = 0) { return {{"distribution", "normal"}, {"mean", mean}, {"sigma", sigma}}; }

Rigid3d FromRotvecDeg(double rx, double ry, double rz, double tx, double ty, double tz) {
  return Rigid3d::FromRotvec(DegToRad(1.0) * Eigen::Vector3d(rx, ry, rz), Eigen::Vector3d(tx, ty, tz));
}

// The measurement: the left camera 31.5 mm left of the hmd origin, turned 0.5°; the board 1.5 m in
// front of the tracker; δ = 12 ms. A correlated 13 × 13 covariance: σ's of 1 mrad / 0.4 mm (X),
// 0.5 mrad / 0.8 mm (Z), 2 ms (δ), correlations from a fixed lower-triangular factor.
HandEyeSolution Measurement() {
  HandEyeSolution s;
  s.hmd_from_camera = FromRotvecDeg(0.3, -0.4, 0.2, -31.5, 0.4, -0.2);
  s.tracker_from_board = FromRotvecDeg(2.0, -10.0, 1.0, 120.0, -40.0, 1500.0);
  s.time_offset = 0.012;
  Eigen::Matrix<double, 13, 13> L = Eigen::Matrix<double, 13, 13>::Identity();
  for (int r = 0; r < 13; ++r)
    for (int c = 0; c < r; ++c) L(r, c) = 0.3 * std::sin(1.7 * r + 0.9 * c);
  Eigen::Matrix<double, 13, 13> C = L * L.transpose();
  const Eigen::VectorXd d = C.diagonal().cwiseSqrt();
  C = d.cwiseInverse().asDiagonal() * C * d.cwiseInverse().asDiagonal();  // a correlation matrix
  Eigen::VectorXd sigma(13);
  sigma << 1e-3, 1e-3, 1e-3, 0.4, 0.4, 0.4, 5e-4, 5e-4, 5e-4, 0.8, 0.8, 0.8, 0.002;
  s.covariance = sigma.asDiagonal() * C * sigma.asDiagonal();
  s.names = HandEyeCovarianceNames();
  s.views = 30;
  s.corners = 1500;
  return s;
}

TrackerNoise Noise() {
  TrackerNoise n;
  n.reports = 500;
  n.from = 0;
  n.to = 5;
  n.mean = FromRotvecDeg(0, 30, 0, 100, 200, 300);
  n.rotation = {3.5e-4, 3.4e-4, 3.6e-4, Eigen::Vector3d(3.4e-4, 3.5e-4, 3.6e-4)};
  n.translation = {0.1, 0.095, 0.105, Eigen::Vector3d(0.1, 0.1, 0.1)};
  return n;
}

class ErrSimHandEye : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) /
           ("errsim_handeye_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::create_directories(dir_);
    rig_.covariance = testing::SampleRelativePoseCovariance();
    Write("rig.json", StereoRigToJson(rig_, kProvenance));
    Write("handeye.json", HandEyeToJson(he_, LengthUnit::kMillimetre, kProvenance));
    Write("noise.json", TrackerNoiseToJson(noise_, LengthUnit::kMillimetre, kProvenance));
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void Write(const std::string& name, const OrderedJson& j) const { std::ofstream(dir_ / name) << DumpJson(j); }

  ChainSpec Spec(const OrderedJson& chain) const {
    return ChainSpecFromJson(JsonDocument::Parse(chain.dump(), "chain.json"), dir_);
  }
  ChainModel Build(const OrderedJson& chain) const { return BuildChainModel(Spec(chain)); }

  // The hmd 1 m in front of the board's origin, three test points around it (board frame = world).
  Rigid3d HmdFromTracker() const { return FromRotvecDeg(1, 2, 0, 0, 0, 1000) * he_.tracker_from_board.inverse(); }

  // The chain that takes camera_extrinsic (the head's mount), tracker_alignment and tracking from
  // the measurement; display's IPD typed in.
  OrderedJson Measured() const {
    OrderedJson c;
    c["format"] = "vstcal/vst-chain@1";
    c["length_unit"] = "mm";
    c["samples"] = 1000;
    c["seed"] = 5;
    c["rig"] = {{"file", "rig.json"}};
    c["handeye"] = {{"file", "handeye.json"}};
    c["tracker_noise"] = {{"file", "noise.json"}};
    c["frames"] = {{"hmd_from_tracker", Pose(HmdFromTracker())}, {"world_from_object", Pose(Rigid3d())}};
    c["display"] = {{"ipd", 63.0}};
    c["head_motion"] = {{"angular_velocity_deg_s", {0.0, 40.0, 0.0}}, {"linear_velocity", {100.0, 0.0, 0.0}}};
    c["test_points"] = {{{"name", "a"}, {"world", {0, 0, 0}}},
                        {{"name", "b"}, {"world", {100, -50, 200}}},
                        {{"name", "c"}, {"world", {-150, 80, -300}}}};
    c["sources"] = {{"tracker_alignment", {{"covariance", "handeye"}}},
                    {"tracking", {{"rotation_deg", "tracker_noise"}, {"translation", "tracker_noise"}, {"latency_s", "handeye"}}},
                    {"camera_extrinsic", {{"rig", {{"covariance", "handeye"}}}, {"right", {{"covariance", "rig"}}}}},
                    {"display", {{"ipd", Normal(2.0)}}}};
    return c;
  }

  // The same chain with the measurement's numbers typed in: tracker_from_world = Z,
  // camera_from_hmd.left = X⁻¹, the X and Z blocks inline, tracking's σ's as numbers (degrees).
  OrderedJson ByHand() const {
    OrderedJson c = Measured();
    c.erase("handeye");
    c.erase("tracker_noise");
    c["frames"]["tracker_from_world"] = Pose(he_.tracker_from_board);
    c["frames"]["camera_from_hmd"] = {{"left", Pose(he_.hmd_from_camera.inverse())}};
    auto block = [&](int at) {
      return OrderedJson{{"parameters", std::vector<std::string>(he_.names.begin() + at, he_.names.begin() + at + 6)},
                         {"matrix", MatrixToJson(Eigen::MatrixXd(he_.covariance.block(at, at, 6, 6)))}};
    };
    c["sources"]["tracker_alignment"] = {{"covariance", block(6)}};
    c["sources"]["camera_extrinsic"]["rig"] = {{"covariance", block(0)}};
    c["sources"]["tracking"] = {{"rotation_deg", Normal(RadToDeg(noise_.rotation.sigma))},
                                {"translation", Normal(noise_.translation.sigma)},
                                {"latency_s", Normal(std::sqrt(he_.covariance(12, 12)))}};
    return c;
  }

  StereoRig rig_ = testing::ZedLikeRig();
  HandEyeSolution he_ = Measurement();
  TrackerNoise noise_ = Noise();
  std::filesystem::path dir_;
};

struct RunReport {
  OrderedJson json;
  std::string text;
};

RunReport ReportOf(const ChainModel& model, bool budget) {
  SimulationOptions options;
  options.samples = model.samples;
  options.budget = budget;
  options.budget_samples = model.samples;
  options.seed = model.seed;
  options.threads = 2;
  const RunDescription run{"chain.json", ChainDigest(model), {}, {}, options};
  const SimulationResult result = RunSimulation(MakeScenarios(model, budget), options, run.digest);
  const ChainEvaluator chain(model);
  return {ReportToJson(chain, result, run, kProvenance), ReportText(chain, result, run)};
}

// Every "origin" of a report removed: what is left are the numbers.
OrderedJson WithoutOrigins(OrderedJson j) {
  for (auto& e : j["budget"]["entries"]) {
    e.erase("origin");
    for (auto& t : e["terms"]) t.erase("origin");
  }
  return j;
}

TEST_F(ErrSimHandEye, ChainFromAMeasurementIsTheHandWrittenChain) {
  const ChainModel measured = Build(Measured());
  const ChainModel by_hand = Build(ByHand());
  EXPECT_EQ(ChainDigest(measured), ChainDigest(by_hand));
  EXPECT_EQ(measured.geometry.tracker_from_world.R, he_.tracker_from_board.R);
  EXPECT_EQ(measured.geometry.tracker_from_world.t, he_.tracker_from_board.t);
  // The right camera through the rig: right_from_left · X⁻¹.
  const Rigid3d right = rig_.right_from_left * he_.hmd_from_camera.inverse();
  EXPECT_LT((measured.geometry.camera_from_hmd[1].t - right.t).norm(), 1e-12);
  const RunReport a = ReportOf(measured, true), b = ReportOf(by_hand, true);
  EXPECT_EQ(DumpJson(WithoutOrigins(a.json)), DumpJson(WithoutOrigins(b.json)));  // same seed: the same bits
  EXPECT_NE(DumpJson(a.json), DumpJson(b.json));                                  // but not the same provenance
  EXPECT_EQ(DumpJson(ReportOf(measured, false).json), DumpJson(ReportOf(by_hand, false).json));

  // The measurement matters: without the mount's covariance the numbers change.
  OrderedJson without = Measured();
  without["sources"]["camera_extrinsic"].erase("rig");
  EXPECT_NE(DumpJson(ReportOf(Build(without), false).json), DumpJson(ReportOf(measured, false).json));
}

TEST_F(ErrSimHandEye, DistributionsAreTheMeasurements) {
  const ChainModel m = Build(Measured());
  const Eigen::MatrixXd x = he_.covariance.block(0, 0, 6, 6), z = he_.covariance.block(6, 6, 6, 6);
  EXPECT_LT((m.mount_mixing * m.mount_mixing.transpose() - x).norm(), 1e-12 * x.norm());
  EXPECT_LT((m.tracker_alignment_mixing * m.tracker_alignment_mixing.transpose() - z).norm(), 1e-12 * z.norm());
  auto normal = [&](Term term, int i) { return std::get<Distribution::Normal>(m.parameters[m.layout.Offset(term) + i].distribution.form()); };
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(normal(Term::kTrackingRotation, i).sigma, noise_.rotation.sigma, 1e-18);
    EXPECT_EQ(normal(Term::kTrackingTranslation, i).sigma, noise_.translation.sigma);
  }
  // The residual after applying δ̂ (the default), or δ̂ itself when the system does not apply it.
  EXPECT_EQ(normal(Term::kTrackingLatency, 0).mean, 0.0);
  EXPECT_EQ(normal(Term::kTrackingLatency, 0).sigma, std::sqrt(he_.covariance(12, 12)));
  OrderedJson uncorrected = Measured();
  uncorrected["sources"]["tracking"]["latency_s"] = "handeye-uncorrected";
  const ChainModel u = Build(uncorrected);
  const auto& latency = std::get<Distribution::Normal>(u.parameters[u.layout.Offset(Term::kTrackingLatency)].distribution.form());
  EXPECT_EQ(latency.mean, he_.time_offset);
  EXPECT_EQ(latency.sigma, std::sqrt(he_.covariance(12, 12)));
}

// A handeye file solved with --bootstrap: the latency takes the bootstrap's σ_δ (the first-order
// one is up to 15 % low with few views, docs/math/handeye.md#delta-bootstrap), X's and Z's stay the
// first-order covariance's blocks.
TEST_F(ErrSimHandEye, LatencyTakesTheBootstrapSigmaWhenTheFileHasOne) {
  HandEyeBootstrap bootstrap;
  bootstrap.replicates = 50;
  bootstrap.solved = 50;
  bootstrap.seed = 7;
  bootstrap.covariance = 1.3 * he_.covariance.topLeftCorner(13, 13);  // δ's σ √1.3 × the first-order one
  bootstrap.mean = Eigen::VectorXd::Zero(13);
  Write("handeye.json", HandEyeToJson(he_, LengthUnit::kMillimetre, kProvenance, nullptr, &bootstrap));
  const double first_order = std::sqrt(he_.covariance(12, 12));
  for (const char* word : {"handeye", "handeye-uncorrected"}) {
    OrderedJson c = Measured();
    c["sources"]["tracking"]["latency_s"] = word;
    const ChainModel m = Build(c);
    const auto& latency = std::get<Distribution::Normal>(m.parameters[m.layout.Offset(Term::kTrackingLatency)].distribution.form());
    EXPECT_NEAR(latency.sigma, std::sqrt(1.3) * first_order, 1e-12 * first_order) << word;
    const Eigen::MatrixXd x = he_.covariance.block(0, 0, 6, 6);
    EXPECT_LT((m.mount_mixing * m.mount_mixing.transpose() - x).norm(), 1e-12 * x.norm()) << word;
  }
  // A bootstrap without its σ is a malformed file, refused naming the field.
  OrderedJson broken = OrderedJson::parse(DumpJson(HandEyeToJson(he_, LengthUnit::kMillimetre, kProvenance, nullptr, &bootstrap)));
  broken["bootstrap"].erase("time_offset_sigma_s");
  Write("handeye.json", broken);
  try {
    Build(Measured());
    ADD_FAILURE() << "a bootstrap without time_offset_sigma_s was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("time_offset_sigma_s"), std::string::npos) << e.what();
  }
}

// The convention, checked against calib-handeye's own tangent (docs/math/vst-chain.md#measured-chain):
// a draw z of the mount's and the alignment's modes moves the pixels as X' = PerturbLeft(X, −M_X z)
// and Z' = PerturbLeft(Z, M_Z z) do when projected here directly — to first order (the mount's
// exact tangent is −(ω, Exp(−ω)ρ)); the draw is ~0.1 σ, so second order is ~1e-4 of the shift.
TEST_F(ErrSimHandEye, MeasuredCovariancesPerturbTheChainAsTheHandEyeTangent) {
  const ChainModel m = Build(Measured());
  const ChainEvaluator chain(m);
  Eigen::Matrix<double, 6, 1> zx, zz;
  zx << 0.1, -0.05, 0.2, 0.03, -0.15, 0.08;
  zz << -0.07, 0.12, 0.04, 0.1, 0.02, -0.09;
  std::vector<double> theta(m.layout.size(), 0.0);
  auto put = [&](Term rotation, Term translation, const Eigen::Matrix<double, 6, 1>& z) {
    for (int j = 0; j < 3; ++j) theta[m.layout.Offset(rotation) + j] = z(j), theta[m.layout.Offset(translation) + j] = z(3 + j);
  };
  put(Term::kRigRotation, Term::kRigTranslation, zx);
  put(Term::kTrackerAlignmentRotation, Term::kTrackerAlignmentTranslation, zz);
  std::vector<double> y(chain.num_vector_outputs());
  ASSERT_TRUE(chain(theta.data(), y.data()));

  const Eigen::Matrix<double, 6, 1> xi_x = -(m.mount_mixing * zx), xi_z = m.tracker_alignment_mixing * zz;
  const Rigid3d x = PerturbLeft(he_.hmd_from_camera, Eigen::Vector3d(xi_x.head<3>()), Eigen::Vector3d(xi_x.tail<3>()));
  const Rigid3d z = PerturbLeft(he_.tracker_from_board, Eigen::Vector3d(xi_z.head<3>()), Eigen::Vector3d(xi_z.tail<3>()));
  const std::array<Rigid3d, kNumEyes> camera_from_hmd = {x.inverse(), rig_.right_from_left * x.inverse()};
  double largest = 0;
  for (size_t k = 0; k < m.geometry.test_points.size(); ++k) {
    const Eigen::Vector3d p = m.geometry.test_points[k].point_in_world;
    for (int e = 0; e < kNumEyes; ++e) {
      const auto q = m.geometry.cameras[e].Project(camera_from_hmd[e] * (HmdFromTracker() * (z * p)));
      const auto q0 = m.geometry.cameras[e].Project(m.geometry.camera_from_hmd[e] * (HmdFromTracker() * (he_.tracker_from_board * p)));
      ASSERT_TRUE(q && q0);
      const Eigen::Vector2d expected = *q - *q0;
      const Eigen::Vector2d got(y[kVectorOutputsPerPoint * k + VectorOffset(VectorOutput::kPixelError, e)],
                                y[kVectorOutputsPerPoint * k + VectorOffset(VectorOutput::kPixelError, e) + 1]);
      EXPECT_LT((got - expected).norm(), 2e-3 * expected.norm() + 1e-9) << "point " << k << " eye " << e << ": " << got.transpose()
                                                                         << " vs " << expected.transpose();
      largest = std::max(largest, expected.norm());
    }
  }
  EXPECT_GT(largest, 0.05);  // the pixels moved: the test compares something
}

// Provenance (issue 21 item 4): per source and term, measured with its file or assumed, in the
// model, the report's JSON and its text.
TEST_F(ErrSimHandEye, BudgetSaysWhereEachDistributionCameFrom) {
  const ChainModel m = Build(Measured());
  const DistributionOrigin handeye{"handeye.json", "vstcal/handeye@1"}, noise{"noise.json", "vstcal/tracker-noise@1"},
      rig{"rig.json", "vstcal/stereo@1"};
  EXPECT_EQ(OriginsOf(m, {Term::kTrackerAlignmentRotation, Term::kTrackerAlignmentTranslation}), std::vector{handeye});
  EXPECT_EQ(OriginsOf(m, {Term::kTrackingRotation, Term::kTrackingTranslation}), std::vector{noise});
  EXPECT_EQ(OriginsOf(m, {Term::kTrackingLatency}), std::vector{handeye});
  EXPECT_EQ(OriginsOf(m, {Term::kRigRotation, Term::kRigTranslation}), std::vector{handeye});
  EXPECT_EQ(OriginsOf(m, {Term::kCameraRotation, Term::kCameraTranslation}), std::vector{rig});
  EXPECT_EQ(OriginsOf(m, {Term::kIpd}), std::vector{DistributionOrigin{}});

  const RunReport r = ReportOf(m, true);
  std::map<std::string, OrderedJson> by_source;
  for (const auto& e : r.json.at("budget").at("entries")) by_source[e.at("source").get<std::string>()] = e;
  ASSERT_EQ(by_source.size(), 4u);
  EXPECT_EQ(by_source["tracker_alignment"]["origin"],
            OrderedJson::parse(R"([{"kind": "measured", "file": "handeye.json", "format": "vstcal/handeye@1"}])"));
  EXPECT_EQ(by_source["display"]["origin"], OrderedJson::parse(R"([{"kind": "assumed"}])"));
  EXPECT_EQ(by_source["tracking"]["origin"].size(), 2u);  // the noise file's σ's and the hand-eye's latency
  for (const auto& t : by_source["tracking"]["terms"]) {
    EXPECT_EQ(t.at("origin")[0].at("file"), t.at("term") == "tracking.latency" ? "handeye.json" : "noise.json") << t.at("term");
  }
  EXPECT_EQ(by_source["camera_extrinsic"]["origin"].size(), 2u);  // the mount's hand-eye X, the rig's right_from_left
  EXPECT_NE(r.text.find("    tracker_alignment: measured (handeye.json), "), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("    display: assumed, "), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("; latency: measured (handeye.json)"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("; rotation: measured (noise.json)"), std::string::npos) << r.text;
}

// The tracker's noise estimated jointly by calib-handeye solve (handeye@1's tracker_noise, the
// covariance then 15 × 15): "tracking": {"rotation_deg": "handeye", "translation": "handeye"} takes
// its σ's, so that one file gives the whole chain; the report is the hand-written chain's with those
// numbers (to the bit), and the budget marks all three tracking terms measured by the handeye file.
TEST_F(ErrSimHandEye, TrackingNoiseFromTheHandEyeFileIsTheHandWrittenChain) {
  HandEyeSolution joint = he_;
  JointTrackerNoise noise;
  noise.rotation = {4.1e-4, 3e-5, 3.5e-4, 4.7e-4};
  noise.translation = {0.13, 0.01, 0.11, 0.15};
  noise.corner_px = {0.21, 0.002, 0.206, 0.214};
  noise.frames = 30;
  noise.rounds = 2;
  joint.tracker_noise = noise;
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(15, 15);
  covariance.topLeftCorner(13, 13) = he_.covariance;
  covariance(13, 13) = noise.rotation.sigma_sigma * noise.rotation.sigma_sigma;
  covariance(14, 14) = noise.translation.sigma_sigma * noise.translation.sigma_sigma;
  joint.covariance = covariance;
  joint.names.insert(joint.names.end(), HandEyeNoiseCovarianceNames().begin(), HandEyeNoiseCovarianceNames().end());
  Write("handeye_joint.json", HandEyeToJson(joint, LengthUnit::kMillimetre, kProvenance));

  OrderedJson measured = Measured();
  measured.erase("tracker_noise");
  measured["handeye"]["file"] = "handeye_joint.json";
  measured["sources"]["tracking"]["rotation_deg"] = "handeye";
  measured["sources"]["tracking"]["translation"] = "handeye";
  OrderedJson by_hand = ByHand();
  by_hand["sources"]["tracking"]["rotation_deg"] = Normal(RadToDeg(noise.rotation.sigma));
  by_hand["sources"]["tracking"]["translation"] = Normal(noise.translation.sigma);

  const ChainModel m = Build(measured), h = Build(by_hand);
  EXPECT_EQ(ChainDigest(m), ChainDigest(h));
  auto sigma = [&](Term term, int i) { return std::get<Distribution::Normal>(m.parameters[m.layout.Offset(term) + i].distribution.form()).sigma; };
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(sigma(Term::kTrackingRotation, i), 4.1e-4);  // the model's unit is the radian
    EXPECT_EQ(sigma(Term::kTrackingTranslation, i), 0.13);
  }
  EXPECT_EQ(sigma(Term::kTrackingLatency, 0), std::sqrt(he_.covariance(12, 12)));
  const RunReport a = ReportOf(m, true), b = ReportOf(h, true);
  EXPECT_EQ(DumpJson(WithoutOrigins(a.json)), DumpJson(WithoutOrigins(b.json)));
  const DistributionOrigin handeye{"handeye_joint.json", "vstcal/handeye@1"};
  EXPECT_EQ(OriginsOf(m, {Term::kTrackingRotation, Term::kTrackingTranslation, Term::kTrackingLatency}), std::vector{handeye});
  for (const auto& e : a.json.at("budget").at("entries")) {
    if (e.at("source") != "tracking") continue;
    EXPECT_EQ(e.at("origin"), OrderedJson::parse(R"([{"kind": "measured", "file": "handeye_joint.json", "format": "vstcal/handeye@1"}])"));
  }
  EXPECT_NE(a.text.find("    tracking: measured (handeye_joint.json), "), std::string::npos) << a.text;
  // The words are kept when the chain is written.
  const OrderedJson written = ChainSpecToJson(Spec(measured), kProvenance);
  EXPECT_EQ(written.at("sources").at("tracking").at("rotation_deg"), "handeye");

  // A handeye file whose tracker was taken as exact has no σ's to give.
  measured["handeye"]["file"] = "handeye.json";
  try {
    Build(measured);
    ADD_FAILURE() << "accepted a handeye file without tracker noise";
  } catch (const InputError& e) {
    const std::string m_text = e.what();
    EXPECT_NE(m_text.find("sources.tracking.rotation_deg"), std::string::npos) << m_text;
    EXPECT_NE(m_text.find("has no tracker noise"), std::string::npos) << m_text;
  }
}

// A written chain reads back as the same spec, references and words kept (not their numbers).
TEST_F(ErrSimHandEye, WrittenChainKeepsItsReferences) {
  const ChainSpec spec = Spec(Measured());
  const OrderedJson written = ChainSpecToJson(spec, kProvenance);
  EXPECT_EQ(written.at("handeye").at("file"), "handeye.json");
  EXPECT_EQ(written.at("sources").at("tracking").at("latency_s"), "handeye");
  EXPECT_EQ(written.at("sources").at("tracker_alignment").at("covariance"), "handeye");
  EXPECT_FALSE(written.at("frames").contains("tracker_from_world"));
  const ChainSpec again = Spec(written);
  EXPECT_EQ(DumpJson(ChainSpecToJson(again, kProvenance)), DumpJson(written));
  EXPECT_EQ(ChainDigest(BuildChainModel(again)), ChainDigest(BuildChainModel(spec)));
}

// Bad references: one line naming the chain's file (or the referenced file) and the field.
TEST_F(ErrSimHandEye, RefusesBadReferences) {
  auto message = [&](const OrderedJson& chain) -> std::string {
    try {
      Build(chain);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  auto expect = [&](const OrderedJson& chain, std::initializer_list<std::string_view> parts) {
    const std::string m = message(chain);
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    for (const std::string_view p : parts) EXPECT_NE(m.find(p), std::string::npos) << "'" << p << "' not in: " << m;
  };
  OrderedJson c = Measured();
  c["handeye"]["file"] = "missing.json";
  expect(c, {"chain.json", "handeye.file", "missing.json", "does not exist"});

  c = Measured();
  c["handeye"]["file"] = "rig.json";  // a stereo@1 file
  expect(c, {"rig.json", "format", "vstcal/handeye@1"});

  Write("handeye_m.json", HandEyeToJson(he_, LengthUnit::kMetre, kProvenance));
  c = Measured();
  c["handeye"]["file"] = "handeye_m.json";
  expect(c, {"chain.json", "handeye.file", "\"m\"", "\"mm\""});

  Write("noise_m.json", TrackerNoiseToJson(noise_, LengthUnit::kMetre, kProvenance));
  c = Measured();
  c["tracker_noise"]["file"] = "noise_m.json";
  expect(c, {"chain.json", "tracker_noise.file", "\"m\""});

  HandEyeSolution truth = he_;  // calib-synth's truth: no covariance
  truth.covariance.resize(0, 0);
  Write("truth.json", HandEyeToJson(truth, LengthUnit::kMillimetre, kProvenance));
  c = Measured();
  c["handeye"]["file"] = "truth.json";
  expect(c, {"chain.json", "sources.tracker_alignment.covariance", "truth.json has no covariance"});
  c["sources"].erase("tracker_alignment");
  expect(c, {"chain.json", "sources.tracking.latency_s", "truth.json has no covariance"});

  c = Measured();
  c.erase("tracker_noise");
  expect(c, {"chain.json", "sources.tracking.rotation_deg", "no tracker noise"});

  c = Measured();
  c.erase("handeye");
  c["frames"]["tracker_from_world"] = Pose(he_.tracker_from_board);
  c["frames"]["camera_from_hmd"] = {{"left", Pose(he_.hmd_from_camera.inverse())}};
  expect(c, {"chain.json", "sources.tracker_alignment.covariance", "no hand-eye calibration"});

  c = Measured();
  c["frames"]["tracker_from_world"] = Pose(he_.tracker_from_board);
  expect(c, {"chain.json", "frames.tracker_from_world", "given with \"handeye\""});

  c = Measured();
  c["sources"]["tracker_alignment"]["rotation_deg"] = Normal(0.1);
  expect(c, {"chain.json", "sources.tracker_alignment", "do not mix"});

  c = Measured();
  c["sources"]["tracking"]["latency_s"] = "kalibr";
  expect(c, {"chain.json", "sources.tracking.latency_s", "unknown value \"kalibr\""});

  c = Measured();
  c["sources"]["camera_extrinsic"]["rig"]["covariance"] = {{"parameters", {"hmd_from_camera.rx", "hmd_from_camera.ry", "hmd_from_camera.rz",
                                                                           "hmd_from_camera.tx", "hmd_from_camera.ty", "right_from_left.tz"}},
                                                           {"matrix", MatrixToJson(Eigen::MatrixXd(Eigen::MatrixXd::Identity(6, 6)))}};
  expect(c, {"chain.json", "sources.camera_extrinsic.rig.covariance.parameters[5]", "right_from_left.tz"});
}

}  // namespace
}  // namespace vstcal
