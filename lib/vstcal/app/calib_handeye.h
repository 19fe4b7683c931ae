// calib-handeye as a library call (docs/tools/calib-handeye.md): where the camera sits on the
// tracked headset, where the board is in the tracker's frame and the offset between the two
// clocks, from the board's corners in timed images and the tracker's log.
#pragma once

#include <string>

#include "vstcal/app/outcome.h"
#include "vstcal/json/provenance.h"

namespace vstcal::app {

struct HandEyeRequest {
  std::string corners;   // correspondences@1, planar views, each with its time
  std::string poses;     // poses@1 (.json) or TUM text
  std::string camera;    // camera@1: the intrinsics (held fixed)
  std::string tum_unit = "m";  // the TUM log's length unit
  double max_time_offset = 0.2;  // s
  std::string output;    // handeye@1
  std::string opencv;    // the same as OpenCV YAML (HandEyeOpenCvYaml); empty: none
  bool keep_all_views = false;  // no bad-frame test (HandEyeOptions::rejection)
};

// calib-handeye noise: the tracker's jitter from a static segment of its log.
struct TrackerNoiseRequest {
  std::string poses;
  std::string tum_unit = "m";
  double from = 0, to = 0;      // s, the tracker's clock
  double max_motion = 10;       // mm: farther from the mean is a headset that moved
  std::string output;           // tracker-noise@1; empty: the summary only
};
Outcome MeasureTrackerNoise(const TrackerNoiseRequest& request, const Provenance& provenance);

// InputError naming the file and field for every bad input (views without a time, a log in
// another unit than declared, a view outside the log's span, a camera of another image size);
// DegenerateError for motion about one axis or too few views.
Outcome SolveHandEyeFiles(const HandEyeRequest& request, const Provenance& provenance);

}  // namespace vstcal::app
