// Bounded time per image (issue 25 item 3), checked for what it must not cost: views and accuracy.
// The hard views (tilted 45°–60°, blur, noise, falling light) that OpenCV's sector-based finder
// finds — the peer, run here on the same images — are found, every id right, as accurately as on
// easy views; a large image searched at a reduced size has its corners mapped back and refined at
// full resolution without bias; board-less images are not found; image sizes come from the
// headers (PNG and JPEG encoded by OpenCV here), so that mixed sizes are refused before any image
// is searched. The timings themselves are in tests/bench/bench_capture.cc (docs/performance.md).
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <tuple>

#include "support/capture_scenes.h"
#include "vstcal/capture/detect.h"
#include "vstcal/capture/detect_run.h"
#include "vstcal/core/error.h"
#include "vstcal/image/image_io.h"

namespace vstcal {
namespace {

namespace fs = std::filesystem;
using testing::CompareWithTruth;
using testing::CornerErrors;
using testing::RenderedView;

cv::Mat AsMat(const GrayImage& g) { return cv::Mat(g.height, g.width, CV_8U, const_cast<uint8_t*>(g.pixels.data())); }

TEST(BoundedDetection, HardViewsTheSectorBasedFinderFindsAreFound) {
  cv::setNumThreads(1);
  const Camera camera = testing::DistortedCamera(640, 480, 600);
  const Target t = testing::SpeedTestBoard();
  int peer_found = 0, ours_found = 0, wrong = 0;
  double sum2 = 0;
  int n = 0;
  for (int k = 0; k < 6; ++k) {
    RenderOptions o;
    o.blur_px = 0.3 * k;
    o.noise = k % 3;
    o.lighting = 0.15 * (k % 4);
    o.lighting_direction_deg = 37 * k;
    const RenderedView view = testing::RenderTestView(camera, t, testing::HardViewPose(camera, t, 18 + 4 * k, k, 12), o, k);
    std::vector<cv::Point2f> corners;
    const bool peer = cv::findChessboardCornersSB(AsMat(view.image), cv::Size(t.cols, t.rows), corners, cv::CALIB_CB_NORMALIZE_IMAGE);
    const Detection d = DetectTarget(view.image, t, DetectorOptions{});
    peer_found += peer;
    if (d.status != DetectionStatus::kFound) {
      EXPECT_FALSE(peer) << "view " << k << ": " << d.reason;
      continue;
    }
    ++ours_found;
    const CornerErrors e = CompareWithTruth(d, view);
    wrong += e.wrong_id;
    sum2 += e.rms_px * e.rms_px * e.matched;
    n += e.matched;
  }
  EXPECT_GE(ours_found, peer_found);
  EXPECT_GE(ours_found, 5);
  EXPECT_EQ(wrong, 0);
  EXPECT_LT(std::sqrt(sum2 / std::max(n, 1)), 0.05);
}

// 2400×1800 is searched at a third of its size (800×600): a corner found there at (x, y) is the
// full image's 3·(x, y) + 1. Without refinement the corners carry that mapping: a mapping of
// 3·(x, y) would put them 1 px up and left on average. Refined, they are as accurate as ever.
TEST(BoundedDetection, LargeImageCornersMapBackToFullResolution) {
  const Camera camera = testing::DistortedCamera(2400, 1800, 1800);
  const Target t = testing::Chessboard9x6();
  RenderOptions o;
  o.blur_px = 1.2;
  o.noise = 2;
  const RenderedView view = testing::RenderTestView(camera, t, testing::TestViewPose(camera, t, 90, 2, 3), o, 2);
  DetectorOptions raw;
  raw.refiner = CornerRefiner::kNone;
  const Detection unrefined = DetectTarget(view.image, t, raw);
  ASSERT_EQ(unrefined.status, DetectionStatus::kFound) << unrefined.reason;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const DetectedCorner& c : unrefined.corners) mean += c.pixel - view.truth.at(c.id);
  mean /= static_cast<double>(unrefined.corners.size());
  EXPECT_LT(mean.norm(), 0.35) << mean.transpose();

  const Detection refined = DetectTarget(view.image, t, DetectorOptions{});
  ASSERT_EQ(refined.status, DetectionStatus::kFound) << refined.reason;
  const CornerErrors e = CompareWithTruth(refined, view);
  EXPECT_EQ(e.wrong_id, 0);
  EXPECT_EQ(e.matched, t.rows * t.cols);
  EXPECT_LT(e.rms_px, 0.05);
}

// Marker boards in an image above 1 MP: the markers are found in the reduced search image (half
// of 1600×1200 here; Kalibr's aprilgrid is looked for there and read in the full image; the 12 MP case is bench_capture's BM_CaptureDetect12MPMarkers), the corners interpolated, fitted or refined at full resolution — as accurate as
// the same boards' corners at 640×480 (docs/experiments/corners.md: ChArUco and aprilgrid 0.013 px,
// libapriltag's tag corners 0.06 px). A ChArUco board, Kalibr's aprilgrid and an AprilTag grid, one
// view each, squares or tags of 90 px (45 px in the search image).
TEST(BoundedDetection, MarkerBoardsInLargeImagesAreFoundAtFullAccuracy) {
  const Camera camera = testing::DistortedCamera(1600, 1200, 1200);
  const Target charuco = testing::Charuco7x5(), aprilgrid = testing::KalibrAprilGrid6x4(), tag_grid = testing::AprilGrid6x4();
  for (const auto& [target, max_rms] : {std::pair{&charuco, 0.03}, {&aprilgrid, 0.03}, {&tag_grid, 0.12}}) {
    for (int k = 0; k < 1; ++k) {
      RenderOptions o;
      o.blur_px = 1.5;
      o.noise = 2;
      const RenderedView view = testing::RenderTestView(camera, *target, testing::TestViewPose(camera, *target, 90, k, 21), o, k);
      const Detection d = DetectTarget(view.image, *target, DetectorOptions{});
      ASSERT_EQ(d.status, DetectionStatus::kFound) << DescribeTarget(*target) << " view " << k << ": " << d.reason;
      const CornerErrors e = CompareWithTruth(d, view);
      EXPECT_EQ(e.wrong_id, 0) << DescribeTarget(*target);
      EXPECT_GE(e.matched, static_cast<int>(0.9 * static_cast<double>(view.truth.size()))) << DescribeTarget(*target) << " view " << k;
      EXPECT_LT(e.rms_px, max_rms) << DescribeTarget(*target) << " view " << k;
      std::printf("%s view %d: %d of %zu corners, RMS %.4f px\n", DescribeTarget(*target).c_str(), k, e.matched, view.truth.size(), e.rms_px);
    }
  }
}

// Kalibr's aprilgrid is searched at full resolution (MarkerSearch, aruco_tags.h): on this tilted
// 2400×1800 view the reduced search gave one corner, and at 4000×3000 seventeen corners a cell off
// their place, where the full image gives 92 of 96, none wrong.
TEST(BoundedDetection, KalibrsAprilgridKeepsItsCornersOnATiltedLargeView) {
  const Camera camera = testing::DistortedCamera(2400, 1800, 2256);
  const Target aprilgrid = testing::KalibrAprilGrid6x4();
  RenderOptions o;
  o.blur_px = 1.5;
  o.noise = 2;
  const RenderedView view = testing::RenderTestView(camera, aprilgrid, testing::TestViewPose(camera, aprilgrid, 90, 3, 9), o, 3);
  const Detection d = DetectTarget(view.image, aprilgrid, DetectorOptions{});
  ASSERT_EQ(d.status, DetectionStatus::kFound) << d.reason;
  const CornerErrors e = CompareWithTruth(d, view);
  EXPECT_EQ(e.wrong_id, 0);
  EXPECT_GE(e.matched, 86);  // 90 % of the 96
  EXPECT_LT(e.rms_px, 0.03);
}

TEST(BoundedDetection, BoardlessImagesAreNotFound) {
  GrayImage noise(640, 480);
  cv::Mat m = AsMat(noise);
  cv::setRNGSeed(5);
  cv::randu(m, 0, 256);
  const GrayImage grey(2400, 1800, 128);  // searched at a third, then at a sixth
  const GrayImage strip(150000, 9, 128);  // 1.35 MP, but too thin to reduce
  for (const GrayImage* image : std::initializer_list<const GrayImage*>{&noise, &grey, &strip}) {
    const Detection d = DetectTarget(*image, testing::SpeedTestBoard(), DetectorOptions{});
    EXPECT_EQ(d.status, DetectionStatus::kNotFound);
    EXPECT_EQ(d.reason.rfind("no chessboard of 10×10 inner corners", 0), 0u) << d.reason;
    // The marker boards' finders search the same reduced images.
    for (const Target& t : {testing::Charuco7x5(), testing::KalibrAprilGrid6x4(), testing::AprilGrid6x4()}) {
      EXPECT_EQ(DetectTarget(*image, t, DetectorOptions{}).status, DetectionStatus::kNotFound) << DescribeTarget(t);
    }
  }
}

class HeaderSizes : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vstcal-bounded-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path Write(const std::string& name, const std::vector<uchar>& bytes) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return p;
  }
  fs::path Encode(const std::string& name, int width, int height) {
    std::vector<uchar> bytes;
    cv::imencode(fs::path(name).extension().string(), cv::Mat(height, width, CV_8U, cv::Scalar(90)), bytes);
    return Write(name, bytes);
  }
  fs::path dir_;
};

TEST_F(HeaderSizes, PngAndJpegSizesWithoutDecoding) {
  EXPECT_EQ(ReadImageHeaderSize(Encode("a.png", 321, 123)), std::make_pair(321, 123));
  EXPECT_EQ(ReadImageHeaderSize(Encode("b.jpg", 640, 480)), std::make_pair(640, 480));
  // A JPEG whose frame header follows 60 KiB of metadata (an APP1 segment, as EXIF with a thumbnail).
  std::vector<uchar> jpeg;
  cv::imencode(".jpg", cv::Mat(30, 40, CV_8U, cv::Scalar(200)), jpeg);
  std::vector<uchar> app1 = {0xFF, 0xE1, 0xF0, 0x00};
  app1.resize(2 + 0xF000, 0x41);
  jpeg.insert(jpeg.begin() + 2, app1.begin(), app1.end());
  EXPECT_EQ(ReadImageHeaderSize(Write("exif.jpg", jpeg)), std::make_pair(40, 30));
  const LoadedImage loaded = LoadImageFile(dir_ / "exif.jpg");  // OpenCV agrees
  EXPECT_EQ(loaded.image.width, 40);
  EXPECT_EQ(loaded.image.height, 30);
  // No size where the header does not say: BMP (decoded, then checked), a truncated PNG, no file.
  EXPECT_EQ(ReadImageHeaderSize(Encode("c.bmp", 64, 48)), std::nullopt);
  EXPECT_EQ(ReadImageHeaderSize(Write("cut.png", {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0})), std::nullopt);
  EXPECT_EQ(ReadImageHeaderSize(dir_ / "missing.png"), std::nullopt);
}

// Mixed sizes are refused from the headers: no image is searched (the progress never moves).
TEST_F(HeaderSizes, MixedSizesRefusedBeforeAnyDetection) {
  std::vector<CaptureInput> inputs;
  for (const auto& [name, w, h] : {std::tuple{"v0.png", 640, 480}, {"v1.png", 640, 480}, {"v2.jpg", 320, 240}}) {
    const fs::path p = Encode(name, w, h);
    inputs.push_back({p.filename().string(), p, std::nullopt});
  }
  DetectRequest request;
  request.target = testing::Chessboard9x6();
  int ticks = 0;
  try {
    DetectInFiles(inputs, request, [&](double) { ++ticks; });
    ADD_FAILURE() << "mixed sizes accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("v2.jpg: 320×240 pixels, but v0.png has 640×480"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ticks, 0);
}

}  // namespace
}  // namespace vstcal
