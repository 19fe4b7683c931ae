// A chessboard partly outside the image: OpenCV's finders can return a full rows × cols grid that
// takes the board's outer edge (black squares against the white margin) for a row of corners when
// a real row is out of view. The refinement then drops that row — its points are not X-junctions —
// and the colour rule, seeing the grid one row off, numbers the rest turned by a half: every
// corner then has another corner's id. Found by calib-handeye on rendered photographs (view 22 of
// calib-synth --rig handeye, 167 px RMS). Such a view must be refused, never numbered wrongly.
#include <gtest/gtest.h>

#include "support/capture_scenes.h"
#include "vstcal/capture/detect.h"
#include "vstcal/capture/render.h"
#include "vstcal/capture/target_pattern.h"
#include "vstcal/handeye/synthetic.h"

namespace vstcal {
namespace {

TEST(DetectChessboard, AGridThatTookTheBoardsEdgeForARowIsRefused) {
  const Camera camera = Camera::FromK((Eigen::Matrix3d() << 600, 0, 319.5, 0, 600, 239.5, 0, 0, 1).finished(), ImageSize{640, 480});
  const HandEyeRecording recording = SynthesizeHandEye(camera, HandEyeSpec{});  // calib-synth --rig handeye's defaults
  Target target = testing::Chessboard9x6();
  target.square_size = target.margin = 30;  // calib-synth's grid: 30 mm
  RenderOptions options;
  options.blur_px = 0.7;
  options.noise = 2;
  const PixelCornerRays rays(camera);
  const Pattern pattern = TargetPattern(target);
  int found = 0, wrong = 0;
  // Views 20–24: 22 is the one found, with its neighbours (the whole recording takes tens of
  // seconds where the board is cut by the image's edge).
  for (size_t k = 20; k < 25; ++k) {
    testing::RenderedView view;
    view.image = RenderView(rays, pattern, recording.camera_from_board[k], options, static_cast<uint32_t>(k));
    view.camera_from_board = recording.camera_from_board[k];
    for (int id = 0; id < NumCorners(target); ++id) {
      const Eigen::Vector2d xy = CornerPosition(target, id);
      if (const auto q = camera.Project(recording.camera_from_board[k] * Eigen::Vector3d(xy.x(), xy.y(), 0))) {
        if (q->x() > -0.5 && q->y() > -0.5 && q->x() < 639.5 && q->y() < 479.5) view.truth[id] = *q;
      }
    }
    const Detection d = DetectTarget(view.image, target, DetectorOptions{});
    if (k == 22) {
      EXPECT_EQ(d.status, DetectionStatus::kRejected);
      EXPECT_NE(d.reason.find("grid off the board: an outer row"), std::string::npos) << d.reason;
    }
    if (d.status != DetectionStatus::kFound) continue;
    ++found;
    const testing::CornerErrors e = testing::CompareWithTruth(d, view);
    EXPECT_EQ(e.wrong_id, 0) << "view " << k << ": " << e.wrong_id << " corners numbered wrongly";
    wrong += e.wrong_id > 0;
  }
  EXPECT_GE(found, 1);
  EXPECT_EQ(wrong, 0);
}

}  // namespace
}  // namespace vstcal
