// calib-synth as a library call (docs/tools/calib-synth.md): synthetic correspondences with the
// ground-truth camera beside them, either a planar template moved through a volume (seed 000's
// set-up) or a board shown at poses spread over the field of view.
#pragma once

#include <string>

#include "vstcal/app/outcome.h"
#include "vstcal/capture/synthetic_camera.h"
#include "vstcal/capture/synthetic_views.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/handeye/synthetic.h"
#include "vstcal/json/provenance.h"

namespace vstcal::app {

struct SynthRequest {
  std::string output;  // correspondences@1
  std::string truth;   // camera@1; empty: output with the extension .truth.json
  // The camera: from a camera@1 file when given, else made from `camera`.
  std::string camera_file;
  SyntheticCameraSpec camera;
  bool planar_views = false;  // else a volume
  VolumeSpec volume;          // its grid, spacing, noise, seed, unit and camera name serve both set-ups
  bool test_points = true;    // volume: seed 000's five test points
  PlanarViewsSpec views;      // planar views: number, distance and tilt of the poses
  // A hand-eye recording instead (issue 22): a headset carrying the camera moved in front of the
  // board, the tracker's log beside the corners (OUTPUT's stem .poses.txt, TUM text in metres) and
  // the true X, Z and time offset (stem .handeye.truth.json, vstcal/handeye@1 without covariance).
  // Its grid, spacing, corner noise and seed are `volume`'s, its views and distance `views`'.
  bool handeye = false;
  HandEyeSpec handeye_spec;
  // Hand-eye: also the views as rendered images of the chessboard the grid is (one more square
  // each way, squares of `spacing`), with the board's target@1 and each image's time — the input
  // of calib-capture detect --times, so that the recording can be measured from photographs.
  std::string images_folder;
};

// The correspondences and the truth camera; the summary (no final newline) counts the points, views
// and test points; the warnings are the planar set-up's (views that lost corners outside the image).
Outcome Synthesize(SynthRequest request, const Provenance& provenance);

// The truth file's default name for a correspondences file.
std::string DefaultTruthPath(const std::string& output);

}  // namespace vstcal::app
