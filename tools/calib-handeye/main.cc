// calib-handeye: the camera's place on the tracked headset, the board in the tracker's frame and
// the two clocks' offset, with their covariance (docs/tools/calib-handeye.md).
#include <iostream>

#include "common/run_tool.h"
#include "common/validators.h"
#include "vstcal/app/calib_handeye.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Estimates hmd_from_camera (where the camera sits on the tracked body), tracker_from_board and the offset "
      "between the tracker's and the camera's clocks, by maximum likelihood over the board corners of timed views "
      "(vstcal/correspondences@1, planar views with views[i].time) and the tracker's log (vstcal/poses@1 .json, or TUM "
      "text: timestamp tx ty tz qx qy qz qw), with their joint covariance. Output: vstcal/handeye@1.\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input, 3 degenerate motion (rotation about one axis, too "
      "few views).",
      "calib-handeye"};
  vstcal::app::HandEyeRequest request;
  app.add_option("CORNERS", request.corners, "the board's corners in timed views (vstcal/correspondences@1)")
      ->required()
      ->check(vstcal::tools::kNonEmpty);
  app.add_option("--poses", request.poses, "the tracker's log: tracker_from_hmd (vstcal/poses@1 .json, or TUM text)")
      ->required()
      ->check(vstcal::tools::kNonEmpty);
  app.add_option("--camera", request.camera, "the camera that took the views (vstcal/camera@1; its intrinsics are held)")
      ->required()
      ->check(vstcal::tools::kNonEmpty);
  app.add_option("--tum-unit", request.tum_unit, "length unit of a TUM log's translations")->capture_default_str();
  app.add_option("--max-time-offset", request.max_time_offset, "search the clocks' offset within ±this many seconds")
      ->capture_default_str();
  app.add_option("-o,--output", request.output, "the vstcal/handeye@1 file to write")->required()->check(vstcal::tools::kNonEmpty);
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "print only errors");
  return vstcal::tools::RunTool(app, argc, argv, [&] {
    vstcal::DeclareOutputs({request.output});
    const vstcal::app::Outcome outcome = vstcal::app::SolveHandEyeFiles(request, vstcal::MakeProvenance("calib-handeye", argc, argv));
    vstcal::app::WriteOutcome(outcome);
    if (!quiet) std::cerr << outcome.summary;
    return 0;
  });
}
