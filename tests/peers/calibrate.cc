// peer_calibrate: one planar-views calibration in process, timed, for scripts/compare-peers.
//   opencv: cv::calibrateCamera as a user of OpenCV calls it (one object/image point list per
//           view, float32 points as OpenCV requires, CALIB_FIX_K3 so that the model is k1, k2, p1,
//           p2 like vstcal's default, OpenCV's own initial guess and termination criteria);
//   vstcal: vstcal::Calibrate with calib-tsai's defaults (Zhang's start, the refinement of k1, k2,
//           p1, p2 and the covariance), on the same file read the same way.
// One program for both, so that the two solves are timed on the same clock, and a process that
// solves once (REPEAT 1) gives the wall time of a whole calibration.
//
// Usage: peer_calibrate opencv|vstcal CORNERS.json [REPEAT]
// Prints one JSON object on stdout: fx, fy, cx, cy, k1, k2, p1, p2, the RMS reprojection error
// (√(Σ|r|²/N) over points, vstcal's fit.rms_px; OpenCV's return value is the same quantity) and the
// median wall time of REPEAT (default 5) solves. Exit code 2 for bad input, 3 when a solve fails.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>

#include "support/opencv_views.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/formats/camera/correspondences_io.h"

namespace {

using namespace vstcal;

struct Solution {
  double fx = 0, fy = 0, cx = 0, cy = 0, k1 = 0, k2 = 0, p1 = 0, p2 = 0, rms_px = 0;
};

Solution SolveOpenCv(const Correspondences& c) {
  const testing::OpenCvViews views = testing::ToOpenCvViews(c);
  cv::Mat K, d;
  std::vector<cv::Mat> rvecs, tvecs;
  const double rms = cv::calibrateCamera(views.object, views.image, cv::Size(c.image_size.width, c.image_size.height), K, d,
                                         rvecs, tvecs, cv::CALIB_FIX_K3);
  return {K.at<double>(0, 0), K.at<double>(1, 1), K.at<double>(0, 2), K.at<double>(1, 2), d.at<double>(0),
          d.at<double>(1),    d.at<double>(2),    d.at<double>(3),    rms};
}

Solution SolveVstcal(const Correspondences& c) {
  const CalibrationResult r = Calibrate(c, CalibrationOptions{});
  if (r.exit_code != ExitCode::kOk) throw std::runtime_error("vstcal::Calibrate: " + r.message);
  const Camera& cam = r.camera.camera;
  const Eigen::Matrix3d K = cam.K();
  const auto d = cam.distortion();  // radial-tangential: k1, k2, p1, p2, k3
  return {K(0, 0), K(1, 1), K(0, 2), K(1, 2), d[0], d[1], d[2], d[3], r.camera.fit->overall.rms_px};
}

}  // namespace

int main(int argc, char** argv) {
  const std::string solver = argc > 1 ? argv[1] : "";
  if (argc < 3 || argc > 4 || (solver != "opencv" && solver != "vstcal")) {
    std::fprintf(stderr, "usage: peer_calibrate opencv|vstcal CORNERS.json [REPEAT]\n");
    return 2;
  }
  Correspondences c;
  int repeat = 5;
  try {
    c = ReadCorrespondences(argv[2]);
    if (argc == 4) repeat = std::stoi(argv[3]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "peer_calibrate: error: %s\n", e.what());
    return 2;
  }
  if (c.rig != Rig::kPlanarViews || repeat < 1) {
    std::fprintf(stderr, "peer_calibrate: error: %s: needs rig \"planar-views\" and REPEAT >= 1\n", argv[2]);
    return 2;
  }
  try {
    Solution s;
    std::vector<double> seconds;
    for (int i = 0; i < repeat; ++i) {
      const auto start = std::chrono::steady_clock::now();
      s = solver == "opencv" ? SolveOpenCv(c) : SolveVstcal(c);
      seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::nth_element(seconds.begin(), seconds.begin() + repeat / 2, seconds.end());
    std::printf(
        "{\"fx\": %.17g, \"fy\": %.17g, \"cx\": %.17g, \"cy\": %.17g, \"k1\": %.17g, \"k2\": %.17g, \"p1\": %.17g, "
        "\"p2\": %.17g, \"rms_px\": %.17g, \"solve_s\": %.6g, \"repeat\": %d, \"opencv_version\": \"%s\"}\n",
        s.fx, s.fy, s.cx, s.cy, s.k1, s.k2, s.p1, s.p2, s.rms_px, seconds[repeat / 2], repeat, CV_VERSION);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "peer_calibrate: error: %s: %s\n", argv[2], e.what());
    return 3;
  }
}
