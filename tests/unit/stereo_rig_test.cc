// vstcal/stereo@1: the rig type, its reader and writer (byte-identical round trips), assembling a
// rig from two cameras, and the baseline's σ against Monte Carlo.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

#include "support/error_of.h"
#include "support/capture_scenes.h"
#include "support/stereo_rigs.h"
#include "vstcal/capture/target_pattern.h"
#include "vstcal/image/undistort.h"
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
  rig.view_pairing = ViewPairing{"([0-9]+)$", "names differ only by left/right (left01 ↔ right01); paired by the number in the name"};
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
  ASSERT_TRUE(back.view_pairing);
  EXPECT_EQ(back.view_pairing->match_views, "([0-9]+)$");
  EXPECT_EQ(back.view_pairing->rule, rig.view_pairing->rule);
  const OrderedJson j = StereoRigToJson(rig, kProvenance);
  EXPECT_EQ(j["baseline"].get<double>(), rig.right_from_left.t.norm());
  EXPECT_TRUE(j["left"].find("provenance") == j["left"].end());  // one provenance, the rig's
  EXPECT_TRUE(StereoRigToJson(ZedLikeRig(), kProvenance)["fit"].is_null());
}

// A stored pairing is an expression with a group, as --match-views takes it.
TEST(StereoRigIo, ViewPairingIsAnExpressionWithAGroup) {
  OrderedJson j = StereoRigToJson(FullRig(), kProvenance);
  j["view_pairing"]["match_views"] = "[0-9]+$";
  EXPECT_NE(ErrorOf([&] { Read(DumpJson(j)); }).find("rig.json: view_pairing.match_views: "), std::string::npos) << ErrorOf([&] { Read(DumpJson(j)); });
  EXPECT_NE(ErrorOf([&] { Read(DumpJson(j)); }).find("has no group"), std::string::npos);
  j["view_pairing"]["match_views"] = "((";
  EXPECT_NE(ErrorOf([&] { Read(DumpJson(j)); }).find("is not a regular expression"), std::string::npos);
}

// Pairing by the names, derived by hand for each naming the issue lists: the key is the number
// that changes from view to view, the rest of the names one text per camera that differs by a
// left/right token. Each derived expression, applied as --match-views, gives both cameras' views
// the same keys.
TEST(ViewPairing, DerivedFromNamesThatDifferByALeftRightToken) {
  struct Case {
    std::vector<std::string> left, right;
    std::string pattern, token;
    size_t paired;
  };
  const std::vector<Case> cases = {
      {{"left01", "left02", "left03"}, {"right01", "right02", "right04"}, "([0-9]+)$", "left/right", 2},
      {{"img_left_3", "img_left_4"}, {"img_right_3", "img_right_4"}, "([0-9]+)$", "left/right", 2},
      {{"L7.png", "L8.png"}, {"R7.png", "R8.png"}, "([0-9]+)[^0-9]*$", "L/R", 2},
      {{"cam0_img5", "cam0_img6"}, {"cam1_img5", "cam1_img6"}, "([0-9]+)$", "cam0/cam1", 2},
      {{"5_cam0", "6_cam0"}, {"5_cam1", "6_cam1"}, "^[^0-9]*([0-9]+)", "cam0/cam1", 2},
      {{"0_img5", "0_img6"}, {"1_img5", "1_img6"}, "([0-9]+)$", "0/1", 2},
      {{"s2_l_07_x", "s2_l_08_x"}, {"s2_r_07_x", "s2_r_08_x"}, "([0-9]+)[^0-9]*$", "l/r", 2},
      {{"s2_l_07_v9", "s2_l_08_v9"}, {"s2_r_07_v9", "s2_r_08_v9"}, "^[^0-9]*(?:[0-9]+[^0-9]*){1}([0-9]+)", "l/r", 2},
      {{"left01"}, {"right01"}, "([0-9]+)$", "left/right", 1},  // one view each: the last number
  };
  for (const Case& c : cases) {
    const DerivedPairing d = DeriveViewPairing(c.left, c.right);
    ASSERT_TRUE(d.pairing) << c.left[0] << ": " << d.problem;
    EXPECT_EQ(d.pairing->match_views, c.pattern) << c.left[0];
    EXPECT_NE(d.pairing->rule.find("names differ only by " + c.token + " (" + c.left[0] + " ↔ " + c.right[0] + ")"), std::string::npos)
        << d.pairing->rule;
    EXPECT_EQ(d.paired, c.paired) << c.left[0];
    Correspondences l, r;
    for (const auto& [names, views] : {std::pair{&c.left, &l.views}, std::pair{&c.right, &r.views}}) {
      for (const std::string& n : *names) views->emplace_back().name = n;
    }
    KeyViews(d.pairing->match_views, "l", &l);
    KeyViews(d.pairing->match_views, "r", &r);
    EXPECT_EQ(l.views[0].name, r.views[0].name) << c.left[0];
    EXPECT_NE(l.views[0].name, c.left[0]);
  }
}

// Names that cannot be paired by themselves: the reason, and the expression the numbers allow.
TEST(ViewPairing, RefusedWithTheExpressionTheNumbersAllow) {
  DerivedPairing d = DeriveViewPairing({"a_01", "a_02"}, {"b_01", "b_02"});  // a/b is no left/right token
  EXPECT_FALSE(d.pairing);
  EXPECT_EQ(d.suggestion, "([0-9]+)$");
  EXPECT_NE(d.problem.find("do not differ by a left/right token"), std::string::npos) << d.problem;
  d = DeriveViewPairing({"left01", "leftx02"}, {"right01", "right02"});  // another shape? no: one more letter
  EXPECT_FALSE(d.pairing);
  EXPECT_EQ(d.suggestion, "([0-9]+)$");
  EXPECT_NE(d.problem.find("differ by more than their number"), std::string::npos) << d.problem;
  d = DeriveViewPairing({"left01", "left02"}, {"right03", "right04"});  // no number in common
  EXPECT_FALSE(d.pairing);
  EXPECT_EQ(d.suggestion, "");
  d = DeriveViewPairing({"left_a", "left_b"}, {"right_a", "right_b"});  // no number
  EXPECT_FALSE(d.pairing);
  EXPECT_EQ(d.suggestion, "");
  EXPECT_NE(d.problem.find("no number"), std::string::npos);
  d = DeriveViewPairing({"left01", "left01b"}, {"right01", "right01b"});  // two shapes
  EXPECT_FALSE(d.pairing);
  EXPECT_NE(d.problem.find("one shape"), std::string::npos);
  d = DeriveViewPairing({"s1_left01", "s2_left02"}, {"s1_right01", "s2_right02"});  // two numbers change
  EXPECT_FALSE(d.pairing);
  EXPECT_NE(d.problem.find("more than one number"), std::string::npos);
}

// OpenCV's (the peer's) corners of a 9 × 6 board in one half of a rectified pair, refined.
std::vector<cv::Point2f> BoardCorners(const GrayImage& pair, bool right_half) {
  const int w = pair.width / 2;
  const cv::Mat whole(pair.height, pair.width, CV_8U, const_cast<uint8_t*>(pair.pixels.data()));
  const cv::Mat half = whole(cv::Rect(right_half ? w : 0, 0, w, pair.height)).clone();
  std::vector<cv::Point2f> corners;
  if (!cv::findChessboardCorners(half, cv::Size(9, 6), corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) return {};
  cv::cornerSubPix(half, corners, cv::Size(5, 5), cv::Size(-1, -1), cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4));
  return corners;
}

// Issue 24 item 4: a noise-free board rendered through both distorted cameras of the ZED-like
// rig, at three poses, rectified by RectifiedPairImage (vstcal's maps, OpenCV's remap, no lines
// drawn): every corner OpenCV finds in the left half is on the row of its match in the right
// half, within 0.1 px; in the raw images the rows differ by pixels (the test could fail).
TEST(RectifiedPairImage, CorrespondingCornersShareARow) {
  const StereoRig rig = ZedLikeRig();
  const Rectification rect = Rectify(rig, {}, "rig");
  const Target board = testing::Chessboard9x6();
  const Pattern pattern = TargetPattern(board);
  RenderOptions options;
  options.blur_px = 0.8;
  const PixelCornerRays rays_left(rig.left.camera), rays_right(rig.right.camera);
  double worst = 0, raw_worst = 0;
  const Rigid3d poses[] = {Rigid3d::FromRotvec(Eigen::Vector3d(0.1, -0.2, 0.05), Eigen::Vector3d(-130, -70, 700)),
                           Rigid3d::FromRotvec(Eigen::Vector3d(-0.3, 0.1, 0.2), Eigen::Vector3d(-300, 20, 800)),
                           Rigid3d::FromRotvec(Eigen::Vector3d(0.2, 0.3, -0.1), Eigen::Vector3d(60, -150, 650))};
  for (const Rigid3d& left_from_board : poses) {
    const Rigid3d right_from_board = rig.right_from_left * left_from_board;
    const GrayImage left = RenderView(rays_left, pattern, left_from_board, options, 0);
    const GrayImage right = RenderView(rays_right, pattern, right_from_board, options, 0);
    const std::vector<cv::Point2f> l = BoardCorners(RectifiedPairImage(rig, rect, left, right, 0), false);
    const std::vector<cv::Point2f> r = BoardCorners(RectifiedPairImage(rig, rect, left, right, 0), true);
    ASSERT_EQ(l.size(), 54u);
    ASSERT_EQ(r.size(), 54u);
    for (size_t k = 0; k < 54; ++k) worst = std::max(worst, static_cast<double>(std::abs(l[k].y - r[k].y)));
    // The same corners in the raw images: side by side without rectification.
    GrayImage raw(2 * left.width, left.height);
    for (int v = 0; v < left.height; ++v) {
      for (int u = 0; u < left.width; ++u) {
        raw.at(u, v) = left.at(u, v);
        raw.at(left.width + u, v) = right.at(u, v);
      }
    }
    const std::vector<cv::Point2f> rl = BoardCorners(raw, false), rr = BoardCorners(raw, true);
    ASSERT_EQ(rl.size(), 54u);
    ASSERT_EQ(rr.size(), 54u);
    for (size_t k = 0; k < 54; ++k) raw_worst = std::max(raw_worst, static_cast<double>(std::abs(rl[k].y - rr[k].y)));
  }
  EXPECT_LT(worst, 0.1) << raw_worst;
  EXPECT_GT(raw_worst, 2.0) << worst;
}

// Undistortion of a pinhole camera is the identity map (pixel centres at integers).
TEST(RectifiedPairImage, UndistortMapOfAPinholeIsTheIdentity) {
  const Camera pinhole = ZedLikeRig(false).left.camera;
  const PixelMap map = UndistortMap(pinhole);
  for (const auto& [u, v] : {std::pair{0, 0}, std::pair{1279, 719}, std::pair{640, 360}}) {
    const size_t k = static_cast<size_t>(v) * 1280 + static_cast<size_t>(u);
    EXPECT_NEAR(map.x[k], u, 1e-3);
    EXPECT_NEAR(map.y[k], v, 1e-3);
  }
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
