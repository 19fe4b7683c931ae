// Issue 25 item 4: a board that is not found is said to be blurred or too small where the image
// shows it (miss_diagnosis.h), on rendered views: a heavily blurred board says blurred (the
// measure, the limit and "refocus"), a board too small in the image says too small ("move the
// camera closer"), and a plain miss — no board, or another board — says neither.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "support/capture_scenes.h"
#include "vstcal/capture/detect.h"
#include "vstcal/capture/miss_diagnosis.h"

namespace vstcal {
namespace {

using testing::RenderedView;

RenderedView MissView(const Target& t, double square_px, double blur_px, int k) {
  const Camera camera = testing::DistortedCamera(640, 480, 600);
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

}  // namespace
}  // namespace vstcal
