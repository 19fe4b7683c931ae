// The renderer against independent computations: closed-form pixel coverage of a fronto-parallel
// board, brute-force supersampling of a tilted board through a distorted lens, and the noise, blur
// and lighting it adds; determinism for any thread count.
#include <gtest/gtest.h>

#include <cmath>

#include "support/capture_scenes.h"
#include "vstcal/capture/corner_refinement.h"
#include "vstcal/capture/render_scene.h"
#include "vstcal/capture/target_pattern.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

using testing::Chessboard9x6;

// Black, by the chessboard's own rule written out again: inside the squares' extent, square
// (i, j) = (⌊x/S⌋ + 1, ⌊y/S⌋ + 1) black when i + j is even.
bool IsBlack(const Target& t, double x, double y) {
  const double S = t.square_size;
  if (x < -S || y < -S || x >= t.cols * S || y >= t.rows * S) return false;
  const long i = static_cast<long>(std::floor(x / S)) + 1, j = static_cast<long>(std::floor(y / S)) + 1;
  return (i + j) % 2 == 0;
}

double Overlap(double a0, double a1, double b0, double b1) { return std::max(0.0, std::min(a1, b1) - std::max(a0, b0)); }

// Facing the board squarely at depth Z with f = Z, one board millimetre is one pixel: pixel
// (u, v) covers board [u − ½ − ox, u + ½ − ox] × [v − ½ − oy, …], and its black fraction is a sum
// of products of interval overlaps.
TEST(Render, FrontoParallelCoverageIsTheClosedForm) {
  const Target t = Chessboard9x6();
  const Camera camera = testing::PinholeCamera(320, 240, 500);
  const double ox = 20.3, oy = 40.65;  // where the board origin projects, relative to the principal point
  const Rigid3d camera_from_board{Eigen::Matrix3d::Identity(), Eigen::Vector3d(ox - 159.5, oy - 119.5, 500)};
  RenderOptions options;
  const std::vector<double> image = RenderCoverage(PixelCornerRays(camera), TargetPattern(t), camera_from_board, options);
  const Rect sheet = SheetExtent(t);
  double worst = 0;
  for (int v = 0; v < 240; ++v) {
    for (int u = 0; u < 320; ++u) {
      const double x0 = u - 0.5 - ox, x1 = x0 + 1, y0 = v - 0.5 - oy, y1 = y0 + 1;
      double black = 0;
      for (int j = 0; j <= t.rows; ++j) {
        for (int i = 0; i <= t.cols; ++i) {
          if ((i + j) % 2 == 0) black += Overlap(x0, x1, (i - 1) * 25.0, i * 25.0) * Overlap(y0, y1, (j - 1) * 25.0, j * 25.0);
        }
      }
      const double on_sheet = Overlap(x0, x1, sheet.x0, sheet.x1) * Overlap(y0, y1, sheet.y0, sheet.y1);
      const double expected = options.background * (1 - on_sheet) + options.white * (on_sheet - black) + options.black * black;
      worst = std::max(worst, std::abs(image[static_cast<size_t>(v) * 320 + u] - expected));
    }
  }
  EXPECT_LT(worst, 1e-9);
}

// Through a distorted lens at a 40° tilt, each pixel's grey is the mean over a 24 × 24 grid of
// points in the pixel, each unprojected and tested with the rule above: the exact area, up to
// the grid's resolution (an edge through a pixel moves its mean by at most 1/24 of the contrast).
TEST(Render, TiltedDistortedCoverageMatchesSupersampling) {
  const Target t = Chessboard9x6();
  const Camera camera = testing::DistortedCamera(320, 240, 300);
  const Eigen::Matrix3d R = RotationFromRotvec(Eigen::Vector3d(DegToRad(30), DegToRad(25), DegToRad(10)));
  const Rigid3d camera_from_board{R, Eigen::Vector3d(0, 0, 500) - R * Eigen::Vector3d(100, 62.5, 0)};
  RenderOptions options;
  const std::vector<double> image = RenderCoverage(PixelCornerRays(camera), TargetPattern(t), camera_from_board, options);
  const Rect sheet = SheetExtent(t);
  const Eigen::Vector3d n = R.col(2);
  const CounterRng pick(3, 0);
  constexpr int kGrid = 24;
  double sum_abs = 0, worst = 0;
  constexpr int kPixels = 1500;
  for (int k = 0; k < kPixels; ++k) {
    const auto r = pick.Uniform2(k, 0);
    const int u = static_cast<int>(r[0] * 320), v = static_cast<int>(r[1] * 240);
    double grey = 0;
    for (int a = 0; a < kGrid; ++a) {
      for (int b = 0; b < kGrid; ++b) {
        const auto ray = camera.Unproject(Eigen::Vector2d(u - 0.5 + (a + 0.5) / kGrid, v - 0.5 + (b + 0.5) / kGrid));
        ASSERT_TRUE(ray);
        const Eigen::Vector3d p = R.transpose() * (n.dot(camera_from_board.t) / n.dot(*ray) * *ray - camera_from_board.t);
        const bool on_sheet = p.x() >= sheet.x0 && p.x() < sheet.x1 && p.y() >= sheet.y0 && p.y() < sheet.y1;
        grey += !on_sheet ? options.background : IsBlack(t, p.x(), p.y()) ? options.black : options.white;
      }
    }
    grey /= kGrid * kGrid;
    const double d = std::abs(image[static_cast<size_t>(v) * 320 + u] - grey);
    sum_abs += d;
    worst = std::max(worst, d);
  }
  const double contrast = options.white - options.black;
  EXPECT_LT(worst, 2.0 * contrast / kGrid);
  EXPECT_LT(sum_abs / kPixels, 0.05 * contrast / kGrid);  // most pixels hold no edge
}

RenderedScene SmallScene(unsigned threads, double noise) {
  SceneSpec spec;
  spec.rig = Rig::kPlanarViews;
  spec.views.num_views = 3;
  spec.views.distance = 600;
  spec.render.noise = noise;
  spec.render.blur_px = 0.8;
  spec.render.lighting = 0.3;
  spec.render.seed = 11;
  spec.threads = threads;
  return RenderScene(testing::DistortedCamera(320, 240, 300), Chessboard9x6(), spec);
}

TEST(Render, SameSeedSameBytesForAnyThreadCount) {
  const RenderedScene one = SmallScene(1, 3), two = SmallScene(2, 3), again = SmallScene(2, 3);
  ASSERT_EQ(one.images.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(one.images[k].pixels, two.images[k].pixels);
    EXPECT_EQ(two.images[k].pixels, again.images[k].pixels);
  }
}

// The noise is N(0, σ²) per pixel before rounding: the difference from the noise-free render has
// standard deviation √(σ² + 1/6) (two roundings of 1/12 each) and mean 0.
TEST(Render, NoiseHasItsSigma) {
  const Camera camera = testing::PinholeCamera(400, 300, 400);
  const Pattern pattern = TargetPattern(Chessboard9x6());
  const PixelCornerRays rays(camera);
  const Rigid3d pose{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-100, -62.5, 500)};
  RenderOptions clean, noisy;
  noisy.noise = 5;
  const GrayImage a = RenderView(rays, pattern, pose, clean, 0), b = RenderView(rays, pattern, pose, noisy, 0);
  double sum = 0, sum2 = 0;
  for (size_t k = 0; k < a.pixels.size(); ++k) {
    const double d = static_cast<double>(b.pixels[k]) - a.pixels[k];
    sum += d;
    sum2 += d * d;
  }
  const double n = static_cast<double>(a.pixels.size()), mean = sum / n;
  EXPECT_NEAR(mean, 0, 0.05);  // standard error 5/√120000 = 0.014
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), std::sqrt(25 + 1.0 / 6), 0.05);
  EXPECT_NE(RenderView(rays, pattern, pose, noisy, 1).pixels, b.pixels);  // another view, another stream
}

// The blur is a Gaussian of the requested σ: the edge-blur measure of the detector (which
// subtracts the pixel's and the sampling's spread) reads it back.
TEST(Render, BlurReadsBackFromTheEdges) {
  const Camera camera = testing::PinholeCamera(400, 300, 400);
  const Pattern pattern = TargetPattern(Chessboard9x6());
  const PixelCornerRays rays(camera);
  const Rigid3d pose{RotationFromRotvec(Eigen::Vector3d(0, 0, 0.3)), Eigen::Vector3d(-80, -70, 450)};
  for (const double sigma : {0.0, 1.0, 2.0}) {
    RenderOptions options;
    options.blur_px = sigma;
    const GrayImage image = RenderView(rays, pattern, pose, options, 0);
    // An edge of square (1, 1): from corner (0, 0) to corner (0, 1) of the board, 20 px long.
    const auto a = camera.Project(pose * Eigen::Vector3d(0, 0, 0)), b = camera.Project(pose * Eigen::Vector3d(25, 0, 0));
    const auto measured = EdgeBlur(image, *a, *b, 8);
    ASSERT_TRUE(measured);
    EXPECT_NEAR(*measured, sigma, 0.15) << sigma;
  }
}

// Lighting multiplies by 1 − L·ramp, the ramp running from 0 at one corner of the image to 1 at
// the opposite one (direction 0°: along +u).
TEST(Render, LightingIsALinearGain) {
  const Camera camera = testing::PinholeCamera(200, 100, 5000);  // 20 × 10 mm of the white margin fills the view
  const Pattern pattern = TargetPattern(Chessboard9x6());
  const Rigid3d pose{Eigen::Matrix3d::Identity(), Eigen::Vector3d(37.5, 37.5, 500)};
  RenderOptions options;
  options.lighting = 0.4;
  options.lighting_direction_deg = 0;
  const GrayImage image = RenderView(PixelCornerRays(camera), pattern, pose, options, 0);
  const std::vector<double> flat = RenderCoverage(PixelCornerRays(camera), pattern, pose, options);
  ASSERT_EQ(flat[0], options.white);
  for (const int u : {0, 50, 199}) {
    const double expected = options.white * (1 - 0.4 * u / 199.0);
    EXPECT_NEAR(image.at(u, 50), expected, 0.5) << u;
  }
}

}  // namespace
}  // namespace vstcal
