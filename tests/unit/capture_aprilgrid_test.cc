// Kalibr's aprilgrid: the layout against Kalibr's own formulas, the printed tags against Kalibr's
// generator, and detection on boards drawn here — OpenCV's drawMarker with a two-cell border,
// placed by Kalibr's layout formula with its black junction squares, independently of vstcal's
// drawing — warped by homographies and blurred: every tag found, the corners against the truth
// beside OpenCV's ArUco corners (raw, cornerSubPix as Kalibr runs it, and OpenCV's own subpixel
// refinement) on the same images. And the messages when a board is read as the other AprilTag type.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iterator>
#include <map>
#include <numbers>
#include <random>

#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>

#include "support/capture_scenes.h"
#include "vstcal/capture/detect.h"
#include "vstcal/capture/target_pattern.h"

namespace vstcal {
namespace {

// Kalibr's default board (kalibr_create_target_pdf's example: 6 × 6 tags, tspace 0.3), in mm.
Target KalibrBoard(int rows = 6, int cols = 6, double tag = 88, double spacing = 0.3) {
  Target t;
  t.type = TargetType::kAprilGrid;
  t.rows = rows;
  t.cols = cols;
  t.tag_size = tag;
  t.tag_spacing = spacing;
  t.family = "tag36h11";
  t.margin = spacing * tag;
  return t;
}

// Kalibr's GridCalibrationTargetAprilgrid::createGridPoints: point r·(2·cols) + c of its
// 2·rows × 2·cols grid, in Kalibr's frame (y up the sheet).
Eigen::Vector2d KalibrPoint(const Target& t, int id) {
  const int cols = 2 * t.cols, r = id / cols, c = id % cols;
  return Eigen::Vector2d((c / 2) * (1 + t.tag_spacing) * t.tag_size + (c % 2) * t.tag_size,
                         (r / 2) * (1 + t.tag_spacing) * t.tag_size + (r % 2) * t.tag_size);
}

TEST(KalibrAprilGrid, CornersAreKalibrsPointsWithYDown) {
  const Target t = KalibrBoard();
  ASSERT_FALSE(CheckTarget(t));
  ASSERT_EQ(NumCorners(t), 4 * 36);
  for (int id = 0; id < NumCorners(t); ++id) {
    const Eigen::Vector2d k = KalibrPoint(t, id);
    EXPECT_EQ(CornerPosition(t, id), Eigen::Vector2d(k.x(), -k.y())) << id;
  }
  // By hand: the first row of points runs 0, s, p, p + s (p = 1.3 s); point 12 is a tag up.
  EXPECT_DOUBLE_EQ(CornerPosition(t, 1).x(), 88);
  EXPECT_DOUBLE_EQ(CornerPosition(t, 2).x(), 114.4);
  EXPECT_DOUBLE_EQ(CornerPosition(t, 12).y(), -88);
  EXPECT_DOUBLE_EQ(CornerPosition(t, 24).y(), -114.4);
  // Tag 7 (second row from the bottom, second column): its bottom-left corner is point 2·12 + 2.
  EXPECT_EQ(MarkerQuads(t)[7][3], CornerPosition(t, 26));
  EXPECT_EQ(MarkerQuads(t)[7][1], CornerPosition(t, 26 + 12 + 1));
  const Rect extent = PatternExtent(t);
  EXPECT_DOUBLE_EQ(extent.x0, -0.3 * 88);
  EXPECT_DOUBLE_EQ(extent.x1, 6 * 1.3 * 88);
  EXPECT_EQ(AprilGridJunctionSquares(t).size(), 49u);
}

// Kalibr's generator (kalibr_create_target_pdf's generateAprilTag) prints data cell (i, j) — row i
// from the top of the printed tag, column j from its left — black when bit 6·i + j, counted from
// the most significant of the 36, of the tag's code is 0 (it sets bit 6·i' + j' from the least
// significant and turns the matrix half a turn). Tag 0's tag36h11 code is 0xd5d628584.
TEST(KalibrAprilGrid, PrintedTagsAreKalibrs) {
  constexpr uint64_t kCode0 = 0xd5d628584ULL;
  const MarkerCells m = AprilGridTagCells(0);
  ASSERT_EQ(m.side, 10);
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const bool border = i < 2 || j < 2 || i >= 8 || j >= 8;
      const bool black = border || !((kCode0 >> (35 - (6 * (i - 2) + (j - 2)))) & 1);
      EXPECT_EQ(m.black[i * 10 + j], black) << i << ", " << j;
    }
  }
}

TEST(KalibrAprilGrid, CheckTargetRefusesWhatKalibrCannotPrintOrDetect) {
  Target t = KalibrBoard();
  t.tag_spacing = 0.05;
  ASSERT_TRUE(CheckTarget(t));
  EXPECT_EQ(CheckTarget(t)->field, "tag_spacing");
  t = KalibrBoard(25, 25);
  ASSERT_TRUE(CheckTarget(t));  // 625 tags: tag36h11 has 587
  EXPECT_EQ(CheckTarget(t)->field, "rows");
}

// A board drawn as Kalibr prints it, on a canvas of `px` pixels per mm: tag t at Kalibr's
// (tc·p, tr·p) from the bottom-left, OpenCV's marker t with a two-cell border turned half a turn
// (PrintedTagsAreKalibrs), a black square of side g at each of its four corners.
struct Canvas {
  cv::Mat image;
  Eigen::Vector2d origin;  // canvas pixel (edges: pixel i spans [i, i + 1]) of Kalibr's origin
  double px_per_mm = 0;
  // A Kalibr point as a canvas pixel, (0, 0) the centre of the top-left pixel.
  Eigen::Vector2d Pixel(const Eigen::Vector2d& kalibr) const {
    return origin + px_per_mm * Eigen::Vector2d(kalibr.x(), -kalibr.y()) - Eigen::Vector2d(0.5, 0.5);
  }
};

Canvas DrawKalibrBoard(const Target& t, double px_per_mm) {
  const double T = t.tag_size, g = t.tag_spacing * T, p = T + g;
  const int tag_px = static_cast<int>(std::lround(T * px_per_mm));
  const int margin = static_cast<int>(std::lround(2 * g * px_per_mm));
  Canvas c;
  c.px_per_mm = px_per_mm;
  const int width = static_cast<int>(std::lround((t.cols * p + g) * px_per_mm)) + 2 * margin;
  const int height = static_cast<int>(std::lround((t.rows * p + g) * px_per_mm)) + 2 * margin;
  c.image = cv::Mat(height, width, CV_8U, cv::Scalar(255));
  c.origin = Eigen::Vector2d(margin + g * px_per_mm, height - margin - g * px_per_mm);
  const cv::Ptr<cv::aruco::Dictionary> dict = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_APRILTAG_36h11);
  auto fill = [&](double x0, double y0, double w) {  // Kalibr's rectangle from its lower-left corner
    const Eigen::Vector2d a = c.origin + px_per_mm * Eigen::Vector2d(x0, -(y0 + w));
    const int side = static_cast<int>(std::lround(w * px_per_mm));
    return cv::Rect(static_cast<int>(std::lround(a.x())), static_cast<int>(std::lround(a.y())), side, side);
  };
  for (int tr = 0; tr < t.rows; ++tr) {
    for (int tc = 0; tc < t.cols; ++tc) {
      cv::Mat marker;
      cv::aruco::drawMarker(dict, tr * t.cols + tc, tag_px, marker, 2);
      cv::rotate(marker, marker, cv::ROTATE_180);
      marker.copyTo(c.image(fill(tc * p, tr * p, T)));
      for (const auto& [dx, dy] : {std::pair{-g, -g}, {T, -g}, {T, T}, {-g, T}}) c.image(fill(tc * p + dx, tr * p + dy, g)).setTo(0);
    }
  }
  return c;
}

struct WarpedView {
  cv::Mat image;
  std::map<int, Eigen::Vector2d> truth;  // Kalibr's point id → pixel
};

// The canvas through the homography `H` (canvas pixel → image pixel, centres at integers) into a
// 640 × 480 image, anti-aliased, blurred by σ = 0.8 px and given noise of σ = 2 grey levels.
WarpedView Warp(const Canvas& canvas, const Target& t, const cv::Matx33d& H, uint32_t seed) {
  cv::Mat smooth;
  const double shrink = std::sqrt(std::abs(cv::determinant(cv::Mat(H))));  // image px per canvas px, roughly
  cv::GaussianBlur(canvas.image, smooth, cv::Size(), 0.5 / shrink);
  WarpedView v;
  cv::warpPerspective(smooth, v.image, cv::Mat(H), cv::Size(640, 480), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(255));
  cv::GaussianBlur(v.image, v.image, cv::Size(), 0.8);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 2);
  for (int r = 0; r < v.image.rows; ++r) {
    for (int col = 0; col < v.image.cols; ++col) {
      uint8_t& px = v.image.at<uint8_t>(r, col);
      px = cv::saturate_cast<uint8_t>(px + noise(rng));
    }
  }
  for (int id = 0; id < NumCorners(t); ++id) {
    const Eigen::Vector2d q = canvas.Pixel(KalibrPoint(t, id));
    const cv::Vec3d h = H * cv::Vec3d(q.x(), q.y(), 1);
    v.truth[id] = Eigen::Vector2d(h[0] / h[2], h[1] / h[2]);
  }
  return v;
}

// Homographies from the canvas into the image: the board's centre to the image's centre, scaled
// to 320 px across (whole at any turn), turned by `roll_deg` and seen at a tilt (a perspective row).
cv::Matx33d ViewOf(const Canvas& c, double roll_deg, double tilt_x, double tilt_y) {
  const double s = 320.0 / std::max(c.image.cols, c.image.rows), a = roll_deg * std::numbers::pi / 180;
  const cv::Matx33d centre(1, 0, -0.5 * c.image.cols, 0, 1, -0.5 * c.image.rows, 0, 0, 1);
  const cv::Matx33d turn(s * std::cos(a), -s * std::sin(a), 0, s * std::sin(a), s * std::cos(a), 0, 0, 0, 1);
  const cv::Matx33d tilt(1, 0, 0, 0, 1, 0, tilt_x, tilt_y, 1);
  const cv::Matx33d image(1, 0, 320, 0, 1, 240, 0, 0, 1);
  return image * tilt * turn * centre;
}

// OpenCV's ArUco corners with a two-cell border; OpenCV's corner k of tag t is Kalibr's point
// bottom-right, bottom-left, top-left, top-right of the printed tag (it is turned half a turn).
std::map<int, Eigen::Vector2d> OpenCvCorners(const cv::Mat& image, const Target& t, int refinement, bool kalibr_subpix) {
  const cv::Ptr<cv::aruco::DetectorParameters> params = cv::aruco::DetectorParameters::create();
  params->markerBorderBits = 2;
  params->cornerRefinementMethod = refinement;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(image, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_APRILTAG_36h11), corners, ids, params);
  std::map<int, Eigen::Vector2d> out;
  const int cols = 2 * t.cols;
  for (size_t k = 0; k < ids.size(); ++k) {
    if (ids[k] >= t.rows * t.cols) continue;
    if (kalibr_subpix) {  // GridCalibrationTargetAprilgrid::computeObservation's refinement
      cv::cornerSubPix(image, corners[k], cv::Size(2, 2), cv::Size(-1, -1),
                       cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::MAX_ITER, 30, 0.1));
    }
    const int base = (ids[k] / t.cols) * 2 * cols + (ids[k] % t.cols) * 2;
    const int point[4] = {base + 1, base, base + cols, base + cols + 1};
    for (int c = 0; c < 4; ++c) out[point[c]] = Eigen::Vector2d(corners[k][c].x, corners[k][c].y);
  }
  return out;
}

GrayImage ToGray(const cv::Mat& m) {
  GrayImage g(m.cols, m.rows);
  g.pixels.assign(m.datastart, m.dataend);
  return g;
}

struct Accuracy {
  double sum2 = 0;
  int n = 0, wrong = 0;
  void Add(const Eigen::Vector2d& found, const Eigen::Vector2d& truth) {
    const double e = (found - truth).norm();
    if (e > 2) {
      ++wrong;
      return;
    }
    sum2 += e * e;
    ++n;
  }
  double rms() const { return n ? std::sqrt(sum2 / n) : NAN; }
};

TEST(KalibrAprilGrid, EveryTagOpenCvDecodesAndCornersMoreAccurateThanOpenCvs) {
  const Target t = KalibrBoard(6, 6, 80);
  const Canvas canvas = DrawKalibrBoard(t, 1.0);  // 80 px tags, 8 px cells, 24 px gaps: whole pixels
  const cv::Matx33d views[] = {ViewOf(canvas, 0, 0, 0), ViewOf(canvas, 30, 4e-4, 0), ViewOf(canvas, 150, -3e-4, 4e-4),
                               ViewOf(canvas, 260, 2e-4, -5e-4)};
  Accuracy ours, raw, subpix, kalibr;
  int found_tags = 0;
  for (uint32_t k = 0; k < std::size(views); ++k) {
    const WarpedView v = Warp(canvas, t, views[k], k + 1);
    const GrayImage gray = ToGray(v.image);
    const Detection d = DetectTarget(gray, t, DetectorOptions{});
    ASSERT_EQ(d.status, DetectionStatus::kFound) << "view " << k << ": " << d.reason;
    found_tags += static_cast<int>(d.corners.size()) / 4;
    for (const DetectedCorner& c : d.corners) ours.Add(c.pixel, v.truth.at(c.id));
    for (const auto& [id, px] : OpenCvCorners(v.image, t, cv::aruco::CORNER_REFINE_NONE, false)) raw.Add(px, v.truth.at(id));
    for (const auto& [id, px] : OpenCvCorners(v.image, t, cv::aruco::CORNER_REFINE_SUBPIX, false)) subpix.Add(px, v.truth.at(id));
    for (const auto& [id, px] : OpenCvCorners(v.image, t, cv::aruco::CORNER_REFINE_NONE, true)) kalibr.Add(px, v.truth.at(id));
  }
  std::printf("aprilgrid 6x6, 4 warped views (tags about 34 px, blur 0.8 px, noise 2): corners found / wrong / RMS px\n"
              "  vstcal (aruco + symmetry)       %3d / %d / %.3f\n"
              "  OpenCV aruco, no refinement     %3d / %d / %.3f\n"
              "  OpenCV aruco, CORNER_REFINE_SUBPIX %3d / %d / %.3f\n"
              "  OpenCV aruco + cornerSubPix 2x2 (Kalibr) %3d / %d / %.3f\n",
              ours.n, ours.wrong, ours.rms(), raw.n, raw.wrong, raw.rms(), subpix.n, subpix.wrong, subpix.rms(), kalibr.n, kalibr.wrong,
              kalibr.rms());
  // With tags of about 34 px (cells of 3.4 px) and blur, OpenCV's detectMarkers with its default
  // sampling decodes 94 of the 144 tags; vstcal's (6 px a cell, the cells' middles: aruco_tags.cc)
  // 105, and keeps at least every corner OpenCV's default finds (docs/experiments/corners.md#aprilgrid).
  EXPECT_GE(ours.n + ours.wrong, subpix.n + subpix.wrong);
  EXPECT_GE(found_tags, 100);
  EXPECT_EQ(ours.wrong, 0);
  EXPECT_LE(ours.rms(), std::min({raw.rms(), subpix.rms(), kalibr.rms()}));
  EXPECT_LT(ours.rms(), 0.05);
}

TEST(KalibrAprilGrid, ReadAsAnAprilTagGridItSaysKalibr) {
  const Target kalibr = KalibrBoard(6, 6, 80);
  const Canvas canvas = DrawKalibrBoard(kalibr, 1.0);
  const WarpedView v = Warp(canvas, kalibr, ViewOf(canvas, 20, 2e-4, 1e-4), 9);
  const GrayImage gray = ToGray(v.image);
  Target vstcal_grid = testing::AprilGrid6x4();
  vstcal_grid.rows = 6;
  const Detection d = DetectTarget(gray, vstcal_grid, DetectorOptions{});
  EXPECT_EQ(d.status, DetectionStatus::kRejected);
  EXPECT_NE(d.reason.find("Kalibr's aprilgrid"), std::string::npos) << d.reason;
  EXPECT_NE(d.reason.find("type to aprilgrid"), std::string::npos) << d.reason;
}

TEST(KalibrAprilGrid, AnAprilTagGridReadAsAnAprilgridSaysSo) {
  const Camera camera = testing::PinholeCamera(640, 480, 600);
  const Target t = testing::AprilGrid6x4();
  const testing::RenderedView view = testing::RenderTestView(camera, t, testing::TestViewPose(camera, t, 40, 0, 3), RenderOptions{}, 0);
  const Detection d = DetectTarget(view.image, KalibrBoard(4, 6, 30), DetectorOptions{});
  EXPECT_EQ(d.status, DetectionStatus::kRejected);
  EXPECT_NE(d.reason.find("type to apriltag-grid"), std::string::npos) << d.reason;
}

TEST(KalibrAprilGrid, NothingInABlankImage) {
  const Detection d = DetectTarget(GrayImage(320, 240, 128), KalibrBoard(), DetectorOptions{});
  EXPECT_EQ(d.status, DetectionStatus::kNotFound);
  EXPECT_NE(d.reason.find("two-cell black border of Kalibr's aprilgrid"), std::string::npos) << d.reason;
}

}  // namespace
}  // namespace vstcal
