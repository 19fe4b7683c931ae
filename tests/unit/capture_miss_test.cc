// Issue 25 item 4: a board that is not found is said to be blurred or too small where the image
// shows it (miss_diagnosis.h), on rendered views: a heavily blurred board says blurred (the
// measure, the limit and "refocus"), a board too small in the image says too small ("move the
// camera closer"), and a plain miss — no board, or another board — says neither.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "support/capture_scenes.h"
#include "vstcal/capture/detect.h"
#include "vstcal/capture/miss_diagnosis.h"
#include "vstcal/capture/saddle_lattice.h"

namespace vstcal {
namespace {

using testing::RenderedView;

RenderedView MissView(const Target& t, double square_px, double blur_px, int k, int width = 640, int height = 480, double f = 600) {
  const Camera camera = testing::DistortedCamera(width, height, f);
  RenderOptions o;
  o.blur_px = blur_px;
  o.noise = 2;
  return testing::RenderTestView(camera, t, testing::TestViewPose(camera, t, square_px, k, 31), o, static_cast<uint32_t>(k));
}

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The blur measure reads the rendered blur back: σ 1 and 4 px within 20 % (sharpest tenth of the edges).
TEST(MissDiagnosis, SharpestEdgeBlurReadsTheRenderedBlur) {
  for (const double sigma : {1.0, 4.0}) {
    const auto sharp = SharpestEdgeBlur(MissView(testing::Chessboard9x6(), 45, sigma, 0).image, 16);
    ASSERT_TRUE(sharp.has_value());
    EXPECT_NEAR(sharp->sigma_px, sigma, 0.2 * sigma) << sharp->edges << " edges";
  }
  EXPECT_FALSE(SharpestEdgeBlur(GrayImage(640, 480, 128), 16).has_value());  // no edge: no verdict
}

TEST(MissDiagnosis, BlurredBoardsSayBlurred) {
  for (const Target& t : {testing::Chessboard9x6(), testing::Charuco7x5(), testing::KalibrAprilGrid6x4(), testing::AprilGrid6x4()}) {
    const Detection d = DetectTarget(MissView(t, 40, 7, 1).image, t, DetectorOptions{});
    ASSERT_NE(d.status, DetectionStatus::kFound) << DescribeTarget(t);
    if (d.status == DetectionStatus::kRejected) {  // found and measured: the found path's own message
      EXPECT_EQ(d.reason.rfind("blurred: ", 0), 0u) << d.reason;
      continue;
    }
    EXPECT_TRUE(Has(d.reason, "the image looks blurred: its sharpest edges are blurred over σ = ")) << DescribeTarget(t) << ": " << d.reason;
    EXPECT_TRUE(Has(d.reason, "more than max_blur_px 3.00 px; refocus the camera")) << d.reason;
    EXPECT_FALSE(Has(d.reason, "too small")) << d.reason;
  }
}

// A chessboard blurred past what the finders read (σ 10 px on 25 px squares: not found, where σ 7
// on 40 px squares is found and rejected above) goes through the miss path: blurred, not too small.
TEST(MissDiagnosis, ChessboardsBlurredPastFindingSayBlurred) {
  const Target t = testing::Chessboard9x6();
  for (int k = 0; k < 2; ++k) {
    const Detection d = DetectTarget(MissView(t, 25, 10, k).image, t, DetectorOptions{});
    ASSERT_EQ(d.status, DetectionStatus::kNotFound) << d.reason;
    EXPECT_TRUE(Has(d.reason, "the image looks blurred: its sharpest edges are blurred over σ = ")) << d.reason;
    EXPECT_FALSE(Has(d.reason, "look too small")) << d.reason;
  }
}

TEST(MissDiagnosis, BoardsTooSmallSayTooSmall) {
  // Each at a size its detector cannot read: libapriltag still decodes vstcal's grid at 11 px.
  for (const auto& [t, square_px] : {std::pair{testing::Charuco7x5(), 11.0}, {testing::KalibrAprilGrid6x4(), 11.0}, {testing::AprilGrid6x4(), 7.0}}) {
    const Detection d = DetectTarget(MissView(t, square_px, 0.5, 2).image, t, DetectorOptions{});
    ASSERT_EQ(d.status, DetectionStatus::kNotFound) << DescribeTarget(t) << ": " << d.reason;
    EXPECT_TRUE(Has(d.reason, "look too small: ")) << DescribeTarget(t) << ": " << d.reason;
    EXPECT_TRUE(Has(d.reason, "move the camera closer")) << d.reason;
    EXPECT_FALSE(Has(d.reason, "blurred")) << d.reason;
  }
}

// A chessboard drawn square by square (not by the renderer): `cols` × `rows` squares of `square`
// px from (x0, y0), smoothed by σ 0.7 px, noise σ 2.
GrayImage DrawnChessboard(int cols, int rows, int square, int x0, int y0) {
  GrayImage image(320, 240, 200);
  cv::Mat m(image.height, image.width, CV_8U, image.pixels.data());
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if ((r + c) % 2 == 0) cv::rectangle(m, cv::Rect(x0 + c * square, y0 + r * square, square, square), cv::Scalar(30), cv::FILLED);
    }
  }
  cv::GaussianBlur(m, m, cv::Size(0, 0), 0.7);
  cv::Mat noise(m.size(), CV_16S);
  cv::setRNGSeed(5);
  cv::randn(noise, 0, 2);
  m.convertTo(m, CV_16S);
  m += noise;
  m.convertTo(m, CV_8U);
  return image;
}

// The lattice of corners reads the square size of a drawn board back (its links are the squares'
// sides: 5, 6 and 9 px), and counts its corners; an edge, noise and one grey show none.
TEST(MissDiagnosis, SaddleLatticeReadsTheSquares) {
  for (const int square : {5, 6, 9}) {
    const auto lattice = FindSaddleLattice(DrawnChessboard(10, 7, square, 40, 40), 3.0 * square);
    ASSERT_TRUE(lattice.has_value()) << square;
    EXPECT_NEAR(lattice->spacing_px, square, 0.5) << square;
    // 9 × 6 inner corners; the outer corners of the border squares (11 × 8 in all) may join them.
    EXPECT_GE(lattice->corners, 9 * 6 * 3 / 4) << square;
    EXPECT_LE(lattice->corners, 11 * 8) << square;
  }
  GrayImage edge(320, 240, 200);
  cv::Mat m(edge.height, edge.width, CV_8U, edge.pixels.data());
  cv::rectangle(m, cv::Rect(0, 0, 160, 240), cv::Scalar(30), cv::FILLED);
  cv::GaussianBlur(m, m, cv::Size(0, 0), 0.7);
  GrayImage noise(320, 240);
  cv::Mat n(noise.height, noise.width, CV_8U, noise.pixels.data());
  cv::setRNGSeed(3);
  cv::randu(n, 0, 256);
  for (const GrayImage* image : {&edge, &noise}) EXPECT_FALSE(FindSaddleLattice(*image, 20).has_value());
  EXPECT_FALSE(FindSaddleLattice(GrayImage(320, 240, 128), 20).has_value());
}

// Squares of 5 px, which the finders do not read (kMinSquareSearchPx), sharp or blurred σ 1.5 px:
// too small, the size read back, not blurred. In a 1600×1200 image (searched reduced) 12 px squares
// are too small too, the limit scaled by the reduction.
TEST(MissDiagnosis, ChessboardsTooSmallSayTooSmall) {
  const Target t = testing::Chessboard9x6();
  for (const double blur : {0.5, 1.5}) {
    const Detection d = DetectTarget(MissView(t, 5, blur, 2).image, t, DetectorOptions{});
    ASSERT_EQ(d.status, DetectionStatus::kNotFound) << d.reason;
    EXPECT_TRUE(Has(d.reason, "the squares look too small: a lattice of ")) << d.reason;
    EXPECT_TRUE(Has(d.reason, "the chessboard finders need about 7 px a square; move the camera closer")) << d.reason;
    EXPECT_FALSE(Has(d.reason, "blurred;")) << d.reason;
    const auto lattice = FindSaddleLattice(MissView(t, 5, blur, 2).image, 10.5);
    ASSERT_TRUE(lattice.has_value());
    EXPECT_NEAR(lattice->spacing_px, 5, 1) << "squares of about 5 px (the view is tilted up to 35°)";
  }
  const Detection large = DetectTarget(MissView(t, 12, 0.5, 2, 1600, 1200, 1500).image, t, DetectorOptions{});
  ASSERT_EQ(large.status, DetectionStatus::kNotFound) << large.reason;
  EXPECT_TRUE(Has(large.reason, "the squares look too small: ")) << large.reason;
  EXPECT_TRUE(Has(large.reason, "in an image this large (searched reduced by ")) << large.reason;
}

TEST(MissDiagnosis, PlainMissesSayNeither) {
  GrayImage noise(640, 480);
  cv::Mat m(noise.height, noise.width, CV_8U, noise.pixels.data());
  cv::setRNGSeed(3);
  cv::randu(m, 0, 256);
  const GrayImage chessboard = MissView(testing::Chessboard9x6(), 40, 0.8, 3).image;  // sharp, but not the board looked for
  const GrayImage grey(640, 480, 128);
  const std::vector<const GrayImage*> images = {&noise, &chessboard, &grey};
  for (const Target& t : {testing::Chessboard9x6(), testing::Charuco7x5(), testing::KalibrAprilGrid6x4(), testing::AprilGrid6x4()}) {
    for (const GrayImage* image : images) {
      const Detection d = DetectTarget(*image, t, DetectorOptions{});
      if (d.status == DetectionStatus::kFound) continue;  // the chessboard itself
      EXPECT_FALSE(Has(d.reason, "blurred")) << DescribeTarget(t) << ": " << d.reason;
      EXPECT_FALSE(Has(d.reason, "too small")) << DescribeTarget(t) << ": " << d.reason;
    }
  }
}

// Marker boards hold small cells whose corners are saddles too, and junctions between tags: read
// as a chessboard, none is a lattice of small squares.
TEST(MissDiagnosis, MarkerBoardsReadAsAChessboardAreNotTooSmall) {
  const Target chessboard = testing::Chessboard9x6();
  for (const auto& [t, square_px] : {std::pair{testing::Charuco7x5(), 11.0}, {testing::Charuco7x5(), 40.0}, {testing::KalibrAprilGrid6x4(), 40.0},
                                     {testing::AprilGrid6x4(), 11.0}}) {
    const Detection d = DetectTarget(MissView(t, square_px, 0.5, 2).image, chessboard, DetectorOptions{});
    ASSERT_EQ(d.status, DetectionStatus::kNotFound) << DescribeTarget(t);
    EXPECT_FALSE(Has(d.reason, "look too small")) << DescribeTarget(t) << ": " << d.reason;
  }
}

}  // namespace
}  // namespace vstcal
