// A 180°-class fisheye calibrated from rendered images (issue 23 item 3): calib-capture renders a
// chessboard through a Kannala–Brandt camera whose image is 179° across, detect finds its corners,
// calib-tsai --lens-model kannala-brandt solves them, and the camera lies within 4 σ of the
// rendering's truth on every lens parameter. OpenCV's cv::fisheye::calibrate on the same detected
// corners, in the same test, is the peer. docs/experiments/fisheye-rendered.md.
#include <cmath>
#include <cstdio>

#include <opencv2/calib3d.hpp>

#include "calibration_checks.h"
#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

// f ≈ 205 px on 640 × 480: θ = 320/205 rad = 89.4° at the side edges (179° across the width).
Json RenderedFisheyeTruth() {
  return Json::parse(R"({"format": "vstcal/camera@1", "image_size": [640, 480], "length_unit": "mm", "method": "synthetic",
    "K": [[205.3, 0, 321.7], [0, 204.6, 238.2], [0, 0, 1]],
    "distortion": {"model": "kannala-brandt", "k1": 0.021, "k2": -0.0043, "k3": 0.0011, "k4": -0.00017}})");
}

class CliFisheyeRender : public CliTest {};

TEST_F(CliFisheyeRender, RenderedFisheyeCalibratesToItsTruthWithinSigma) {
  WriteJson("in/fisheye.json", RenderedFisheyeTruth());
  const auto run = [&](std::string_view tool, const std::vector<std::string>& args) {
    const CommandResult r = Run(tool, args);
    EXPECT_EQ(r.exit_code, kOk) << tool << ": " << r.err;
    return r.exit_code == kOk;
  };
  ASSERT_TRUE(run("calib-capture", {"target", "--rows", "6", "--cols", "8", "--square-size", "30", "--dpi", "0", "-o",
                                    "in/board"}));
  // Boards 270 × 210 mm at ~220 mm: each fills a third of the image, aimed up to 62° off the axis.
  ASSERT_TRUE(run("calib-capture", {"render", "in/board.target.json", "--camera", "in/fisheye.json", "--rig",
                                    "planar-views", "--views", "10", "--distance", "220", "--seed", "3", "-o", "in/views"}));
  ASSERT_TRUE(run("calib-capture", {"detect", "in/board.target.json", "in/views/view-*.png", "-o", "in/corners.json"}));
  const CommandResult solve = Run("calib-tsai", {"in/corners.json", "--lens-model", "kannala-brandt", "-o", "out/camera.json"});
  ASSERT_EQ(solve.exit_code, kOk) << solve.err;

  const Json camera = ReadJson("out/camera.json");
  // 179° across: the start came from the equidistant rounds, not from Zhang's pinhole on the raw
  // corners, and the file and the summary say so (docs/formats.md#camera-fisheye-start).
  const std::string chosen = camera.at("fisheye_start").at("chosen").get<std::string>();
  EXPECT_EQ(chosen.rfind("equidistant rounds from", 0), 0u) << chosen;
  EXPECT_NE(solve.err.find("  fisheye start: " + chosen + ", "), std::string::npos) << solve.err;
  // The reports take the fisheye as any camera (issue 23 item 3): reproj-report's residuals through
  // the Kannala–Brandt projection, corners past 70° off the axis included, are the solver's own fit.
  const CommandResult report = Run("reproj-report", {"out/camera.json", "in/corners.json", "-o", "out/report.json"});
  ASSERT_EQ(report.exit_code, kOk) << report.err;
  const Json reported = ReadJson("out/report.json")["cameras"][0]["overall"]["error_px"];
  EXPECT_EQ(reported["n"], camera["fit"]["n_points"]);
  EXPECT_NEAR(reported["rms"].get<double>(), camera["fit"]["rms_px"].get<double>(), 1e-9);
  const Json truth = ReadJson("in/views/camera.truth.json");
  const std::vector<std::string> names = {"fx", "fy", "cx", "cy", "k1", "k2", "k3", "k4"};
  EXPECT_EQ(camera.at("distortion").at("model"), "kannala-brandt");
  EXPECT_TRUE(WithinSigmas(camera, truth, names, 4));

  // The detected corners reach far off the axis: the set is a fisheye's, not a pinhole's.
  const Json corners = ReadJson("in/corners.json");
  std::vector<std::vector<cv::Point3d>> object;
  std::vector<std::vector<cv::Point2d>> image;
  double widest_deg = 0;
  for (const Json& view : corners.at("views")) {
    object.emplace_back();
    image.emplace_back();
    for (const Json& p : view.at("points")) {
      object.back().emplace_back(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
      image.back().emplace_back(p[3].get<double>(), p[4].get<double>());
      const double theta_d = std::hypot((p[3].get<double>() - 321.7) / 205.3, (p[4].get<double>() - 238.2) / 204.6);
      widest_deg = std::max(widest_deg, theta_d * 180 / M_PI);
    }
  }
  EXPECT_GE(object.size(), 8u);
  EXPECT_GT(widest_deg, 70.0);

  // Peer: OpenCV's fisheye calibration (its own start, skew fixed) on the same corners.
  cv::Matx33d K;
  cv::Vec4d D;
  std::vector<cv::Vec3d> rvecs, tvecs;
  const double rms = cv::fisheye::calibrate(object, image, cv::Size(640, 480), K, D, rvecs, tvecs,
                                            cv::fisheye::CALIB_RECOMPUTE_EXTRINSIC | cv::fisheye::CALIB_FIX_SKEW,
                                            cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-12));
  const double opencv[8] = {K(0, 0), K(1, 1), K(0, 2), K(1, 2), D[0], D[1], D[2], D[3]};
  std::printf("%-4s %12s %14s %12s %14s\n", "", "truth", "vstcal", "sigma", "opencv");
  for (size_t i = 0; i < names.size(); ++i) {
    const double ours = LensParameter(camera, names[i]), sigma = Sigma(camera, names[i]);
    std::printf("%-4s %12.6g %14.8g %12.4g %14.8g\n", names[i].c_str(), LensParameter(truth, names[i]), ours, sigma, opencv[i]);
    // The same corners, the same model, the same least squares: one optimum.
    EXPECT_NEAR(opencv[i], ours, 0.1 * sigma) << names[i];
  }
  std::printf("RMS vstcal %.4f px, opencv %.4f px (OpenCV's is per coordinate)\n", camera.at("fit").at("rms_px").get<double>(),
              rms);
}

}  // namespace
}  // namespace vstcal::cli_test
