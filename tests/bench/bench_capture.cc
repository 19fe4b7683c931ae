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
// Bounded time per image (issue 25 item 3), each image once (Iterations = the set's size), with
// the tail per image as counters (p99_s, max_s: thread CPU seconds) beside the mean:
//   BM_CaptureDetectHard      DetectTarget on 60 hard views (30 of a 9×6 board, 30 of the 10×10):
//                             tilted 45°–60° (HardViewPose), squares 12–41 px, blur σ 0–1.5 px,
//                             noise σ 0–3, lighting falling by 0–60 %; found, wrong ids, RMS
//   BM_OpenCvHardClassicThenSB  the peer on the same views: cv::findChessboardCorners (adaptive
//                             threshold), then findChessboardCornersSB where it fails — what
//                             DetectTarget ran before the bound, and what OpenCV users run —
//                             with vstcal's steps after it (untimed) for the former accuracy;
//                             at 1280×720 it takes minutes (views of 20–50 s each)
//   BM_CaptureBoardless       DetectTarget on images without a board: uniform noise 640×480,
//                             blurred noise 12 MP, one grey 12 MP, one grey 100 MP
//   BM_OpenCvBoardless        cv::findChessboardCorners on the board-less images it finishes in
//                             minutes (noise 640×480, one grey 12 MP); 12 MP blurred noise took
//                             it 84 s (issue 25)
//   BM_CaptureDetect12MP      DetectTarget on a 4000×3000 view of the board (squares ≈ 150 px)
//   BM_CaptureDetect12MPMarkers  the same for a ChArUco board (0), Kalibr's aprilgrid (1) and an
//                             AprilTag grid (2): found, corners, RMS against the truth
//   BM_OpenCvDetectMarkers12MP   OpenCV's detectMarkers on the whole 12 MP view (0, 1): what
//                             the ChArUco and aprilgrid detectors ran before the bound
//   BM_CaptureDetectHardMarkers  DetectTarget on 30 hard views of marker board 0 (ChArUco) or 1
//                             (Kalibr's aprilgrid) at 640×480 or 1280×720: tilted 45°–60°, squares
//                             (tags) 20–49 px, blur, noise, lighting as the chessboard's; found,
//                             wrong ids, RMS, corners of the visible ones, and the tail per image
//   BM_OpenCvHardMarkers      OpenCV's detectMarkers on the same views, whole image (the peer)
//   BM_CaptureBoardlessMarkers   DetectTarget for marker board 0–2 on board-less image 0–3
//   BM_OpenCvBoardlessMarkers    detectMarkers on the whole board-less 12 MP images (1, 2)
// OpenCV runs single-threaded in the per-image benchmarks (cv::setNumThreads(1)), as it does
// inside DetectInFiles, which parallelises over images instead.
#include <benchmark/benchmark.h>

#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include <time.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

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

// Thread CPU seconds of f().
double CpuSeconds(const std::function<void()>& f) {
  timespec a{}, b{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &a);
  f();
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &b);
  return static_cast<double>(b.tv_sec - a.tv_sec) + 1e-9 * static_cast<double>(b.tv_nsec - a.tv_nsec);
}

// The tail of per-image times as counters: mean, p99 (nearest rank) and max, CPU seconds.
void ReportTail(benchmark::State& state, std::vector<double> seconds) {
  if (seconds.empty()) return;
  std::sort(seconds.begin(), seconds.end());
  double sum = 0;
  for (const double t : seconds) sum += t;
  const size_t rank = static_cast<size_t>(std::ceil(0.99 * static_cast<double>(seconds.size())));
  state.counters["mean_s"] = sum / static_cast<double>(seconds.size());
  state.counters["p99_s"] = seconds[std::max<size_t>(rank, 1) - 1];
  state.counters["max_s"] = seconds.back();
  state.counters["images"] = static_cast<double>(seconds.size());
}

struct HardView {
  Target board;
  testing::RenderedView view;
};

// Hard view k's rendering: blur σ 0–1.5 px, noise σ 0–3, light falling by 0–60 % from a turning direction.
RenderOptions HardViewRendering(int k) {
  RenderOptions o;
  o.blur_px = 0.3 * (k % 6);
  o.noise = k % 4;
  o.lighting = 0.2 * (k % 4);
  o.lighting_direction_deg = 37 * k;
  o.seed = static_cast<uint64_t>(k + 1);
  return o;
}

// 60 hard views at 640×480 (f 600) or 1280×720 (f 1000): 30 of the 9×6 board, 30 of the 10×10.
const std::vector<HardView>& HardViews(int width) {
  static std::map<int, std::vector<HardView>> sets;
  std::vector<HardView>& s = sets[width];
  if (s.empty()) {
    const bool vga = width == 640;
    const Camera camera = testing::DistortedCamera(width, vga ? 480 : 720, vga ? 600 : 1000);
    for (int tb = 0; tb < 2; ++tb) {
      const Target board = tb == 0 ? testing::Chessboard9x6() : Board();
      for (int k = 0; k < 30; ++k) {
        const double square_px = 12 + (k * 7) % 30;
        const Rigid3d pose = testing::HardViewPose(camera, board, square_px, k, static_cast<uint64_t>(11 + tb + (vga ? 0 : 2)));
        s.push_back({board, testing::RenderTestView(camera, board, pose, HardViewRendering(k), static_cast<uint32_t>(k))});
      }
    }
  }
  return s;
}

// Found views, wrong ids and the corner RMS against the truth, as counters.
struct Accuracy {
  size_t found = 0, wrong = 0, matched = 0;
  double sum2 = 0;
  void Add(const Detection& d, const testing::RenderedView& view) {
    if (d.status != DetectionStatus::kFound) return;
    ++found;
    const testing::CornerErrors e = testing::CompareWithTruth(d, view);
    wrong += static_cast<size_t>(e.wrong_id);
    sum2 += e.rms_px * e.rms_px * e.matched;
    matched += static_cast<size_t>(e.matched);
  }
  void Report(benchmark::State& state) const {
    state.counters["found"] = static_cast<double>(found);
    state.counters["wrong_ids"] = static_cast<double>(wrong);
    state.counters["rms_px"] = matched > 0 ? std::sqrt(sum2 / static_cast<double>(matched)) : 0.0;
  }
};

void BM_CaptureDetectHard(benchmark::State& state) {
  cv::setNumThreads(1);
  const std::vector<HardView>& views = HardViews(static_cast<int>(state.range(0)));
  size_t k = 0;
  Accuracy accuracy;
  std::vector<double> seconds;
  for (auto _ : state) {
    const HardView& h = views[k++ % views.size()];
    Detection d;
    seconds.push_back(CpuSeconds([&] { d = DetectTarget(h.view.image, h.board, DetectorOptions{}); }));
    accuracy.Add(d, h.view);
  }
  accuracy.Report(state);
  ReportTail(state, seconds);
}

// The peer's finders timed; vstcal's steps (orientation, refinement, blur: ≈ 0.25 ms) then run
// untimed on their corners, for the accuracy of the pipeline DetectTarget was before the bound.
void BM_OpenCvHardClassicThenSB(benchmark::State& state) {
  cv::setNumThreads(1);
  const std::vector<HardView>& views = HardViews(static_cast<int>(state.range(0)));
  size_t k = 0;
  Accuracy accuracy;
  std::vector<double> seconds;
  std::vector<cv::Point2f> corners;
  for (auto _ : state) {
    const HardView& h = views[k++ % views.size()];
    const cv::Mat gray = AsMat(h.view.image);
    const cv::Size size(h.board.cols, h.board.rows);
    bool ok = false;
    seconds.push_back(CpuSeconds([&] {
      ok = cv::findChessboardCorners(gray, size, corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE) ||
           cv::findChessboardCornersSB(gray, size, corners, cv::CALIB_CB_NORMALIZE_IMAGE);
    }));
    if (!ok) continue;
    std::vector<Eigen::Vector2d> grid;
    for (const cv::Point2f& p : corners) grid.emplace_back(p.x, p.y);
    const GridOrientation o = OrientChessboard(h.view.image, h.board, grid, false);
    if (!o.problem.empty()) continue;
    Detection d;
    d.corners.resize(grid.size());
    for (size_t id = 0; id < grid.size(); ++id) d.corners[id] = {static_cast<int>(id), grid[o.detected_index[id]]};
    RefineXCorners(h.view.image, h.board, CornerRefiner::kSymmetry, 0.4, &d.corners);
    d.blur_px = MedianGridEdgeBlur(h.view.image, h.board, d.corners, 0.4);
    d.status = DetectionStatus::kFound;
    Conclude(DetectorOptions{}, &d);
    accuracy.Add(d, h.view);
  }
  accuracy.Report(state);
  ReportTail(state, seconds);
}

// Board-less images: 0 uniform noise 640×480, 1 blurred noise (σ 2 px) 4000×3000, 2 one grey
// 4000×3000, 3 one grey 10000×10000 (the largest image calib-capture reads).
GrayImage Boardless(int which) {
  const int w = which == 0 ? 640 : which == 3 ? 10000 : 4000, h = which == 0 ? 480 : which == 3 ? 10000 : 3000;
  GrayImage image(w, h, 128);
  if (which <= 1) {
    cv::Mat m = AsMat(image);
    cv::setRNGSeed(7);
    cv::randu(m, 0, 256);
    if (which == 1) cv::GaussianBlur(m, m, cv::Size(0, 0), 2);
  }
  return image;
}

void BM_CaptureBoardless(benchmark::State& state) {
  cv::setNumThreads(1);
  const GrayImage image = Boardless(static_cast<int>(state.range(0)));
  size_t found = 0;
  std::vector<double> seconds;
  for (auto _ : state) {
    Detection d;
    seconds.push_back(CpuSeconds([&] { d = DetectTarget(image, Board(), DetectorOptions{}); }));
    found += d.status != DetectionStatus::kNotFound;
  }
  if (found != 0) state.SkipWithError("a board was found in a board-less image");
  ReportTail(state, seconds);
}

void BM_OpenCvBoardless(benchmark::State& state) {
  cv::setNumThreads(1);
  const GrayImage image = Boardless(static_cast<int>(state.range(0)));
  std::vector<cv::Point2f> corners;
  std::vector<double> seconds;
  for (auto _ : state) {
    seconds.push_back(CpuSeconds([&] {
      cv::findChessboardCorners(AsMat(image), cv::Size(10, 10), corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
    }));
  }
  ReportTail(state, seconds);
}

void BM_CaptureDetect12MP(benchmark::State& state) {
  cv::setNumThreads(1);
  static const testing::RenderedView view = [] {
    const Camera camera = testing::DistortedCamera(4000, 3000, 3000);
    RenderOptions o;
    o.blur_px = 1.5;
    o.noise = 2;
    return testing::RenderTestView(camera, Board(), testing::TestViewPose(camera, Board(), 150, 3, 9), o, 3);
  }();
  std::vector<double> seconds;
  double rms = 0;
  for (auto _ : state) {
    Detection d;
    seconds.push_back(CpuSeconds([&] { d = DetectTarget(view.image, Board(), DetectorOptions{}); }));
    if (d.status != DetectionStatus::kFound) state.SkipWithError("the 12 MP view was not found");
    rms = testing::CompareWithTruth(d, view).rms_px;
  }
  state.counters["rms_px"] = rms;
  ReportTail(state, seconds);
}

// Marker boards (issue 25: bounded time for ChArUco and tag grids as for the chessboard): 0 the
// 7×5 ChArUco board (DICT_5X5_100), 1 a 6×4 Kalibr aprilgrid, 2 the 6×4 tag36h11 AprilTag grid.
Target MarkerBoard(int which) {
  if (which == 0) return testing::Charuco7x5();
  if (which == 2) return testing::AprilGrid6x4();
  return testing::KalibrAprilGrid6x4();
}

// A 4000×3000 view of marker board `which` (squares or tags ≈ 150 px, blur σ 1.5 px, noise σ 2).
const testing::RenderedView& MarkerView12MP(int which) {
  static std::map<int, testing::RenderedView> views;
  auto it = views.find(which);
  if (it == views.end()) {
    const Camera camera = testing::DistortedCamera(4000, 3000, 3000);
    const Target t = MarkerBoard(which);
    RenderOptions o;
    o.blur_px = 1.5;
    o.noise = 2;
    it = views.emplace(which, testing::RenderTestView(camera, t, testing::TestViewPose(camera, t, 150, 3, 9), o, 3)).first;
  }
  return it->second;
}

void BM_CaptureDetect12MPMarkers(benchmark::State& state) {
  cv::setNumThreads(1);
  const int which = static_cast<int>(state.range(0));
  const Target t = MarkerBoard(which);
  const testing::RenderedView& view = MarkerView12MP(which);
  std::vector<double> seconds;
  testing::CornerErrors e;
  for (auto _ : state) {
    Detection d;
    seconds.push_back(CpuSeconds([&] { d = DetectTarget(view.image, t, DetectorOptions{}); }));
    if (d.status != DetectionStatus::kFound) state.SkipWithError(("the 12 MP view was not found: " + d.reason).c_str());
    e = testing::CompareWithTruth(d, view);
  }
  state.counters["rms_px"] = e.rms_px;
  state.counters["corners"] = e.matched;
  state.counters["of"] = static_cast<double>(view.truth.size());
  state.counters["wrong_ids"] = e.wrong_id;
  ReportTail(state, seconds);
}

// The peer: OpenCV's detectMarkers on the whole 12 MP image (DetectTarget's first step before the
// bound; 0 ChArUco's dictionary, 1 the aprilgrid's tag36h11 with its two-cell border).
void BM_OpenCvDetectMarkers12MP(benchmark::State& state) {
  cv::setNumThreads(1);
  const int which = static_cast<int>(state.range(0));
  const cv::Mat gray = AsMat(MarkerView12MP(which).image);
  const cv::Ptr<cv::aruco::DetectorParameters> params = cv::aruco::DetectorParameters::create();
  params->markerBorderBits = which == 0 ? 1 : 2;
  const cv::Ptr<cv::aruco::Dictionary> dictionary =
      cv::aruco::getPredefinedDictionary(which == 0 ? cv::aruco::DICT_5X5_100 : cv::aruco::DICT_APRILTAG_36h11);
  std::vector<double> seconds;
  size_t markers = 0;
  for (auto _ : state) {
    std::vector<std::vector<cv::Point2f>> corners;
    std::vector<int> ids;
    seconds.push_back(CpuSeconds([&] { cv::aruco::detectMarkers(gray, dictionary, corners, ids, params); }));
    markers = ids.size();
  }
  state.counters["markers"] = static_cast<double>(markers);
  ReportTail(state, seconds);
}

// DetectTarget for marker board range(0) on board-less image range(1) (Boardless).
void BM_CaptureBoardlessMarkers(benchmark::State& state) {
  cv::setNumThreads(1);
  const GrayImage image = Boardless(static_cast<int>(state.range(1)));
  const Target t = MarkerBoard(static_cast<int>(state.range(0)));
  size_t found = 0;
  std::vector<double> seconds;
  for (auto _ : state) {
    Detection d;
    seconds.push_back(CpuSeconds([&] { d = DetectTarget(image, t, DetectorOptions{}); }));
    found += d.status != DetectionStatus::kNotFound;
  }
  if (found != 0) state.SkipWithError("a board was found in a board-less image");
  ReportTail(state, seconds);
}

// The peer on the 12 MP board-less images: detectMarkers on the whole image (0 ChArUco's, 1 the aprilgrid's).
void BM_OpenCvBoardlessMarkers(benchmark::State& state) {
  cv::setNumThreads(1);
  const GrayImage image = Boardless(static_cast<int>(state.range(1)));
  const int which = static_cast<int>(state.range(0));
  const cv::Ptr<cv::aruco::DetectorParameters> params = cv::aruco::DetectorParameters::create();
  params->markerBorderBits = which == 0 ? 1 : 2;
  const cv::Ptr<cv::aruco::Dictionary> dictionary =
      cv::aruco::getPredefinedDictionary(which == 0 ? cv::aruco::DICT_5X5_100 : cv::aruco::DICT_APRILTAG_36h11);
  std::vector<double> seconds;
  for (auto _ : state) {
    std::vector<std::vector<cv::Point2f>> corners;
    std::vector<int> ids;
    seconds.push_back(CpuSeconds([&] { cv::aruco::detectMarkers(AsMat(image), dictionary, corners, ids, params); }));
  }
  ReportTail(state, seconds);
}

// Hard views of the marker boards (issue 25 item 3), as HardViews for the chessboard: 30 views a
// board and size, tilted 45°–60°, squares (tags) 20–49 px — a marker needs about 2 px a cell, so the
// range starts higher than the chessboard's 12 px — blur σ 0–1.5 px, noise σ 0–3, light falling by
// 0–60 %. Board `which`: MarkerBoard (0 ChArUco, 1 Kalibr's aprilgrid, 2 the AprilTag grid).
const std::vector<testing::RenderedView>& HardMarkerViews(int which, int width) {
  static std::map<std::pair<int, int>, std::vector<testing::RenderedView>> sets;
  std::vector<testing::RenderedView>& s = sets[{which, width}];
  if (s.empty()) {
    const bool vga = width == 640;
    const Camera camera = testing::DistortedCamera(width, vga ? 480 : 720, vga ? 600 : 1000);
    const Target board = MarkerBoard(which);
    for (int k = 0; k < 30; ++k) {
      const double square_px = 20 + (k * 7) % 30;
      const Rigid3d pose = testing::HardViewPose(camera, board, square_px, k, static_cast<uint64_t>(21 + which + (vga ? 0 : 4)));
      s.push_back(testing::RenderTestView(camera, board, pose, HardViewRendering(k), static_cast<uint32_t>(k)));
    }
  }
  return s;
}

// DetectTarget on the hard views of marker board range(0) at width range(1): found views (≥ 6
// corners), wrong ids, corner RMS, and the tail per image.
void BM_CaptureDetectHardMarkers(benchmark::State& state) {
  cv::setNumThreads(1);
  const int which = static_cast<int>(state.range(0));
  const std::vector<testing::RenderedView>& views = HardMarkerViews(which, static_cast<int>(state.range(1)));
  const Target t = MarkerBoard(which);
  size_t k = 0, corners = 0, truth = 0;
  Accuracy accuracy;
  std::vector<double> seconds;
  for (auto _ : state) {
    const testing::RenderedView& view = views[k++ % views.size()];
    Detection d;
    seconds.push_back(CpuSeconds([&] { d = DetectTarget(view.image, t, DetectorOptions{}); }));
    accuracy.Add(d, view);
    if (d.status == DetectionStatus::kFound) corners += d.corners.size();
    truth += view.truth.size();
  }
  accuracy.Report(state);
  state.counters["corners"] = static_cast<double>(corners);
  state.counters["of"] = static_cast<double>(truth);
  ReportTail(state, seconds);
}

// The peer on the same views: OpenCV's detectMarkers on the whole image (0 ChArUco's dictionary,
// 1 the aprilgrid's tag36h11 with its two-cell border), the step DetectTarget bounds.
void BM_OpenCvHardMarkers(benchmark::State& state) {
  cv::setNumThreads(1);
  const int which = static_cast<int>(state.range(0));
  const std::vector<testing::RenderedView>& views = HardMarkerViews(which, static_cast<int>(state.range(1)));
  const cv::Ptr<cv::aruco::DetectorParameters> params = cv::aruco::DetectorParameters::create();
  params->markerBorderBits = which == 0 ? 1 : 2;
  const cv::Ptr<cv::aruco::Dictionary> dictionary =
      cv::aruco::getPredefinedDictionary(which == 0 ? cv::aruco::DICT_5X5_100 : cv::aruco::DICT_APRILTAG_36h11);
  size_t k = 0, markers = 0;
  std::vector<double> seconds;
  for (auto _ : state) {
    const cv::Mat gray = AsMat(views[k++ % views.size()].image);
    std::vector<std::vector<cv::Point2f>> corners;
    std::vector<int> ids;
    seconds.push_back(CpuSeconds([&] { cv::aruco::detectMarkers(gray, dictionary, corners, ids, params); }));
    markers += ids.size();
  }
  state.counters["markers"] = static_cast<double>(markers);
  ReportTail(state, seconds);
}

BENCHMARK(BM_CaptureDetect)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvFindChessboard)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvFindAndSubPix)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CaptureSteps)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CaptureDetectFiles)->Args({640, 1})->Args({640, 2})->Args({1280, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderView)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CaptureDetectHard)->Arg(640)->Arg(1280)->Iterations(60)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvHardClassicThenSB)->Arg(640)->Arg(1280)->Iterations(60)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CaptureBoardless)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Iterations(3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvBoardless)->Arg(0)->Arg(2)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CaptureDetect12MP)->Iterations(3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CaptureDetect12MPMarkers)->Arg(0)->Arg(1)->Arg(2)->Iterations(5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvDetectMarkers12MP)->Arg(0)->Arg(1)->Iterations(3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CaptureBoardlessMarkers)
    ->ArgsProduct({{0, 1, 2}, {0, 1, 2, 3}})
    ->Iterations(5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CaptureDetectHardMarkers)->ArgsProduct({{0, 1}, {640, 1280}})->Iterations(30)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvHardMarkers)->ArgsProduct({{0, 1}, {640, 1280}})->Iterations(30)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvBoardlessMarkers)->ArgsProduct({{0, 1}, {1, 2}})->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
