// vstcal/stereo@1: the rig type, its reader and writer (byte-identical round trips), assembling a
// rig from two cameras, and the baseline's σ against Monte Carlo.
#include <gtest/gtest.h>

#include <cmath>

#include "support/error_of.h"
#include "support/stereo_rigs.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/random/philox.h"
#include "vstcal/stereo/rectify.h"

namespace vstcal {
namespace {

using testing::ErrorOf;
using testing::SampleRelativePoseCovariance;
using testing::ZedLikeRig;

const Provenance kProvenance{"stereo_rig_test", {"--flag"}, std::nullopt};

std::string Write(const StereoRig& rig) { return DumpJson(StereoRigToJson(rig, kProvenance)); }
StereoRig Read(const std::string& text) { return StereoRigFromJson(JsonDocument::Parse(text, "rig.json")); }

// Everything a rig file can hold.
StereoRig FullRig() {
  StereoRig rig = ZedLikeRig();
  rig.covariance = SampleRelativePoseCovariance();
  rig.rectification = Rectify(rig, {0.5, true}, "rig");
  rig.fit = StereoFit{{0.21, 0.9, 540}, {{"pair-00", {0.2, 0.8, 54}}, {"pair-01", {0.22, 0.9, 54}}}};
  ParameterCovariance intrinsics;
  intrinsics.parameters = {"fx", "fy", "k1"};
  intrinsics.matrix = Eigen::Vector3d(0.04, 0.05, 1e-8).asDiagonal();
  intrinsics.matrix(0, 1) = intrinsics.matrix(1, 0) = 0.03;
  rig.left.covariance = intrinsics;
  return rig;
}

TEST(StereoRigIo, ReadThenWriteIsByteIdentical) {
  for (const StereoRig& rig : {ZedLikeRig(false), ZedLikeRig(), FullRig()}) {
    const std::string text = Write(rig);
    EXPECT_EQ(Write(Read(text)), text);
  }
}

TEST(StereoRigIo, ReadsBackEveryField) {
  const StereoRig rig = FullRig();
  const StereoRig back = Read(Write(rig));
  EXPECT_EQ(back.length_unit, rig.length_unit);
  EXPECT_EQ(back.method, "assembled");
  EXPECT_EQ(back.left.camera.params, rig.left.camera.params);
  EXPECT_EQ(back.right.camera.params, rig.right.camera.params);
  EXPECT_EQ(back.left.name, "left");
  EXPECT_EQ(back.right_from_left.R, rig.right_from_left.R);  // kept bit for bit: a rotation to rounding
  EXPECT_EQ(back.right_from_left.t, rig.right_from_left.t);
  ASSERT_TRUE(back.covariance && back.rectification && back.fit && back.left.covariance);
  EXPECT_EQ(back.covariance->matrix, rig.covariance->matrix);
  EXPECT_EQ(back.rectification->Q, rig.rectification->Q);
  EXPECT_EQ(back.rectification->valid_roi_right, rig.rectification->valid_roi_right);
  EXPECT_EQ(back.fit->views[1].name, "pair-01");
  EXPECT_EQ(back.left.covariance->matrix, rig.left.covariance->matrix);
  const OrderedJson j = StereoRigToJson(rig, kProvenance);
  EXPECT_EQ(j["baseline"].get<double>(), rig.right_from_left.t.norm());
  EXPECT_TRUE(j["left"].find("provenance") == j["left"].end());  // one provenance, the rig's
  EXPECT_TRUE(StereoRigToJson(ZedLikeRig(), kProvenance)["fit"].is_null());
}

// R written by another tool with 9 digits is a rotation within 1e-6: replaced by the nearest one.
TEST(StereoRigIo, CoarseRotationIsOrthonormalized) {
  OrderedJson j = StereoRigToJson(ZedLikeRig(), kProvenance);
  j["right_from_left"]["R"][0][0] = std::round(j["right_from_left"]["R"][0][0].get<double>() * 1e9) / 1e9;
  const StereoRig back = Read(DumpJson(j));
  EXPECT_LT((back.right_from_left.R.transpose() * back.right_from_left.R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-15);
}

// A rectification of another rig does not align this one's cameras.
TEST(StereoRigIo, RectificationMustFitTheRig) {
  StereoRig other = ZedLikeRig();
  other.right_from_left = Rigid3d::FromRotvec(Eigen::Vector3d(0, 0.02, 0), other.right_from_left.t);
  StereoRig rig = ZedLikeRig();
  rig.rectification = Rectify(other, {}, "other");
  EXPECT_NE(ErrorOf([&] { Read(Write(rig)); }).find("rig.json: rectification: its rotations do not align the cameras"),
            std::string::npos);
  // Q of another focal length reprojects to the wrong point.
  rig.rectification = Rectify(rig, {}, "rig");
  rig.rectification->Q(2, 3) *= 1.01;
  EXPECT_NE(ErrorOf([&] { Read(Write(rig)); }).find("rig.json: rectification.Q: does not reproject"), std::string::npos);
}

// σ_b² = t̂ᵀ Σ_ρρ t̂ (a rotation about the origin keeps |t|): against |Exp(ω) t + ρ| for 40,000
// draws of (ω, ρ) ~ N(0, Σ). The σ of a sample of N has relative standard error 1/√(2N) = 0.35 %.
TEST(StereoRig, BaselineSigmaMatchesMonteCarlo) {
  StereoRig rig = ZedLikeRig();
  rig.covariance = SampleRelativePoseCovariance();
  // Rotations large enough that a first-order error in ω would show: σ 1.5° per axis.
  rig.covariance->matrix.topLeftCorner<3, 3>() *= 900.0;
  const Eigen::Matrix<double, 6, 6> L = rig.covariance->matrix.llt().matrixL();
  const CounterRng rng(11, 0);
  const int n = 40000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    Eigen::Matrix<double, 6, 1> z;
    for (uint32_t k = 0; k < 3; ++k) {
      const auto g = rng.Normal2(static_cast<uint64_t>(i), k);
      z(2 * k) = g[0], z(2 * k + 1) = g[1];
    }
    const Eigen::Matrix<double, 6, 1> d = L * z;
    const double b = PerturbLeft(rig.right_from_left, Eigen::Vector3d(d.head<3>()), Eigen::Vector3d(d.tail<3>())).t.norm();
    sum += b, sum2 += b * b;
  }
  const double mean = sum / n, sigma = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(sigma / *BaselineSigma(rig), 1.0, 4 * std::sqrt(0.5 / n));
  // The rotation's σ per axis is the covariance's, in radians.
  EXPECT_NEAR(RelativeRotationSigma(rig)->x(), std::sqrt(rig.covariance->matrix(0, 0)), 1e-15);
}

CalibratedCamera Posed(const Camera& camera, const Rigid3d& camera_from_world, LengthUnit unit = LengthUnit::kMillimetre) {
  CalibratedCamera c;
  c.camera = camera;
  c.method = "dlt";
  c.length_unit = unit;
  c.camera_from_world = camera_from_world;
  ParameterCovariance cov;
  cov.parameters = {"fx", "camera_from_world.tz", "cx"};
  cov.matrix = Eigen::Matrix3d::Identity();
  cov.matrix(0, 2) = cov.matrix(2, 0) = 0.5;
  cov.matrix(0, 1) = cov.matrix(1, 0) = 0.25;
  c.covariance = cov;
  return c;
}

TEST(StereoRig, AssembleDerivesTheRigFromPosesInOneWorld) {
  const StereoRig truth = ZedLikeRig();
  const Rigid3d left_from_world = Rigid3d::FromRotvec(Eigen::Vector3d(0.1, -0.3, 0.05), Eigen::Vector3d(40, -20, 1500));
  AssembleInput in;
  in.left = Posed(truth.left.camera, left_from_world);
  in.right = Posed(truth.right.camera, truth.right_from_left * left_from_world);
  const StereoRig rig = AssembleRig(in);
  EXPECT_LT((rig.right_from_left.R - truth.right_from_left.R).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((rig.right_from_left.t - truth.right_from_left.t).norm(), 1e-12);
  EXPECT_EQ(rig.method, "assembled");
  EXPECT_EQ(rig.left.name, "left");
  EXPECT_FALSE(rig.left.camera_from_world.has_value());
  // The intrinsics' marginal covariance: the pose rows and columns dropped, the rest kept.
  ASSERT_TRUE(rig.left.covariance.has_value());
  EXPECT_EQ(rig.left.covariance->parameters, (std::vector<std::string>{"fx", "cx"}));
  EXPECT_EQ(rig.left.covariance->matrix(0, 1), 0.5);
  // And the file it writes reads back.
  EXPECT_EQ(Write(Read(Write(rig))), Write(rig));
}

TEST(StereoRig, AssembleRefusesWhatItCannotKnow) {
  const StereoRig truth = ZedLikeRig();
  AssembleInput in;
  in.left = Posed(truth.left.camera, Rigid3d::Identity());
  in.right = Posed(truth.right.camera, truth.right_from_left, LengthUnit::kMetre);
  in.left_name = "l.json";
  in.right_name = "r.json";
  EXPECT_EQ(ErrorOf([&] { AssembleRig(in); }),
            "r.json: length_unit: \"m\", but l.json is in \"mm\": their poses cannot be composed; give both cameras in "
            "one length unit");
  in.right.camera_from_world.reset();
  EXPECT_NE(ErrorOf([&] { AssembleRig(in); }).find("r.json: camera_from_world: absent"), std::string::npos);
  in.right_from_left = Rigid3d::Identity();
  EXPECT_NE(ErrorOf([&] { AssembleRig(in); }).find("right_from_left: the two cameras coincide (baseline 0)"), std::string::npos);
  in.right_from_left->t = Eigen::Vector3d(3e200, 0, 0);  // finite, but its square is not
  EXPECT_NE(ErrorOf([&] { AssembleRig(in); }).find("right_from_left: the baseline is too large to compute with"), std::string::npos);
  // Given, with its unit, the rig takes it whatever the cameras' units: they hold no lengths.
  in.right_from_left = truth.right_from_left;
  in.length_unit = LengthUnit::kCentimetre;
  const StereoRig rig = AssembleRig(in);
  EXPECT_EQ(rig.length_unit, LengthUnit::kCentimetre);
  EXPECT_EQ(rig.right.length_unit, LengthUnit::kCentimetre);
}

}  // namespace
}  // namespace vstcal
