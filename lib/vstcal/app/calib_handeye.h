// calib-handeye as a library call (docs/tools/calib-handeye.md): where the camera sits on the
// tracked headset, where the board is in the tracker's frame and the offset between the two
// clocks, from the board's corners in timed images and the tracker's log.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
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
  // A stereo rig (docs/math/handeye.md#rig): stereo@1 whose right_from_left is held and whose
  // cameras are the two that took `corners` (left) and `right_corners`; `camera` is then empty.
  // Each right view must pair with a left view, by name (left01 ↔ right01) or by time.
  std::string rig;
  std::string right_corners;
  // The tracker's poses taken as exact instead of weighed by their noise, estimated jointly
  // (HandEyeOptions::estimate_tracker_noise).
  bool tracker_exact = false;
  // δ's σ (and the whole covariance) also by a parametric bootstrap of this many replicates
  // (docs/math/handeye.md#delta-bootstrap; unset or 0: none): each replicate one more solve.
  // Replicate b draws from (seed, b) alone, so the file does not depend on `threads`.
  std::optional<int> bootstrap;
  uint64_t seed = 1;
  unsigned threads = 0;  // 0: every core
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
// another unit than declared, a view outside the log's span, a camera of another image size, a
// rig without the right camera's views or whose views cannot be paired);
// DegenerateError for motion about one axis or too few views.
Outcome SolveHandEyeFiles(const HandEyeRequest& request, const Provenance& provenance);

}  // namespace vstcal::app
