// Detection on rendered images, scored against the rendered truth: chessboard accuracy beside
// OpenCV's classic detector with cornerSubPix on the same images, orientation (mirrored and turned
// detector orders, half-turn symmetric boards), ChArUco and AprilTag grids with partial views and
// mismatched target files, why libapriltag cannot read a Kalibr grid, and the rejections.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

extern "C" {
#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>
}

#include "support/capture_scenes.h"
#include "support/sanitizers.h"
#include "vstcal/capture/chessboard_orientation.h"
#include "vstcal/capture/detect.h"
#include "vstcal/capture/target_pattern.h"

namespace vstcal {
namespace {

using testing::AprilGrid6x4;
using testing::Charuco7x5;
using testing::Chessboard9x6;
using testing::CompareWithTruth;
using testing::CornerErrors;
using testing::RenderedView;
using testing::RenderTestView;
using testing::TestViewPose;

struct Score {
  double rms_px = 0;
  int found = 0, wrong_id = 0, views = 0;
};

// RMS over all corners of `views` views of `target` rendered with `options`.
Score ScoreDetector(const Camera& camera, const Target& target, double square_px, const RenderOptions& options,
                    const DetectorOptions& detector, int views, uint64_t seed = 1) {
  Score s;
  double sum2 = 0;
  int n = 0;
  for (int k = 0; k < views; ++k) {
    const RenderedView view = RenderTestView(camera, target, TestViewPose(camera, target, square_px, k, seed), options, k);
    const Detection d = DetectTarget(view.image, target, detector);
    ++s.views;
    if (d.status != DetectionStatus::kFound) continue;
    ++s.found;
    const CornerErrors e = CompareWithTruth(d, view);
    s.wrong_id += e.wrong_id;
    sum2 += e.rms_px * e.rms_px * e.matched;
    n += e.matched;
  }
  s.rms_px = n > 0 ? std::sqrt(sum2 / n) : 0;
  return s;
}

DetectorOptions With(CornerRefiner refiner, ChessboardFinder finder = ChessboardFinder::kClassicThenSectorBased) {
  DetectorOptions d;
  d.refiner = refiner;
  d.finder = finder;
  return d;
}

// The target: ≤ 0.05 px RMS on clean images with squares of 20 px and more, and no worse
// than OpenCV's classic detector refined by cornerSubPix on the same images (the best OpenCV peer;
// scripts/compare-detectors adds findChessboardCornersSB and mrgingham).
TEST(DetectChessboard, SubPixelAccuracyBeatsCornerSubPix) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  const Camera camera = testing::DistortedCamera(640, 480, 600);
  const Target t = Chessboard9x6();
  struct Condition {
    double square_px, blur, noise, limit;
  };
  for (const Condition& c : {Condition{20, 0, 0, 0.05}, Condition{40, 0, 0, 0.05}, Condition{30, 1.0, 2, 0.05}}) {
    RenderOptions options;
    options.blur_px = c.blur;
    options.noise = c.noise;
    const Score ours = ScoreDetector(camera, t, c.square_px, options, With(CornerRefiner::kSymmetry), 4);
    const Score peer = ScoreDetector(camera, t, c.square_px, options, With(CornerRefiner::kCornerSubPix, ChessboardFinder::kClassic), 4);
    SCOPED_TRACE("square " + std::to_string(c.square_px) + " px, blur " + std::to_string(c.blur) + ", noise " + std::to_string(c.noise));
    EXPECT_EQ(ours.found, 4);
    EXPECT_EQ(ours.wrong_id, 0);
    EXPECT_LT(ours.rms_px, c.limit);
    EXPECT_LE(ours.rms_px, peer.rms_px);
  }
}

// The classic detector misses some boards of 8 px squares; the sector-based one, tried where it
// fails, finds them.
TEST(DetectChessboard, SmallSquaresFallBackToTheSectorBasedFinder) {
  const Camera camera = testing::PinholeCamera(640, 480, 600);
  const Target t = Chessboard9x6();
  const Score classic = ScoreDetector(camera, t, 8, RenderOptions{}, With(CornerRefiner::kSymmetry, ChessboardFinder::kClassic), 6);
  const Score both = ScoreDetector(camera, t, 8, RenderOptions{}, With(CornerRefiner::kSymmetry), 6);
  EXPECT_LT(classic.found, 6);
  EXPECT_EQ(both.found, 6);
  EXPECT_EQ(both.wrong_id, 0);
  EXPECT_LT(both.rms_px, 0.05);
}

// A 9×6 board (rows + cols odd) has one numbering: upside down in the image it is still found
// with every id at its own corner.
TEST(DetectChessboard, AsymmetricBoardUpsideDownKeepsItsIds) {
  const Camera camera = testing::PinholeCamera(640, 480, 600);
  const Target t = Chessboard9x6();
  for (const double roll : {90.0, 180.0, 270.0}) {
    const RenderedView view = RenderTestView(camera, t, TestViewPose(camera, t, 30, 0, 5, roll), RenderOptions{}, 0);
    const Detection d = DetectTarget(view.image, t, With(CornerRefiner::kSymmetry));
    ASSERT_EQ(d.status, DetectionStatus::kFound) << roll;
    EXPECT_EQ(CompareWithTruth(d, view).wrong_id, 0) << roll;
  }
}

// Whatever order a detector returns the grid in (mirrored, turned), the numbering is the same.
TEST(ChessboardOrientation, AnyDetectorOrderGivesTheSameNumbering) {
  const Camera camera = testing::PinholeCamera(640, 480, 600);
  Target t = Chessboard9x6();
  t.rows = t.cols = 7;  // square: eight orders
  const RenderedView view = RenderTestView(camera, t, TestViewPose(camera, t, 30, 2, 5), RenderOptions{}, 0);
  const int n = 7;
  std::vector<Eigen::Vector2d> truth(n * n);
  for (int id = 0; id < n * n; ++id) truth[id] = view.truth.at(id);
  const GridOrientation reference = OrientChessboard(view.image, t, truth, false);
  ASSERT_TRUE(reference.problem.empty());
  for (int order = 0; order < 8; ++order) {
    std::vector<Eigen::Vector2d> shuffled(n * n);
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) {
        int rr = order & 1 ? n - 1 - r : r, cc = order & 2 ? n - 1 - c : c;
        if (order & 4) std::swap(rr, cc);
        shuffled[r * n + c] = truth[rr * n + cc];
      }
    }
    const GridOrientation o = OrientChessboard(view.image, t, shuffled, false);
    ASSERT_TRUE(o.problem.empty()) << order;
    for (int id = 0; id < n * n; ++id) EXPECT_EQ(shuffled[o.detected_index[id]], truth[reference.detected_index[id]]) << order;
  }
}

// An 8×6 board (rows + cols even) looks the same turned by half: its corner 0 is the one whose
// X axis points right in the image. Turned by 180° in the image, corner 0 is the true corner 47;
// with its rows near vertical, a volume (one world frame) refuses the view, planar views take it.
TEST(DetectChessboard, HalfTurnSymmetricBoardIsNumberedFromTheImageOrRefused) {
  const Camera camera = testing::PinholeCamera(640, 480, 600);
  Target t = Chessboard9x6();
  t.cols = 8;
  ASSERT_TRUE(IsHalfTurnSymmetric(t));
  const RenderedView upright = RenderTestView(camera, t, TestViewPose(camera, t, 30, 1, 5, 0), RenderOptions{}, 0);
  const RenderedView turned = RenderTestView(camera, t, TestViewPose(camera, t, 30, 1, 5, 180), RenderOptions{}, 0);
  const Detection a = DetectTarget(upright.image, t, With(CornerRefiner::kSymmetry));
  const Detection b = DetectTarget(turned.image, t, With(CornerRefiner::kSymmetry));
  ASSERT_EQ(a.status, DetectionStatus::kFound);
  ASSERT_EQ(b.status, DetectionStatus::kFound);
  EXPECT_LT((a.corners[0].pixel - upright.truth.at(0)).norm(), 0.1);
  EXPECT_LT((b.corners[0].pixel - turned.truth.at(47)).norm(), 0.1);

  DetectorOptions volume = With(CornerRefiner::kSymmetry);
  volume.refuse_ambiguous_orientation = true;
  EXPECT_EQ(DetectTarget(upright.image, t, volume).status, DetectionStatus::kFound);
  const RenderedView sideways = RenderTestView(camera, t, Rigid3d{RotationFromRotvec(Eigen::Vector3d(0, 0, DegToRad(88))),
                                                                  Eigen::Vector3d(62.5, -87.5, 600)},
                                               RenderOptions{}, 0);
  const Detection refused = DetectTarget(sideways.image, t, volume);
  EXPECT_EQ(refused.status, DetectionStatus::kRejected);
  EXPECT_NE(refused.reason.find("orientation ambiguous"), std::string::npos) << refused.reason;
  EXPECT_EQ(DetectTarget(sideways.image, t, With(CornerRefiner::kSymmetry)).status, DetectionStatus::kFound);
}

TEST(DetectCharuco, AccurateWithTheRightIds) {
  const Camera camera = testing::DistortedCamera(640, 480, 600);
  RenderOptions options;
  options.blur_px = 0.7;
  options.noise = 2;
  const Score s = ScoreDetector(camera, Charuco7x5(), 40, options, With(CornerRefiner::kSymmetry), 4);
  EXPECT_EQ(s.found, 4);
  EXPECT_EQ(s.wrong_id, 0);
  EXPECT_LT(s.rms_px, 0.05);
}

// Half the board outside the image: the corners that are in view, with their own ids.
TEST(DetectCharuco, PartialViewsKeepTheirIds) {
  const Camera camera = testing::PinholeCamera(640, 480, 600);
  const Target t = Charuco7x5();
  const Rigid3d pose{Eigen::Matrix3d::Identity(), Eigen::Vector3d(120, -60, 500)};  // columns beyond u = 640 leave the image
  const RenderedView view = RenderTestView(camera, t, pose, RenderOptions{}, 0);
  ASSERT_LT(view.truth.size(), static_cast<size_t>(NumCorners(t)));
  const Detection d = DetectTarget(view.image, t, With(CornerRefiner::kSymmetry));
  ASSERT_EQ(d.status, DetectionStatus::kFound) << d.reason;
  EXPECT_GE(d.corners.size(), 8u);
  EXPECT_LT(d.corners.size(), static_cast<size_t>(NumCorners(t)));
  EXPECT_EQ(CompareWithTruth(d, view).wrong_id, 0);
}

// A target file with rows and cols swapped puts the markers elsewhere: the view is refused, never
// numbered wrongly.
TEST(DetectCharuco, SwappedRowsAndColsAreRefused) {
  const Camera camera = testing::PinholeCamera(640, 480, 600);
  const Target t = Charuco7x5();
  const RenderedView view = RenderTestView(camera, t, TestViewPose(camera, t, 40, 0, 3), RenderOptions{}, 0);
  Target swapped = t;
  std::swap(swapped.rows, swapped.cols);
  const Detection d = DetectTarget(view.image, swapped, With(CornerRefiner::kSymmetry));
  EXPECT_NE(d.status, DetectionStatus::kFound);
  EXPECT_NE(d.reason.find("not where the target file puts them"), std::string::npos) << d.reason;
  EXPECT_NE(d.reason.find(" px off, tolerance "), std::string::npos) << d.reason;  // which markers, and by how much
}

TEST(DetectAprilGrid, EveryTagWithItsCorners) {
  const Camera camera = testing::DistortedCamera(640, 480, 600);
  RenderOptions options;
  options.blur_px = 0.7;
  options.noise = 2;
  const Score s = ScoreDetector(camera, AprilGrid6x4(), 40, options, With(CornerRefiner::kSymmetry), 4);
  EXPECT_EQ(s.found, 4);
  EXPECT_EQ(s.wrong_id, 0);
  EXPECT_LT(s.rms_px, 0.15);  // libapriltag's line fits: see docs/experiments/corners.md
}

TEST(DetectAprilGrid, SwappedRowsAndColsAreRefused) {
  const Camera camera = testing::PinholeCamera(640, 480, 600);
  const Target t = AprilGrid6x4();
  const RenderedView view = RenderTestView(camera, t, TestViewPose(camera, t, 40, 0, 3), RenderOptions{}, 0);
  Target swapped = t;
  std::swap(swapped.rows, swapped.cols);
  const Detection d = DetectTarget(view.image, swapped, With(CornerRefiner::kSymmetry));
  EXPECT_EQ(d.status, DetectionStatus::kRejected);
  EXPECT_NE(d.reason.find("not where the target file puts them"), std::string::npos) << d.reason;
}

int LibapriltagCount(const GrayImage& g) {
  apriltag_family_t* family = tag36h11_create();
  apriltag_detector_t* detector = apriltag_detector_create();
  detector->nthreads = 1;
  apriltag_detector_add_family(detector, family);
  image_u8_t image{g.width, g.height, g.width, const_cast<uint8_t*>(g.pixels.data())};
  zarray_t* found = apriltag_detector_detect(detector, &image);
  const int n = zarray_size(found);
  apriltag_detections_destroy(found);
  apriltag_detector_destroy(detector);
  tag36h11_destroy(family);
  return n;
}

// Kalibr's aprilgrid draws tag36h11 codes inside a black border two cells wide, with black squares
// between the tags' corners. libapriltag finds the outer edge of the black square and reads the
// 8 × 8 cells tag36h11 has from border to border (width_at_border = 8) — across Kalibr's 10 cells
// its sampling grid misses every data bit, so no tag decodes. vstcal's grid (1-cell border, white
// gaps) decodes every tag; the corner squares alone are not what breaks Kalibr's.
TEST(DetectAprilGrid, LibapriltagReadsVstcalsGridButNotKalibrs) {
  const Camera camera = testing::PinholeCamera(800, 600, 800);
  const Rigid3d pose{RotationFromRotvec(Eigen::Vector3d(0.2, 0.1, 0.05)), Eigen::Vector3d(-117, -78, 600)};
  RenderOptions options;
  options.blur_px = 0.7;
  options.noise = 1;
  const double tag = 30, gap = 9, pitch = tag + gap;
  auto grid = [&](bool two_cell_border, bool corner_squares) {
    std::vector<Rect> black;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 6; ++c) {
        const MarkerCells m = AprilTagCells("tag36h11", r * 6 + c);
        if (!two_cell_border) {
          AddMarkerCells(m, c * pitch, r * pitch, tag / 8, &black);
          continue;
        }
        MarkerCells kalibr;
        kalibr.side = 10;
        kalibr.black.assign(100, true);
        for (int i = 1; i < 7; ++i) {
          for (int j = 1; j < 7; ++j) kalibr.black[(i + 1) * 10 + j + 1] = m.black[i * 8 + j];
        }
        AddMarkerCells(kalibr, c * pitch, r * pitch, tag / 10, &black);
      }
    }
    if (corner_squares) {
      for (int r = 0; r <= 4; ++r) {
        for (int c = 0; c <= 6; ++c) black.push_back(Rect{c * pitch - gap, r * pitch - gap, c * pitch, r * pitch});
      }
    }
    const Pattern pattern(Rect{-gap - 10, -gap - 10, 6 * pitch + 10, 4 * pitch + 10}, std::move(black));
    return LibapriltagCount(RenderView(PixelCornerRays(camera), pattern, pose, options, 0));
  };
  EXPECT_EQ(grid(true, true), 0);    // Kalibr's aprilgrid
  EXPECT_EQ(grid(true, false), 0);   // its two-cell border alone
  EXPECT_GE(grid(false, true), 20);  // its corner squares alone: most tags still decode
  EXPECT_EQ(grid(false, false), 24);
}

TEST(Detect, RejectsBlurredViews) {
  const Camera camera = testing::PinholeCamera(640, 480, 600);
  const Target t = Chessboard9x6();
  RenderOptions options;
  options.blur_px = 4;
  const RenderedView view = RenderTestView(camera, t, TestViewPose(camera, t, 45, 0, 7), options, 0);
  const Detection d = DetectTarget(view.image, t, With(CornerRefiner::kSymmetry));
  ASSERT_EQ(d.status, DetectionStatus::kRejected);
  EXPECT_NE(d.reason.find("blurred"), std::string::npos) << d.reason;
  EXPECT_NEAR(d.blur_px, 4, 0.5);
}

TEST(Detect, NothingInABlankImage) {
  const GrayImage blank(320, 240, 128);
  for (const Target& t : {Chessboard9x6(), Charuco7x5(), AprilGrid6x4()}) {
    const Detection d = DetectTarget(blank, t, DetectorOptions{});
    EXPECT_EQ(d.status, DetectionStatus::kNotFound);
    EXPECT_FALSE(d.reason.empty());
  }
}

// A ChArUco view with only a corner of the board in the image: fewer corners than --min-corners.
TEST(Detect, RejectsTooFewCorners) {
  const Camera camera = testing::PinholeCamera(640, 480, 600);
  const Target t = Charuco7x5();
  const RenderedView view = RenderTestView(camera, t, Rigid3d{Eigen::Matrix3d::Identity(), Eigen::Vector3d(160, 110, 450)}, RenderOptions{}, 0);
  DetectorOptions options = With(CornerRefiner::kSymmetry);
  options.min_corners = 10;
  const Detection d = DetectTarget(view.image, t, options);
  ASSERT_EQ(d.status, DetectionStatus::kRejected) << d.reason;
  EXPECT_NE(d.reason.find("too few corners"), std::string::npos) << d.reason;
}

}  // namespace
}  // namespace vstcal
