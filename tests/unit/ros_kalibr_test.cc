// ROS camera_info and Kalibr camchain.yaml: the readers against hand-written sample files
// (tests/data/README.md: written from the formats' descriptions, not by vstcal), each writer's
// output laid out as the samples are, files read and written again being the same bytes, and a
// rig's ROS rectification beside cv::stereoRectify run here.
#include <gtest/gtest.h>

#include <charconv>
#include <fstream>
#include <sstream>

#include <Eigen/Core>  // before opencv2/core/eigen.hpp, which needs it
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>

#include "support/stereo_rigs.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/kalibr_camchain.h"
#include "vstcal/formats/camera/ros_camera_info.h"
#include "vstcal/formats/camera/yaml_tree.h"
#include "vstcal/formats/stereo/rig_interop.h"

namespace vstcal {
namespace {

const Provenance kProvenance{"ros_kalibr_test", {}, std::nullopt};

std::string Sample(const std::string& relative) {
  std::ifstream in(std::string(VSTCAL_SOURCE_DIR) + "/tests/data/" + relative);
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_FALSE(s.str().empty()) << relative;
  return s.str();
}

// The top-level keys of a YAML text in file order.
std::vector<std::string> Keys(const std::string& text) {
  std::vector<std::string> keys;
  for (const auto& [key, value] : ParseYamlMap(text, "t.yaml", "a test file").members) keys.push_back(key);
  return keys;
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

RosCameraInfo Ros(const std::string& text) { return RosCameraInfoFromText(text, "cam.yaml", LengthUnit::kMillimetre); }

TEST(RosCameraInfo, ReadsTheMonocularSample) {
  const std::string text = Sample("ros/mono_plumb_bob.yaml");
  const RosCameraInfo info = Ros(text);
  const Camera& c = info.camera.camera;
  EXPECT_EQ(info.camera.name, "narrow_stereo");
  EXPECT_EQ(c.image_size.width, 640);
  EXPECT_EQ(c.image_size.height, 480);
  EXPECT_EQ(LensModelName(c.model), "radial-tangential");
  Eigen::Matrix3d K;
  K << 423.10428, 0, 309.05867, 0, 424.08911, 227.45914, 0, 0, 1;
  EXPECT_EQ(c.K(), K);
  EXPECT_EQ(std::vector<double>(c.distortion().begin(), c.distortion().end()),
            (std::vector<double>{-0.322543, 0.104152, -0.000386, 0.000593, 0.0}));
  EXPECT_EQ(info.rectification, Eigen::Matrix3d::Identity());
  Matrix34d P;
  P << 339.45395, 0, 308.37622, 0, 0, 385.20322, 225.7627, 0, 0, 0, 1, 0;
  EXPECT_EQ(info.projection, P);
  // P ≠ [K | 0]: a rectification camera@1 does not hold, so a note says it is not kept.
  const ImportedCamera in = ImportRosCameraInfo(info, "cam.yaml");
  ASSERT_EQ(in.notes.size(), 1u);
  EXPECT_NE(in.notes[0].find("projection_matrix"), std::string::npos);
}

TEST(RosCameraInfo, ReadsTheStereoSamplesRectification) {
  const RosCameraInfo left = Ros(Sample("ros/stereo_left.yaml")), right = Ros(Sample("ros/stereo_right.yaml"));
  EXPECT_EQ(left.rectification(0, 1), -0.001103671718363574);
  EXPECT_EQ(left.projection.col(3), Eigen::Vector3d::Zero());
  // sensor_msgs/CameraInfo: Tx = P[0][3] = −fx'·B, B the baseline in metres.
  EXPECT_EQ(-right.projection(0, 3) / right.projection(0, 0), 0.12);
  EXPECT_EQ(right.camera.name, "right");
}

TEST(RosCameraInfo, ReadsRationalPolynomialAndEquidistant) {
  const RosCameraInfo r = Ros(Sample("ros/rational_polynomial.yaml"));
  EXPECT_EQ(LensModelName(r.camera.camera.model), "rational");
  EXPECT_EQ(std::vector<double>(r.camera.camera.distortion().begin(), r.camera.camera.distortion().end()),
            (std::vector<double>{0.25, -0.0625, 0.0001, -0.0002, 0.003, 0.6, -0.05, 0.012}));
  // image_geometry projects "equidistant" with cv::fisheye: vstcal's "kannala-brandt", k1…k4 as written.
  const RosCameraInfo f = Ros(Sample("ros/equidistant.yaml"));
  EXPECT_EQ(LensModelName(f.camera.camera.model), "kannala-brandt");
  EXPECT_EQ(std::vector<double>(f.camera.camera.distortion().begin(), f.camera.camera.distortion().end()),
            (std::vector<double>{-0.0071, 0.0436, -0.0412, 0.0076}));
  const std::string e = ErrorOf([] {
    Ros(Sample("ros/equidistant.yaml").replace(Sample("ros/equidistant.yaml").find("cols: 4"), 7, "cols: 5"));
  });
  EXPECT_NE(e.find("cam.yaml: distortion_coefficients: expected 1×4, got 1×5"), std::string::npos) << e;
}

// Written, each sample reads back as the same camera, R and P, in the samples' field order, and a
// second pass gives the same bytes.
TEST(RosCameraInfo, WriterFollowsTheSamplesAndIsAFixedPoint) {
  for (const std::string name : {"mono_plumb_bob", "stereo_left", "stereo_right", "rational_polynomial", "equidistant"}) {
    const std::string sample = Sample("ros/" + name + ".yaml");
    const RosCameraInfo info = Ros(sample);
    const std::string once = RosCameraInfoText(info, name, kProvenance).text;
    EXPECT_EQ(Keys(once), Keys(sample)) << name;
    const RosCameraInfo back = Ros(once);
    EXPECT_EQ(back.camera.camera.params, info.camera.camera.params) << name;
    EXPECT_EQ(back.rectification, info.rectification) << name;
    EXPECT_EQ(back.projection, info.projection) << name;
    EXPECT_EQ(RosCameraInfoText(back, name, kProvenance).text, once) << name;
  }
}

TEST(RosCameraInfo, SingleCameraGetsIdentityAndKZero) {
  CalibratedCamera cam;
  Eigen::Matrix3d K;
  K << 600, 0, 319.5, 0, 601, 239.5, 0, 0, 1;
  cam.camera = Camera::FromK(K, {640, 480});
  const ExportedCamera out = RosCameraInfoText(cam, "cam.json", kProvenance);
  const RosCameraInfo back = Ros(out.text);
  EXPECT_EQ(back.rectification, Eigen::Matrix3d::Identity());
  EXPECT_EQ(back.projection.leftCols<3>(), K);
  EXPECT_EQ(back.projection.col(3), Eigen::Vector3d::Zero());
  // "none" has no ROS name: plumb_bob with five zeros, said in a note.
  EXPECT_EQ(std::vector<double>(back.camera.camera.distortion().begin(), back.camera.camera.distortion().end()),
            std::vector<double>(5, 0.0));
  ASSERT_EQ(out.notes.size(), 1u);
  EXPECT_NE(out.notes[0].find("plumb_bob with five zeros"), std::string::npos);
}

TEST(KalibrCamchain, ReadsTheStereoSample) {
  std::vector<std::string> notes;
  const std::vector<KalibrCamera> chain = KalibrCamchainFromText(Sample("kalibr/camchain_stereo.yaml"), "c.yaml", &notes);
  ASSERT_EQ(chain.size(), 2u);
  const Camera& c0 = chain[0].camera.camera;
  EXPECT_EQ(c0.params, (std::vector<double>{458.654, 457.296, 367.215, 248.375, 0, -0.28340811, 0.07395907, 0.00019359,
                                            1.76187114e-05, 0}));
  EXPECT_EQ(c0.image_size.width, 752);
  EXPECT_EQ(c0.image_size.height, 480);
  EXPECT_EQ(chain[0].rostopic, "/cam0/image_raw");
  EXPECT_FALSE(chain[0].cam_from_previous);
  const Rigid3d& T = *chain[1].cam_from_previous;
  EXPECT_EQ(T.R(0, 1), -0.0023246633354866717);  // a rotation to rounding: kept bit for bit
  EXPECT_EQ(T.t, Eigen::Vector3d(-0.110073808127187, 0.000399121547014, -0.000853702503357));
  // T_cam_imu and timeshift_cam_imu are not read, and said so.
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("cam0.T_cam_imu"), std::string::npos);
  EXPECT_NE(notes[1].find("cam0.timeshift_cam_imu"), std::string::npos);

  const StereoRig rig = RigFromKalibr(chain, "c.yaml");
  EXPECT_EQ(rig.length_unit, LengthUnit::kMetre);
  EXPECT_EQ(rig.right_from_left.t, T.t);
  EXPECT_EQ(rig.right.camera.params, chain[1].camera.camera.params);
}

TEST(KalibrCamchain, WriterFollowsTheSampleAndIsAFixedPoint) {
  std::vector<std::string> notes;
  const std::string sample = Sample("kalibr/camchain_stereo.yaml");
  const StereoRig rig = RigFromKalibr(KalibrCamchainFromText(sample, "c.yaml", &notes), "c.yaml");
  const std::string once = KalibrCamchainText(rig, "rig", kProvenance).text;
  // The layout of the sample: a block sequence of four rows at T_cn_cnm1's indentation, PyYAML's.
  EXPECT_NE(once.find("cam1:\n  T_cn_cnm1:\n  - [0.9999787501914441, -0.0023246633354866717, "
                      "-0.006090575172680886, -0.110073808127187]\n"),
            std::string::npos)
      << once;
  EXPECT_NE(once.find("  distortion_coeffs: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]\n"),
            std::string::npos)
      << once;
  EXPECT_EQ(Keys(once), (std::vector<std::string>{"cam0", "cam1"}));
  const StereoRig back = RigFromKalibr(KalibrCamchainFromText(once, "c.yaml", &notes), "c.yaml");
  EXPECT_EQ(back.left.camera.params, rig.left.camera.params);
  EXPECT_EQ(back.right_from_left.R, rig.right_from_left.R);
  EXPECT_EQ(back.right_from_left.t, rig.right_from_left.t);
  EXPECT_EQ(KalibrCamchainText(back, "rig", kProvenance).text, once);
}

TEST(KalibrCamchain, OneCameraAndThree) {
  std::vector<std::string> notes;
  EXPECT_EQ(KalibrCamchainFromText(Sample("kalibr/camchain_mono.yaml"), "m.yaml", &notes).size(), 1u);
  const auto three = KalibrCamchainFromText(Sample("kalibr/camchain_three.yaml"), "t.yaml", &notes);
  ASSERT_EQ(three.size(), 3u);
  const std::string e = ErrorOf([&] { RigFromKalibr(three, "t.yaml"); });
  EXPECT_EQ(e.rfind("t.yaml: cam2: a chain of 3 cameras, and a vstcal/stereo@1 rig holds two; ", 0), 0u) << e;
}

// Kalibr's pinhole-equidistant is cv::fisheye's model: read as "kannala-brandt", written back the same.
TEST(KalibrCamchain, EquidistantRoundTrip) {
  std::string sample = Sample("kalibr/camchain_mono.yaml");
  sample.replace(sample.find("distortion_model: radtan"), 24, "distortion_model: equidistant");
  std::vector<std::string> notes;
  const auto chain = KalibrCamchainFromText(sample, "m.yaml", &notes);
  ASSERT_EQ(chain.size(), 1u);
  const Camera& c = chain[0].camera.camera;
  EXPECT_EQ(LensModelName(c.model), "kannala-brandt");
  EXPECT_EQ(std::vector<double>(c.distortion().begin(), c.distortion().end()),
            (std::vector<double>{-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05}));
  const std::string once = KalibrCamchainText(chain, "m", kProvenance).text;
  EXPECT_NE(once.find("  distortion_model: equidistant\n"), std::string::npos) << once;
  const auto back = KalibrCamchainFromText(once, "m.yaml", &notes);
  EXPECT_EQ(back[0].camera.camera.params, c.params);
  EXPECT_EQ(KalibrCamchainText(back, "m", kProvenance).text, once);
}

TEST(KalibrCamchain, RadtanHasNoK3) {
  CalibratedCamera cam;
  Eigen::Matrix3d K;
  K << 600, 0, 319.5, 0, 601, 239.5, 0, 0, 1;
  const double d[5] = {-0.1, 0.01, 0, 0, 0.005};
  cam.camera = Camera::FromK(K, {640, 480}, RadialTangentialModel{}, d);
  KalibrCamera kc;
  kc.camera = cam;
  const std::string e = ErrorOf([&] { KalibrCamchainText({kc}, "cam.json", kProvenance); });
  EXPECT_EQ(e.rfind("cam.json: distortion: Kalibr's radtan holds k1, k2, r1, r2 only", 0), 0u) << e;
}

// The rig's two camera_info against cv::stereoRectify of the same rig, with t in metres as ROS
// measures it: R1, R2, P1 and P2 (whose P2[0][3] = −fx'·B).
TEST(RosStereo, RectificationIsOpenCvsStereoRectifyInMetres) {
  const StereoRig rig = testing::ZedLikeRig();  // mm
  const auto [left_text, right_text] = RosStereoTexts(rig, "rig.json", kProvenance);
  const RosCameraInfo left = Ros(left_text.text), right = Ros(right_text.text);
  cv::Mat K1, K2, R, t, D1, D2, R1, R2, P1, P2, Q;
  cv::eigen2cv(rig.left.camera.K(), K1);
  cv::eigen2cv(rig.right.camera.K(), K2);
  cv::eigen2cv(rig.right_from_left.R, R);
  const Eigen::Vector3d t_m = rig.right_from_left.t / 1000.0;
  cv::eigen2cv(t_m, t);
  D1 = cv::Mat(std::vector<double>(rig.left.camera.distortion().begin(), rig.left.camera.distortion().end()), true);
  D2 = cv::Mat(std::vector<double>(rig.right.camera.distortion().begin(), rig.right.camera.distortion().end()), true);
  cv::stereoRectify(K1, D1, K2, D2, cv::Size(1280, 720), R, t, R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, -1);
  auto expect_near = [](const Eigen::MatrixXd& ours, const cv::Mat& cv_m, const char* what) {
    Eigen::MatrixXd theirs;
    cv::cv2eigen(cv_m, theirs);
    ASSERT_EQ(ours.rows(), theirs.rows()) << what;
    EXPECT_LT((ours - theirs).cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, theirs.cwiseAbs().maxCoeff())) << what;
  };
  expect_near(left.rectification, R1, "R1");
  expect_near(right.rectification, R2, "R2");
  expect_near(left.projection, P1, "P1");
  expect_near(right.projection, P2, "P2");
  // sensor_msgs/CameraInfo: Tx = −fx'·B with B the baseline in metres (63.0016 mm here).
  EXPECT_NEAR(right.projection(0, 3), -right.projection(0, 0) * rig.baseline() / 1000.0, 1e-12 * right.projection(0, 0));
  EXPECT_EQ(left.camera.name, "left");
  EXPECT_EQ(right.camera.name, "right");
}

TEST(YamlFloat, ExactAndReadAsAFloatByYaml11) {
  EXPECT_EQ(YamlFloat(640), "640.0");
  EXPECT_EQ(YamlFloat(1e-12), "1.0e-12");
  EXPECT_EQ(YamlFloat(0.1), "0.1");
  EXPECT_EQ(YamlFloat(-2.5e20), "-2.5e+20");
  for (const double v : {0.1, 1.0 / 3.0, -1.76187114e-05, 6.02214076e23, 5e-324}) {
    const std::string s = YamlFloat(v);
    double back = 0;
    std::from_chars(s.data(), s.data() + s.size(), back);
    EXPECT_EQ(back, v) << s;
  }
}

TEST(YamlTree, RefusesWhatACameraFileNeverHas) {
  auto e = [](const std::string& text) { return ErrorOf([&] { ParseYamlMap(text, "f.yaml", "a test file"); }); };
  EXPECT_NE(e("a: 1\na: 2\n").find("f.yaml: line 2, column 1: the key \"a\" appears a second time"), std::string::npos);
  EXPECT_NE(e("a: &x 1\nb: *x\n").find("an alias"), std::string::npos);
  EXPECT_NE(e("a: 1\n---\nb: 2\n").find("a second YAML document"), std::string::npos);
  EXPECT_NE(e(std::string(100, '[') + std::string(100, ']')).find("nested more than 64 levels"), std::string::npos);
  EXPECT_NE(e("- 1\n- 2\n").find("the top level is not a map"), std::string::npos);
  EXPECT_NE(e("a: [1, 2\n").find("not valid YAML"), std::string::npos);
}

}  // namespace
}  // namespace vstcal
