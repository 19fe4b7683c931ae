// Chessboard detection speed (issue 9 item 8), on rendered 10×10-corner chessboards (the board
// mrgingham reads too) at 640×480 (squares ≈ 30 px) and 1280×720 (≈ 50 px), 8 views each with
// blur σ 0.8 px and noise σ 2:
//   BM_CaptureDetect          vstcal::DetectTarget, one image at a time, one core
//   BM_OpenCvFindChessboard   cv::findChessboardCorners alone, as DetectTarget calls it
//   BM_OpenCvFindAndSubPix    the same plus cv::cornerSubPix (a usual OpenCV pipeline)
//   BM_CaptureSteps           what DetectTarget adds to the finder, alone: orientation, point-
//                             symmetry refinement, edge blur, from the finder's corners (the
//                             overhead, timed without the finder's own noise)
//   BM_CaptureDetectFiles     DetectInFiles over 32 PNG files on disk: read, decode, detect,
//                             account, on 1 or 2 threads (real time: images per second)
//   BM_RenderView             the renderer, one 640×480 view with blur and noise
// OpenCV runs single-threaded in the per-image benchmarks (cv::setNumThreads(1)), as it does
// inside DetectInFiles, which parallelises over images instead.
#include <benchmark/benchmark.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <fstream>

#include "support/capture_scenes.h"
#include "vstcal/capture/chessboard_orientation.h"
#include "vstcal/capture/detect_run.h"
#include "vstcal/capture/detect_steps.h"
#include "vstcal/capture/target_drawing.h"
#include "vstcal/capture/target_pattern.h"

namespace {

using namespace vstcal;
namespace fs = std::filesystem;

Target Board() { return testing::SpeedTestBoard(); }

struct Set {
  std::vector<GrayImage> images;
};

const Set& Images(int width) {
  static std::map<int, Set> sets;
  Set& s = sets[width];
  if (s.images.empty()) s.images = testing::SpeedTestImages(width);
  return s;
}

cv::Mat AsMat(const GrayImage& g) { return cv::Mat(g.height, g.width, CV_8U, const_cast<uint8_t*>(g.pixels.data())); }

void BM_CaptureDetect(benchmark::State& state) {
  cv::setNumThreads(1);
  const Set& s = Images(static_cast<int>(state.range(0)));
  const Target t = Board();
  size_t k = 0, found = 0;
  for (auto _ : state) {
    const Detection d = DetectTarget(s.images[k++ % s.images.size()], t, DetectorOptions{});
    found += d.status == DetectionStatus::kFound;
  }
  if (found != k) state.SkipWithError("a view was not found");
  state.SetItemsProcessed(static_cast<int64_t>(k));
}

void BM_OpenCvFindChessboard(benchmark::State& state) {
  cv::setNumThreads(1);
  const Set& s = Images(static_cast<int>(state.range(0)));
  size_t k = 0, found = 0;
  std::vector<cv::Point2f> corners;
  for (auto _ : state) {
    found += cv::findChessboardCorners(AsMat(s.images[k++ % s.images.size()]), cv::Size(10, 10), corners,
                                       cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
  }
  if (found != k) state.SkipWithError("a view was not found");
  state.SetItemsProcessed(static_cast<int64_t>(k));
}

void BM_OpenCvFindAndSubPix(benchmark::State& state) {
  cv::setNumThreads(1);
  const Set& s = Images(static_cast<int>(state.range(0)));
  size_t k = 0;
  std::vector<cv::Point2f> corners;
  for (auto _ : state) {
    const cv::Mat gray = AsMat(s.images[k++ % s.images.size()]);
    if (cv::findChessboardCorners(gray, cv::Size(10, 10), corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
      cv::cornerSubPix(gray, corners, cv::Size(5, 5), cv::Size(-1, -1), cv::TermCriteria(3, 30, 0.01));
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(k));
}

void BM_CaptureSteps(benchmark::State& state) {
  const Set& s = Images(static_cast<int>(state.range(0)));
  const Target t = Board();
  std::vector<std::vector<Eigen::Vector2d>> grids;
  for (const GrayImage& image : s.images) {
    std::vector<cv::Point2f> corners;
    cv::findChessboardCorners(AsMat(image), cv::Size(10, 10), corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
    grids.emplace_back();
    for (const cv::Point2f& p : corners) grids.back().emplace_back(p.x, p.y);
  }
  size_t k = 0;
  for (auto _ : state) {
    const size_t i = k++ % s.images.size();
    const GridOrientation o = OrientChessboard(s.images[i], t, grids[i], false);
    std::vector<DetectedCorner> corners(grids[i].size());
    for (size_t id = 0; id < corners.size(); ++id) corners[id] = {static_cast<int>(id), grids[i][o.detected_index[id]]};
    RefineXCorners(s.images[i], t, CornerRefiner::kSymmetry, 0.4, &corners);
    benchmark::DoNotOptimize(MedianGridEdgeBlur(s.images[i], t, corners, 0.4));
  }
  state.SetItemsProcessed(static_cast<int64_t>(k));
}

// 32 PNGs (the 8 views, 4 times, as different files: the bytes differ by a pixel so that the
// duplicate check passes) in a temporary folder.
const std::vector<CaptureInput>& Files(int width) {
  static std::map<int, std::vector<CaptureInput>> files;
  std::vector<CaptureInput>& f = files[width];
  if (f.empty()) {
    const fs::path dir = fs::temp_directory_path() / ("vstcal-bench-capture-" + std::to_string(width));
    fs::create_directories(dir);
    const Set& s = Images(width);
    for (int k = 0; k < 32; ++k) {
      GrayImage image = s.images[k % s.images.size()];
      image.pixels[0] = static_cast<uint8_t>(k);
      const fs::path path = dir / ("view-" + std::to_string(k) + ".png");
      std::ofstream(path, std::ios::binary) << EncodePng(image);
      f.push_back({path.string(), path, std::nullopt});
    }
  }
  return f;
}

void BM_CaptureDetectFiles(benchmark::State& state) {
  const auto& files = Files(static_cast<int>(state.range(0)));
  DetectRequest request;
  request.target = Board();
  request.threads = static_cast<unsigned>(state.range(1));
  for (auto _ : state) {
    const CaptureResult r = DetectInFiles(files, request);
    if (r.correspondences.views.size() != files.size()) state.SkipWithError("a view was not found");
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * files.size()));
}

void BM_RenderView(benchmark::State& state) {
  const Camera camera = testing::DistortedCamera(640, 480, 600);
  const PixelCornerRays rays(camera);
  const Pattern pattern = TargetPattern(Board());
  const Rigid3d pose = testing::TestViewPose(camera, Board(), 30, 0, 9);
  RenderOptions options;
  options.blur_px = 0.8;
  options.noise = 2;
  for (auto _ : state) benchmark::DoNotOptimize(RenderView(rays, pattern, pose, options, 0));
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_CaptureDetect)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvFindChessboard)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvFindAndSubPix)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CaptureSteps)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CaptureDetectFiles)->Args({640, 1})->Args({640, 2})->Args({1280, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderView)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
