// Issue 25 item 1: ChArUco boards drawn by OpenCV's own generator (CharucoBoard::draw, in the test,
// not by vstcal), warped by cv::warpPerspective to views tilted up to ~50° with ~40 px squares,
// blurred and noisy — the tutorial's proportions (DICT_4X4_50, markers half the square) and the
// larger markers of DICT_5X5_100 at 0.7. vstcal must accept at least 95 % of the views OpenCV's
// interpolateCornersCharuco accepts, with no corner numbered wrongly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgproc.hpp>

#include "vstcal/capture/detect.h"
#include "vstcal/capture/target.h"
#include "vstcal/capture/target_drawing.h"

namespace vstcal {
namespace {

struct BoardCase {
  const char* dictionary;
  int dictionary_id;
  double marker_ratio;
  int first_id = 0;  // a board whose maker offset its ids (board.ids = first_id + k)
};

constexpr int kCols = 7, kRows = 5;         // inner corners; OpenCV's board is 8 × 6 squares
constexpr int kPxPerSquare = 100, kMargin = 50;  // the drawn board's resolution

// The homography from the drawn board image (pixel centres at integers) to a view: a pinhole
// camera (f 600, 640 × 480) looking at the board from `distance` squares, tilted about a random
// axis by up to `max_tilt_deg` and turned in its plane.
cv::Matx33d ViewHomography(std::mt19937_64& rng, double max_tilt_deg) {
  std::uniform_real_distribution<double> u(-1, 1);
  const double f = 600, square_mm = 1;
  const double tilt = max_tilt_deg * M_PI / 180 * std::abs(u(rng)), axis = M_PI * u(rng), roll = 0.5 * u(rng);
  cv::Matx33d R;
  cv::Rodrigues(cv::Vec3d(tilt * std::cos(axis), tilt * std::sin(axis), roll), R);
  // Board point (X, Y) in squares, centred; the camera ~15 squares away: squares of ~40 px.
  const cv::Vec3d t(0.3 * u(rng), 0.3 * u(rng), 15 * square_mm);
  const cv::Matx33d K(f, 0, 319.5, 0, f, 239.5, 0, 0, 1);
  const cv::Matx33d board_from_drawn(1.0 / kPxPerSquare, 0, -(kMargin - 0.5 + 0.5 * (kCols + 1) * kPxPerSquare) / kPxPerSquare,  //
                                     0, 1.0 / kPxPerSquare, -(kMargin - 0.5 + 0.5 * (kRows + 1) * kPxPerSquare) / kPxPerSquare,  //
                                     0, 0, 1);
  const cv::Matx33d camera_from_board(R(0, 0), R(0, 1), t[0], R(1, 0), R(1, 1), t[1], R(2, 0), R(2, 1), t[2]);
  return K * camera_from_board * board_from_drawn;
}

TEST(DetectCharuco, AcceptsWhatOpenCvAcceptsOnBoardsOpenCvDrew) {
  const BoardCase cases[] = {{"DICT_4X4_50", cv::aruco::DICT_4X4_50, 0.5},
                             {"DICT_5X5_100", cv::aruco::DICT_5X5_100, 0.7},
                             {"DICT_5X5_100", cv::aruco::DICT_5X5_100, 0.8},
                             {"DICT_6X6_250", cv::aruco::DICT_6X6_250, 0.9},
                             {"DICT_5X5_100", cv::aruco::DICT_5X5_100, 0.7, 40}};
  for (const BoardCase& c : cases) {
    const cv::Ptr<cv::aruco::Dictionary> dictionary = cv::aruco::getPredefinedDictionary(c.dictionary_id);
    const cv::Ptr<cv::aruco::CharucoBoard> board =
        cv::aruco::CharucoBoard::create(kCols + 1, kRows + 1, 1.0f, static_cast<float>(c.marker_ratio), dictionary);
    for (size_t k = 0; k < board->ids.size(); ++k) board->ids[k] = c.first_id + static_cast<int>(k);
    cv::Mat drawn;
    board->draw(cv::Size((kCols + 1) * kPxPerSquare + 2 * kMargin, (kRows + 1) * kPxPerSquare + 2 * kMargin), drawn, kMargin, 1);
    Target target;
    target.type = TargetType::kCharuco;
    target.rows = kRows;
    target.cols = kCols;
    target.square_size = 30;
    target.marker_size = 30 * c.marker_ratio;
    target.dictionary = c.dictionary;
    target.first_id = c.first_id;
    target.margin = 15;
    ASSERT_FALSE(CheckTarget(target).has_value()) << c.dictionary;

    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0, 2);
    int opencv_found = 0, ours_found = 0, both = 0, wrong = 0;
    size_t opencv_corners = 0, ours_corners = 0;
    double opencv_sum2 = 0, ours_sum2 = 0;
    // Inner corner `id` on the drawn board lies at the edge between squares: continuous coordinate
    // margin + (col + 1)·100, pixel centres at integers (−½); in the view through H.
    const auto truth = [](const cv::Matx33d& H, int id) {
      const cv::Vec3d p = H * cv::Vec3d(kMargin + (id % kCols + 1) * kPxPerSquare - 0.5, kMargin + (id / kCols + 1) * kPxPerSquare - 0.5, 1);
      return Eigen::Vector2d(p[0] / p[2], p[1] / p[2]);
    };
    constexpr int kViews = 20;
    for (int k = 0; k < kViews; ++k) {
      const cv::Matx33d H = ViewHomography(rng, 50);
      cv::Mat view;
      cv::warpPerspective(drawn, view, cv::Mat(H), cv::Size(640, 480), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(110));
      // Every fourth view has a hand over the board's middle: the corners around it must stay.
      if (k % 4 == 3) cv::rectangle(view, cv::Rect(260, 170, 120, 120), cv::Scalar(90), cv::FILLED);
      cv::GaussianBlur(view, view, cv::Size(0, 0), 0.7);
      for (int y = 0; y < view.rows; ++y) {
        for (int x = 0; x < view.cols; ++x) view.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(view.at<uint8_t>(y, x) + noise(rng));
      }
      // OpenCV: markers, then the corners between them (at least 4 to count as found).
      std::vector<std::vector<cv::Point2f>> marker_corners;
      std::vector<int> marker_ids, ids;
      std::vector<cv::Point2f> corners;
      cv::aruco::detectMarkers(view, dictionary, marker_corners, marker_ids);
      if (!marker_ids.empty()) cv::aruco::interpolateCornersCharuco(marker_corners, marker_ids, view, board, corners, ids);
      const bool opencv_ok = ids.size() >= 4;
      opencv_found += opencv_ok;
      opencv_corners += ids.size();
      for (size_t i = 0; i < ids.size(); ++i) opencv_sum2 += (truth(H, ids[i]) - Eigen::Vector2d(corners[i].x, corners[i].y)).squaredNorm();

      GrayImage image(view.cols, view.rows);
      for (int y = 0; y < view.rows; ++y) std::copy(view.ptr<uint8_t>(y), view.ptr<uint8_t>(y) + view.cols, &image.at(0, y));
      DetectorOptions options;
      options.min_corners = 4;  // as OpenCV's count above
      const Detection d = DetectTarget(image, target, options);
      const bool ours_ok = d.status == DetectionStatus::kFound;
      ours_found += ours_ok;
      both += ours_ok && opencv_ok;
      if (!ours_ok) {
        std::printf("%s view %d: %s (OpenCV: %zu corners)\n", c.dictionary, k, d.reason.c_str(), ids.size());
        continue;
      }
      ours_corners += d.corners.size();
      for (const DetectedCorner& corner : d.corners) {
        const double e2 = (truth(H, corner.id) - corner.pixel).squaredNorm();
        if (e2 > 4) ++wrong;
        ours_sum2 += e2;
      }
    }
    const double opencv_rms = std::sqrt(opencv_sum2 / static_cast<double>(opencv_corners)),
                 ours_rms = std::sqrt(ours_sum2 / static_cast<double>(ours_corners));
    std::printf("%s marker %.1f first id %d: OpenCV %d views (%zu corners, %.3f px RMS), vstcal %d views (%zu corners, %.3f px RMS), both %d, wrong %d\n",
                c.dictionary, c.marker_ratio, c.first_id, opencv_found, opencv_corners, opencv_rms, ours_found, ours_corners, ours_rms, both, wrong);
    // Occluded corners are not counted against either: each keeps what it can see.
    EXPECT_GE(ours_corners, opencv_corners * 95 / 100) << c.dictionary;
    EXPECT_LT(ours_rms, opencv_rms) << c.dictionary;
    ::testing::Test::RecordProperty(std::string(c.dictionary) + " opencv_views", opencv_found);
    ::testing::Test::RecordProperty(std::string(c.dictionary) + " vstcal_views", ours_found);
    EXPECT_GE(both, static_cast<int>(std::ceil(0.95 * opencv_found))) << c.dictionary;
    EXPECT_EQ(wrong, 0) << c.dictionary;
  }
}

// vstcal draws a board with offset ids as OpenCV reads it: every marker OpenCV decodes on vstcal's
// print has the id first_id + k of the marker vstcal put there.
TEST(DetectCharuco, OffsetIdsAreDrawnAsOpenCvReadsThem) {
  Target t;
  t.type = TargetType::kCharuco;
  t.rows = kRows;
  t.cols = kCols;
  t.square_size = 30;
  t.marker_size = 21;
  t.dictionary = "DICT_5X5_100";
  t.first_id = 40;
  t.margin = 30;
  ASSERT_FALSE(CheckTarget(t).has_value());
  const GrayImage drawn = RasterizeTarget(t, 101.6);  // 4 px a millimetre
  const cv::Mat image(drawn.height, drawn.width, CV_8U, const_cast<uint8_t*>(drawn.pixels.data()));
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(image, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_5X5_100), corners, ids);
  const std::vector<Quad> quads = MarkerQuads(t);
  ASSERT_EQ(ids.size(), quads.size());
  const Rect sheet = SheetExtent(t);
  for (size_t k = 0; k < ids.size(); ++k) {
    const int index = ids[k] - t.first_id;
    ASSERT_GE(index, 0);
    ASSERT_LT(index, static_cast<int>(quads.size()));
    // The decoded marker's first corner is the quad's top-left one, at 4 px a unit from the sheet's corner.
    const Eigen::Vector2d expected = 4 * (quads[static_cast<size_t>(index)][0] - Eigen::Vector2d(sheet.x0, sheet.y0));
    EXPECT_LT((Eigen::Vector2d(corners[k][0].x, corners[k][0].y) - expected).norm(), 2.0) << ids[k];
  }
  // Read back with first_id 0 (ids 0 … 23), the board's markers are another board's: none of its.
  Target zero = t;
  zero.first_id = 0;
  const Detection d = DetectTarget(drawn, zero, DetectorOptions{});
  EXPECT_NE(d.status, DetectionStatus::kFound);
}


// Boards OpenCV drew before 4.6 ("legacy"): with an even number of square rows the top-left square
// is white. Bookworm's OpenCV 4.6 cannot draw them (CharucoBoard::setLegacyPattern is OpenCV 4.8's),
// so the test draws one by the rule of 4.8's createCharucoBoard with legacyPattern and an even row
// count — square (x, y) black where (y + 1) % 2 == x % 2, every other square holding the next marker
// in row-major order — with OpenCV's own drawMarker, independently of vstcal's IsBlackSquare and
// MarkerQuads. 8 × 6 squares (kCols + 1, kRows + 1): an even number of rows.
cv::Mat DrawLegacyBoard(const cv::Ptr<cv::aruco::Dictionary>& dictionary, int marker_px, std::vector<cv::Point>* marker_squares) {
  const int squares_x = kCols + 1, squares_y = kRows + 1, inset = (kPxPerSquare - marker_px) / 2;
  cv::Mat drawn(squares_y * kPxPerSquare + 2 * kMargin, squares_x * kPxPerSquare + 2 * kMargin, CV_8U, cv::Scalar(255));
  int id = 0;
  for (int y = 0; y < squares_y; ++y) {
    for (int x = 0; x < squares_x; ++x) {
      const cv::Rect square(kMargin + x * kPxPerSquare, kMargin + y * kPxPerSquare, kPxPerSquare, kPxPerSquare);
      if ((y + 1) % 2 == x % 2) {
        drawn(square).setTo(0);
        continue;
      }
      cv::Mat marker;
      cv::aruco::drawMarker(dictionary, id++, marker_px, marker, 1);
      marker.copyTo(drawn(cv::Rect(square.x + inset, square.y + inset, marker_px, marker_px)));
      marker_squares->emplace_back(x, y);
    }
  }
  return drawn;
}

Target LegacyTestTarget(bool legacy) {
  Target t;
  t.type = TargetType::kCharuco;
  t.rows = kRows;
  t.cols = kCols;
  t.square_size = 30;
  t.marker_size = 21;
  t.dictionary = "DICT_5X5_100";
  t.margin = 15;
  t.legacy = legacy;
  return t;
}

GrayImage WarpLegacyTestView(const cv::Mat& drawn, const cv::Matx33d& H, std::mt19937_64& rng) {
  cv::Mat view;
  cv::warpPerspective(drawn, view, cv::Mat(H), cv::Size(640, 480), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(110));
  cv::GaussianBlur(view, view, cv::Size(0, 0), 0.7);
  std::normal_distribution<double> noise(0, 2);
  GrayImage image(view.cols, view.rows);
  for (int y = 0; y < view.rows; ++y) {
    for (int x = 0; x < view.cols; ++x) image.at(x, y) = cv::saturate_cast<uint8_t>(view.at<uint8_t>(y, x) + noise(rng));
  }
  return image;
}

TEST(DetectCharuco, LegacyBoardsAreReadAndTheWrongPatternNamed) {
  const cv::Ptr<cv::aruco::Dictionary> dictionary = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_5X5_100);
  std::vector<cv::Point> marker_squares;
  const cv::Mat drawn = DrawLegacyBoard(dictionary, 70, &marker_squares);
  const Target legacy = LegacyTestTarget(true), current = LegacyTestTarget(false);
  ASSERT_FALSE(CheckTarget(legacy).has_value());
  std::mt19937_64 rng(11);
  int found = 0, wrong = 0, corners = 0;
  double sum2 = 0;
  for (int k = 0; k < 12; ++k) {
    const cv::Matx33d H = ViewHomography(rng, 50);
    const GrayImage image = WarpLegacyTestView(drawn, H, rng);
    DetectorOptions options;
    options.min_corners = 4;
    const Detection d = DetectTarget(image, legacy, options);
    if (d.status == DetectionStatus::kFound) {
      ++found;
      for (const DetectedCorner& c : d.corners) {
        const cv::Vec3d p = H * cv::Vec3d(kMargin + (c.id % kCols + 1) * kPxPerSquare - 0.5, kMargin + (c.id / kCols + 1) * kPxPerSquare - 0.5, 1);
        const double e2 = (Eigen::Vector2d(p[0] / p[2], p[1] / p[2]) - c.pixel).squaredNorm();
        wrong += e2 > 4;
        sum2 += e2;
        ++corners;
      }
    } else {
      std::printf("legacy view %d: %s\n", k, d.reason.c_str());
    }
    // Read as OpenCV's current pattern, the board is refused, naming the legacy field as the fix.
    const Detection as_current = DetectTarget(image, current, options);
    EXPECT_EQ(as_current.status, DetectionStatus::kRejected) << k;
    EXPECT_EQ(as_current.reason.rfind("pattern mismatch: the markers sit where OpenCV's legacy ChArUco pattern puts them", 0), 0u) << as_current.reason;
    EXPECT_NE(as_current.reason.find("set the target's legacy to true"), std::string::npos) << as_current.reason;
    EXPECT_EQ(as_current.reason.find("rows, cols"), std::string::npos) << as_current.reason;
  }
  const double rms = std::sqrt(sum2 / std::max(corners, 1));
  std::printf("legacy DICT_5X5_100 marker 0.7: vstcal %d of 12 views, %d corners, %.3f px RMS, wrong %d\n", found, corners, rms, wrong);
  EXPECT_GE(found, 11);
  EXPECT_EQ(wrong, 0);
  EXPECT_LT(rms, 0.15);  // as the current pattern's boards above (≈ 0.07 px, mostly the warp's aliasing)

  // And the reverse: a board OpenCV 4.6 drew (its current pattern) read as legacy.
  const cv::Ptr<cv::aruco::CharucoBoard> board = cv::aruco::CharucoBoard::create(kCols + 1, kRows + 1, 1.0f, 0.7f, dictionary);
  cv::Mat drawn_current;
  board->draw(cv::Size((kCols + 1) * kPxPerSquare + 2 * kMargin, (kRows + 1) * kPxPerSquare + 2 * kMargin), drawn_current, kMargin, 1);
  const Detection as_legacy = DetectTarget(WarpLegacyTestView(drawn_current, ViewHomography(rng, 30), rng), legacy, DetectorOptions{});
  EXPECT_EQ(as_legacy.status, DetectionStatus::kRejected);
  EXPECT_NE(as_legacy.reason.find("OpenCV's current ChArUco pattern"), std::string::npos) << as_legacy.reason;
  EXPECT_NE(as_legacy.reason.find("set the target's legacy to false"), std::string::npos) << as_legacy.reason;

  // vstcal prints the legacy board as the rule above: every marker OpenCV decodes on vstcal's
  // drawing sits in the square the rule gives its id.
  const GrayImage print = RasterizeTarget(legacy, 101.6);  // 4 px a millimetre: squares of 120 px
  const cv::Mat image(print.height, print.width, CV_8U, const_cast<uint8_t*>(print.pixels.data()));
  std::vector<std::vector<cv::Point2f>> marker_corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(image, dictionary, marker_corners, ids);
  ASSERT_EQ(ids.size(), marker_squares.size());
  for (size_t k = 0; k < ids.size(); ++k) {
    const cv::Point2f centre = 0.25f * (marker_corners[k][0] + marker_corners[k][1] + marker_corners[k][2] + marker_corners[k][3]);
    const int x = static_cast<int>(std::floor((centre.x / 4 - legacy.margin) / legacy.square_size));
    const int y = static_cast<int>(std::floor((centre.y / 4 - legacy.margin) / legacy.square_size));
    EXPECT_EQ(cv::Point(x, y), marker_squares[static_cast<size_t>(ids[k])]) << ids[k];
  }
}

}  // namespace
}  // namespace vstcal
