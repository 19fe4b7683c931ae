// peer_corners: the corner detectors of scripts/compare-detectors, on the same images, in process.
//
//   peer_corners render DIR    renders the comparison set: a 10×10-corner chessboard (mrgingham
//                              finds N×N grids only) of 25 mm squares seen by a 1280×1024 pinhole
//                              camera (f 1400) at squares of 12, 20, 30, 45 and 60 px, clean, with
//                              blur σ 1 px and with noise σ 2 grey levels; 10 views per condition
//                              (tilts up to 35°, any roll), DIR/<condition>/view-XX.png plus
//                              DIR/<condition>/truth.json ({"view-00.png": [[u, v] per corner]}).
//   peer_corners detect DIR    runs every in-process detector on every image and prints one JSON
//                              line per image and detector: {"condition", "image", "detector",
//                              "corners": [[u, v], …] or null, "seconds"}.
//   peer_corners speedset DIR  writes bench_capture's images as PNG files for scripts/bench-capture:
//                              DIR/640/view-NN.png and DIR/1280/view-NN.png, 32 each (the 8 views
//                              four times, a pixel changed so that no two files are identical).
//   peer_corners markers       ChArUco (7×5, 40 px squares) and AprilTag-grid (6×4, 40 px tags)
//                              views, 10 each, blur σ 0.7 and noise σ 2, 640×480: the RMS and mean
//                              error of OpenCV's interpolated ChArUco corners as they come, of
//                              vstcal's (refined), and of libapriltag's tag corners.
//   peer_corners real          calibrates OpenCV's stereo sample (opencv-doc) from each detector's
//                              corners with the same solver and prints the reprojection RMS.
// Detectors: vstcal (DetectTarget's defaults: classic finder, the sector-based one where it fails,
// point-symmetry refinement); OpenCV classic + cornerSubPix with the tutorial's 11 × 11 half-size
// window ("opencv-classic-subpix11") and with a window fitted to the squares, half-size 0.4 × the
// square ("opencv-classic-subpix-fit"); findChessboardCornersSB plain and with CALIB_CB_ACCURACY.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "support/capture_scenes.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/image/image_io.h"
#include "vstcal/capture/target_drawing.h"
#include "vstcal/formats/capture/target_io.h"

namespace {

namespace fs = std::filesystem;
using namespace vstcal;

constexpr int kViews = 10;
const double kSquares[] = {12, 20, 30, 45, 60};

Target Board10() {
  Target t = testing::Chessboard9x6();
  t.rows = t.cols = 10;
  return t;
}

struct Condition {
  std::string name;
  double square_px, blur, noise;
};
std::vector<Condition> Conditions() {
  std::vector<Condition> out;
  for (const double s : kSquares) {
    const std::string px = std::to_string(static_cast<int>(s));
    out.push_back({"sq" + px + "-clean", s, 0, 0});
    out.push_back({"sq" + px + "-blur1", s, 1, 0});
    out.push_back({"sq" + px + "-noise2", s, 0, 2});
  }
  return out;
}

using Finder = std::function<std::vector<cv::Point2f>(const cv::Mat& gray, double square_px)>;

std::vector<cv::Point2f> Classic(const cv::Mat& gray) {
  std::vector<cv::Point2f> p;
  if (!cv::findChessboardCorners(gray, cv::Size(10, 10), p, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) p.clear();
  return p;
}

std::vector<std::pair<std::string, Finder>> Detectors(const Target& target) {
  return {
      {"vstcal",
       [target](const cv::Mat& gray, double) {
         GrayImage image(gray.cols, gray.rows);
         std::memcpy(image.pixels.data(), gray.data, image.pixels.size());
         const Detection d = DetectTarget(image, target, DetectorOptions{});
         std::vector<cv::Point2f> p;
         if (d.status == DetectionStatus::kFound) {
           for (const auto& c : d.corners) p.emplace_back(static_cast<float>(c.pixel.x()), static_cast<float>(c.pixel.y()));
         }
         return p;
       }},
      {"opencv-classic-subpix11",
       [](const cv::Mat& gray, double) {
         std::vector<cv::Point2f> p = Classic(gray);
         if (!p.empty()) cv::cornerSubPix(gray, p, cv::Size(11, 11), cv::Size(-1, -1), cv::TermCriteria(3, 30, 0.001));
         return p;
       }},
      {"opencv-classic-subpix-fit",
       [](const cv::Mat& gray, double square_px) {
         std::vector<cv::Point2f> p = Classic(gray);
         const int half = std::clamp(static_cast<int>(std::lround(0.4 * square_px)), 2, 10);
         if (!p.empty()) cv::cornerSubPix(gray, p, cv::Size(half, half), cv::Size(-1, -1), cv::TermCriteria(3, 40, 0.001));
         return p;
       }},
      {"opencv-sb",
       [](const cv::Mat& gray, double) {
         std::vector<cv::Point2f> p;
         if (!cv::findChessboardCornersSB(gray, cv::Size(10, 10), p, cv::CALIB_CB_NORMALIZE_IMAGE)) p.clear();
         return p;
       }},
      {"opencv-sb-accuracy",
       [](const cv::Mat& gray, double) {
         std::vector<cv::Point2f> p;
         if (!cv::findChessboardCornersSB(gray, cv::Size(10, 10), p, cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_ACCURACY)) p.clear();
         return p;
       }},
  };
}

int Render(const fs::path& dir) {
  const Target t = Board10();
  const Camera camera = testing::PinholeCamera(1280, 1024, 1400);
  for (const Condition& c : Conditions()) {
    fs::create_directories(dir / c.name);
    nlohmann::json truth = nlohmann::json::object();
    for (int k = 0; k < kViews; ++k) {
      RenderOptions options;
      options.blur_px = c.blur;
      options.noise = c.noise;
      options.seed = 1000 + k;
      const testing::RenderedView view =
          testing::RenderTestView(camera, t, testing::TestViewPose(camera, t, c.square_px, k, 77, 360.0 * k / kViews), options, k);
      char name[32];
      std::snprintf(name, sizeof name, "view-%02d.png", k);
      std::ofstream(dir / c.name / name, std::ios::binary) << EncodePng(view.image);
      nlohmann::json corners = nlohmann::json::array();
      for (const auto& [id, px] : view.truth) corners.push_back({px.x(), px.y()});
      truth[name] = corners;
    }
    std::ofstream(dir / c.name / "truth.json") << truth.dump() << "\n";
  }
  return 0;
}

int Markers() {
  const Camera camera = testing::DistortedCamera(640, 480, 600);
  RenderOptions options;
  options.blur_px = 0.7;
  options.noise = 2;
  struct Row {
    const char* name;
    Target target;
    CornerRefiner refiner;
  };
  for (const Row& row : {Row{"charuco, OpenCV's corners", testing::Charuco7x5(), CornerRefiner::kNone},
                         Row{"charuco, vstcal", testing::Charuco7x5(), CornerRefiner::kSymmetry},
                         Row{"apriltag-grid, libapriltag", testing::AprilGrid6x4(), CornerRefiner::kSymmetry}}) {
    DetectorOptions detector;
    detector.refiner = row.refiner;
    double sum2 = 0;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    int n = 0, found = 0;
    for (int k = 0; k < 10; ++k) {
      const testing::RenderedView view =
          testing::RenderTestView(camera, row.target, testing::TestViewPose(camera, row.target, 40, k, 21), options, k);
      const Detection d = DetectTarget(view.image, row.target, detector);
      if (d.status != DetectionStatus::kFound) continue;
      ++found;
      for (const DetectedCorner& c : d.corners) {
        const Eigen::Vector2d e = c.pixel - view.truth.at(c.id);
        sum2 += e.squaredNorm();
        mean += e;
        ++n;
      }
    }
    std::printf("%s\n", nlohmann::json{{"detector", row.name}, {"found", found}, {"corners", n}, {"rms_px", n ? std::sqrt(sum2 / n) : -1.0},
                                       {"mean_px", {n ? mean.x() / n : 0.0, n ? mean.y() / n : 0.0}}}
                            .dump()
                            .c_str());
  }
  return 0;
}

int SpeedSet(const fs::path& dir) {
  for (const int width : {640, 1280}) {
    fs::create_directories(dir / std::to_string(width));
    const std::vector<GrayImage> images = testing::SpeedTestImages(width);
    for (int k = 0; k < 32; ++k) {
      GrayImage image = images[k % images.size()];
      image.pixels[0] = static_cast<uint8_t>(k);
      char name[32];
      std::snprintf(name, sizeof name, "view-%02d.png", k);
      std::ofstream(dir / std::to_string(width) / name, std::ios::binary) << EncodePng(image);
    }
  }
  std::ofstream(dir / "board.target.json") << DumpJson(TargetToJson(testing::SpeedTestBoard(), Provenance{"peer_corners", {}, std::nullopt}));
  return 0;
}

int Detect(const fs::path& dir) {
  const Target t = Board10();
  cv::setNumThreads(1);  // one core each, as mrgingham --jobs 1
  for (const Condition& c : Conditions()) {
    for (int k = 0; k < kViews; ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "view-%02d.png", k);
      const LoadedImage loaded = LoadImageFile(dir / c.name / name);
      if (!loaded.problem.empty()) throw std::runtime_error(loaded.problem);
      const cv::Mat gray(loaded.image.height, loaded.image.width, CV_8U, const_cast<uint8_t*>(loaded.image.pixels.data()));
      for (const auto& [detector, find] : Detectors(t)) {
        const auto start = std::chrono::steady_clock::now();
        const std::vector<cv::Point2f> p = find(gray, c.square_px);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        nlohmann::json corners = nullptr;
        if (!p.empty()) {
          corners = nlohmann::json::array();
          for (const cv::Point2f& q : p) corners.push_back({q.x, q.y});
        }
        std::printf("%s\n", nlohmann::json{{"condition", c.name}, {"image", name}, {"detector", detector}, {"corners", corners}, {"seconds", seconds}}
                                .dump()
                                .c_str());
      }
    }
  }
  return 0;
}

// OpenCV's stereo sample: each detector's corners (numbered by vstcal's nearest corner) calibrated
// by the same solver (vstcal::Calibrate, k1, k2, p1, p2): the reprojection RMS says how
// consistent each detector's corners are where no truth is known.
int Real() {
  const Target t = testing::Chessboard9x6();
  for (const std::string side : {"left", "right"}) {
    std::map<std::string, Correspondences> sets;
    for (const int i : {1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14}) {
      char path[128];
      std::snprintf(path, sizeof path, "/usr/share/doc/opencv-doc/examples/data/%s%02d.jpg", side.c_str(), i);
      const LoadedImage loaded = LoadImageFile(path);
      if (!loaded.problem.empty()) throw std::runtime_error(std::string(path) + ": " + loaded.problem);
      const Detection ours = DetectTarget(loaded.image, t, DetectorOptions{});
      const cv::Mat gray(loaded.image.height, loaded.image.width, CV_8U, const_cast<uint8_t*>(loaded.image.pixels.data()));
      for (const auto& [detector, find] : Detectors(t)) {
        std::vector<cv::Point2f> p;
        if (detector == "vstcal") {
          for (const auto& c : ours.corners) p.emplace_back(static_cast<float>(c.pixel.x()), static_cast<float>(c.pixel.y()));
        } else {
          const std::string sized = detector;  // the 9×6 board: the finders are rebuilt for its size
          std::vector<cv::Point2f> q;
          const bool sb = sized.rfind("opencv-sb", 0) == 0;
          const bool found = sb ? cv::findChessboardCornersSB(gray, cv::Size(9, 6), q,
                                                              cv::CALIB_CB_NORMALIZE_IMAGE | (sized == "opencv-sb-accuracy" ? cv::CALIB_CB_ACCURACY : 0))
                                : cv::findChessboardCorners(gray, cv::Size(9, 6), q, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
          if (!found) continue;
          if (sized == "opencv-classic-subpix11") cv::cornerSubPix(gray, q, cv::Size(11, 11), cv::Size(-1, -1), cv::TermCriteria(3, 30, 0.001));
          if (sized == "opencv-classic-subpix-fit") cv::cornerSubPix(gray, q, cv::Size(5, 5), cv::Size(-1, -1), cv::TermCriteria(3, 40, 0.001));
          p = q;
        }
        Correspondences& c = sets[detector];
        c.image_size = {640, 480};
        c.rig = Rig::kPlanarViews;
        View v{std::to_string(i), "", std::nullopt, {}};
        for (const auto& corner : ours.corners) {
          const Eigen::Vector2d xy = CornerPosition(t, corner.id);
          const auto nearest = *std::min_element(p.begin(), p.end(), [&](const cv::Point2f& a, const cv::Point2f& b) {
            return (Eigen::Vector2d(a.x, a.y) - corner.pixel).norm() < (Eigen::Vector2d(b.x, b.y) - corner.pixel).norm();
          });
          v.observations.push_back({Eigen::Vector3d(xy.x(), xy.y(), 0), Eigen::Vector2d(nearest.x, nearest.y)});
        }
        c.views.push_back(std::move(v));
      }
    }
    for (const auto& [detector, c] : sets) {
      const CalibrationResult r = Calibrate(c, CalibrationOptions{});
      std::printf("%s\n", nlohmann::json{{"side", side}, {"detector", detector}, {"views", c.views.size()},
                                         {"rms_px", r.camera.fit ? r.camera.fit->overall.rms_px : -1.0},
                                         {"fx", r.camera.camera.params[0]}, {"fy", r.camera.camera.params[1]}}
                              .dump()
                              .c_str());
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "render" && argc == 3) return Render(argv[2]);
    if (mode == "detect" && argc == 3) return Detect(argv[2]);
    if (mode == "real" && argc == 2) return Real();
    if (mode == "speedset" && argc == 3) return SpeedSet(argv[2]);
    if (mode == "markers" && argc == 2) return Markers();
    std::fprintf(stderr, "usage: peer_corners render DIR | detect DIR | real | markers | speedset DIR\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "peer_corners: %s\n", e.what());
    return 1;
  }
}
