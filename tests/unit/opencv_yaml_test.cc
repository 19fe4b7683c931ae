// OpenCV FileStorage YAML: exact round trips for every lens model, and OpenCV itself as the peer
// (it reads what we write and projects the same pixels; we read what it writes).
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "support/error_of.h"
#include "support/interop_cameras.h"
#include "support/scenes.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/opencv_yaml.h"

namespace vstcal {
namespace {

using testing::ErrorOf;
using testing::InteropCameras;
using testing::PointsInFront;

const Provenance kProvenance{"opencv_yaml_test", {"--flag", "a\nb"}, std::nullopt};

ImportedCamera ReadText(const std::string& text) {
  return OpenCvYamlFromText(text, "cam.yaml", LengthUnit::kMillimetre);
}

std::string WriteText(const CalibratedCamera& c) { return OpenCvYamlText(c, "cam.json", kProvenance).text; }

TEST(OpenCvYaml, RoundTripIsExactForEveryModel) {
  for (const CalibratedCamera& c : InteropCameras(false)) {
    const ImportedCamera back = ReadText(WriteText(c));
    EXPECT_EQ(LensModelName(back.camera.camera.model), LensModelName(c.camera.model));
    EXPECT_EQ(back.camera.camera.params, c.camera.params) << LensModelName(c.camera.model);  // bit for bit
    EXPECT_EQ(back.camera.camera.image_size, c.camera.image_size);
    EXPECT_EQ(back.camera.method, "opencv");
    EXPECT_TRUE(back.notes.empty() == (c.camera.distortion().size() > 0)) << LensModelName(c.camera.model);
  }
}

// OpenCV reads our file with its own FileStorage and projects with cv::projectPoints: the pixels
// agree with ours. This is what an OpenCV user gets from calib-convert.
TEST(OpenCvYaml, OpenCvReadsWhatWeWriteAndProjectsTheSame) {
  for (const CalibratedCamera& c : InteropCameras(false)) {
    cv::FileStorage fs(WriteText(c), cv::FileStorage::READ | cv::FileStorage::MEMORY);
    cv::Mat K, d;
    fs["camera_matrix"] >> K;
    fs["distortion_coefficients"] >> d;
    EXPECT_EQ(static_cast<int>(fs["image_width"]), c.camera.image_size.width);
    EXPECT_EQ(static_cast<int>(fs["image_height"]), c.camera.image_size.height);
    ASSERT_EQ(K.rows, 3);
    ASSERT_EQ(static_cast<size_t>(d.total()), c.camera.distortion().size());
    const auto points = PointsInFront(1000, 21);
    std::vector<cv::Point3d> object;
    for (const auto& p : points) object.emplace_back(p.x(), p.y(), p.z());
    std::vector<cv::Point2d> image;
    cv::projectPoints(object, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, d, image);
    double worst = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      worst = std::max(worst, (*c.camera.Project(points[i]) - Eigen::Vector2d(image[i].x, image[i].y)).norm());
    }
    EXPECT_LT(worst, 1e-9) << LensModelName(c.camera.model);
  }
}

// A file as OpenCV's calibration sample writes it, with the fields we ignore, written here by
// cv::FileStorage itself.
std::string SampleFile(const cv::Mat& K, const cv::Mat& d) {
  cv::FileStorage fs(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  fs << "calibration_time"
     << "Sat 21 Nov 2026 10:00:00 UTC";
  fs << "nframes" << 25 << "image_width" << 1920 << "image_height" << 1080;
  fs << "board_width" << 9 << "board_height" << 6 << "square_size" << 25.0;
  fs << "flags" << 16384;
  fs << "camera_matrix" << K;
  if (!d.empty()) fs << "distortion_coefficients" << d;
  fs << "avg_reprojection_error" << 0.31;
  fs << "extrinsic_parameters" << cv::Mat::zeros(25, 6, CV_64F);
  return fs.releaseAndGetString();
}

TEST(OpenCvYaml, ReadsFilesOpenCvWrites) {
  const cv::Mat K = (cv::Mat_<double>(3, 3) << 1402.123456789, 0, 961.5, 0, 1399.87654321, 539.25, 0, 0, 1);
  struct Case {
    cv::Mat d;
    std::string model;
    std::vector<double> expected;
  };
  const std::vector<Case> cases = {
      {(cv::Mat_<double>(5, 1) << -0.21, 0.05, 1e-12, -3e-4, -0.011),
       "radial-tangential",
       {-0.21, 0.05, 1e-12, -3e-4, -0.011}},
      {(cv::Mat_<double>(1, 5) << -0.21, 0.05, 1e-4, -3e-4, -0.011),
       "radial-tangential",
       {-0.21, 0.05, 1e-4, -3e-4, -0.011}},
      {(cv::Mat_<double>(1, 4) << -0.21, 0.05, 1e-4, -3e-4), "radial-tangential", {-0.21, 0.05, 1e-4, -3e-4, 0.0}},
      {(cv::Mat_<double>(8, 1) << 2.16, -1.18, -9.3e-5, 7.8e-4, -0.235, 2.446, -0.67, -0.628),
       "rational",
       {2.16, -1.18, -9.3e-5, 7.8e-4, -0.235, 2.446, -0.67, -0.628}},
      {cv::Mat(), "none", {}},
  };
  for (const Case& c : cases) {
    const ImportedCamera in = ReadText(SampleFile(K, c.d));
    const Camera& cam = in.camera.camera;
    EXPECT_EQ(LensModelName(cam.model), c.model);
    EXPECT_EQ(std::vector<double>(cam.distortion().begin(), cam.distortion().end()), c.expected) << c.model;
    EXPECT_EQ(cam.K()(0, 0), 1402.123456789);
    EXPECT_EQ(cam.K()(1, 1), 1399.87654321);
    EXPECT_EQ(cam.K()(0, 2), 961.5);
    EXPECT_EQ(cam.K()(1, 2), 539.25);
    EXPECT_EQ(cam.image_size, (ImageSize{1920, 1080}));
  }
}

// dt: f is float data: the values are the floats', as OpenCV reads them.
TEST(OpenCvYaml, ReadsFloatMatrices) {
  const cv::Mat K = (cv::Mat_<float>(3, 3) << 800.25f, 0, 320.5f, 0, 799.75f, 240.125f, 0, 0, 1);
  const cv::Mat d = (cv::Mat_<float>(5, 1) << -0.1f, 0.01f, 0, 0, 0);
  const Camera cam = ReadText(SampleFile(K, d)).camera.camera;
  EXPECT_EQ(cam.params[0], 800.25);
  EXPECT_EQ(cam.distortion()[0], static_cast<double>(-0.1f));
}

TEST(OpenCvYaml, SkewInTheFileIsKeptWithANote) {
  const cv::Mat K = (cv::Mat_<double>(3, 3) << 800, 0.75, 320, 0, 800, 240, 0, 0, 1);
  const ImportedCamera in = ReadText(SampleFile(K, cv::Mat::zeros(5, 1, CV_64F)));
  EXPECT_EQ(in.camera.camera.K()(0, 1), 0.75);
  ASSERT_EQ(in.notes.size(), 1u);
  EXPECT_NE(in.notes[0].find("cam.yaml: camera_matrix: K[0][1] (skew) = 0.75 is kept"), std::string::npos)
      << in.notes[0];
}

TEST(OpenCvYaml, RefusesToWriteSkew) {
  CalibratedCamera c = InteropCameras(false)[1];
  c.camera.params[4] = 0.5;  // s
  const std::string e = ErrorOf([&] { WriteText(c); });
  EXPECT_NE(e.find("cam.json: K[0][1]: the camera has skew 0.5 px, and OpenCV has no skew term"), std::string::npos)
      << e;
  // |s|·max|v − cy|/fy over the rows v ∈ [−0.5, 719.5]: cy = 359.9, fy = 1230.000000001.
  EXPECT_NE(e.find("up to 0.146504 px"), std::string::npos) << e;
}

TEST(OpenCvYaml, APoseIsNotWrittenAndANoteSaysSo) {
  const ExportedCamera out = OpenCvYamlText(InteropCameras(true)[1], "cam.json", kProvenance);
  EXPECT_EQ(out.text.find("camera_from_world"), std::string::npos);
  ASSERT_EQ(out.notes.size(), 1u);
  EXPECT_NE(out.notes[0].find("cam.json: camera_from_world: not written"), std::string::npos) << out.notes[0];
}

TEST(OpenCvYaml, ProvenanceIsAOneLineComment) {
  const std::string text = WriteText(InteropCameras(false)[1]);
  EXPECT_NE(text.find("# vstcal provenance: {\"tool\":\"opencv_yaml_test\",\"version\":"), std::string::npos) << text;
  EXPECT_NE(text.find(R"("args":["--flag","a\nb"],"seed":null})"), std::string::npos) << text;
}

// A fisheye is written with cv::fisheye's four coefficients and `distortion_model: fisheye`, read
// back bit for bit, and OpenCV reading the same file projects the same pixels with
// cv::fisheye::projectPoints.
TEST(OpenCvYaml, FisheyeRoundTripAndOpenCvFisheyeProjectsTheSame) {
  CalibratedCamera c;
  Eigen::Matrix3d K;
  K << 285.7, 0, 421.3, 0, 285.8, 398.6, 0, 0, 1;
  const double d[4] = {-0.0071, 0.0436, -0.0412, 0.0076};
  c.camera = Camera::FromK(K, ImageSize{848, 800}, KannalaBrandtModel{}, d);
  const std::string text = WriteText(c);
  EXPECT_NE(text.find("distortion_model: fisheye"), std::string::npos) << text;
  const ImportedCamera back = ReadText(text);
  EXPECT_EQ(LensModelName(back.camera.camera.model), "kannala-brandt");
  EXPECT_EQ(back.camera.camera.params, c.camera.params);
  EXPECT_TRUE(back.notes.empty());
  cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  cv::Mat cv_K, cv_d;
  fs["camera_matrix"] >> cv_K;
  fs["distortion_coefficients"] >> cv_d;
  ASSERT_EQ(cv_d.total(), 4u);
  std::vector<cv::Point3d> object;
  for (const auto& p : PointsInFront(500, 22)) object.emplace_back(p.x(), p.y(), p.z());
  std::vector<cv::Point2d> image;
  cv::fisheye::projectPoints(object, image, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), cv_K, cv_d);
  for (size_t i = 0; i < object.size(); ++i) {
    const Eigen::Vector3d p(object[i].x, object[i].y, object[i].z);
    EXPECT_LT((*c.camera.Project(p) - Eigen::Vector2d(image[i].x, image[i].y)).norm(), 1e-9);
  }
}

// Four coefficients without the key are calibrateCamera's (k1, k2, p1, p2), never guessed to be
// a fisheye's: a note says how a fisheye file says so. The key with another count or value is refused.
TEST(OpenCvYaml, FourCoefficientsAreFisheyeOnlyWhenTheFileSaysSo) {
  const cv::Mat K = (cv::Mat_<double>(3, 3) << 800, 0, 320, 0, 800, 240, 0, 0, 1);
  const std::string four = SampleFile(K, (cv::Mat_<double>(4, 1) << -0.21, 0.05, 1e-4, -3e-4));
  const ImportedCamera plumb = ReadText(four);
  EXPECT_EQ(LensModelName(plumb.camera.camera.model), "radial-tangential");
  ASSERT_EQ(plumb.notes.size(), 1u);
  EXPECT_NE(plumb.notes[0].find("cam.yaml: distortion_coefficients: 4 coefficients without distortion_model: read as "
                                "calibrateCamera's (k1, k2, p1, p2)"),
            std::string::npos)
      << plumb.notes[0];
  const ImportedCamera fisheye = ReadText(four + "distortion_model: fisheye\n");
  EXPECT_EQ(LensModelName(fisheye.camera.camera.model), "kannala-brandt");
  EXPECT_EQ(fisheye.camera.camera.params[5], -0.21);
  const std::string five = SampleFile(K, cv::Mat::zeros(5, 1, CV_64F)) + "distortion_model: fisheye\n";
  EXPECT_NE(ErrorOf([&] { ReadText(five); }).find("cam.yaml: distortion_coefficients: distortion_model fisheye takes 4"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { ReadText(four + "distortion_model: equidistant\n"); })
                .find("cam.yaml: distortion_model: expected \"fisheye\", got the string \"equidistant\""),
            std::string::npos);
}

// Thin-prism and tilted models are refused by name, not as a wrong length.
TEST(OpenCvYaml, RefusesThinPrismAndTiltedModels) {
  const cv::Mat K = (cv::Mat_<double>(3, 3) << 800, 0, 320, 0, 800, 240, 0, 0, 1);
  EXPECT_NE(ErrorOf([&] {
              ReadText(SampleFile(K, cv::Mat::zeros(12, 1, CV_64F)));
            }).find("cam.yaml: distortion_coefficients: 12 coefficients are OpenCV's thin-prism model"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              ReadText(SampleFile(K, cv::Mat::zeros(14, 1, CV_64F)));
            }).find("cam.yaml: distortion_coefficients: 14 coefficients are OpenCV's tilted-sensor model"),
            std::string::npos);
}

}  // namespace
}  // namespace vstcal
