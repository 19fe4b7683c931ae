// What each calib-stereo subcommand does, as library calls (docs/tools/calib-stereo.md): the tool's
// main parses flags into one of these requests, calls it and writes the returned files all or
// nothing; none of them writes over one of its inputs (InputError). A C++ user gets the same
// results without the tool.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "vstcal/app/outcome.h"
#include "vstcal/core/units.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/json/provenance.h"
#include "vstcal/stereo/display_plan.h"
#include "vstcal/stereo/rectify.h"
#include "vstcal/stereo/registration.h"
#include "vstcal/calib/stereo_solve.h"
#include "vstcal/stereo/synthetic_tracks.h"

namespace vstcal::app {

// assemble: a rig from two camera files (vstcal/camera@1, OpenCV YAML or mrcal .cameramodel, by
// extension) and right_from_left, given or derived from the cameras' poses in one frame (a mrcal
// camera without extrinsics is at its reference).
struct AssembleRequest {
  std::string left, right, output;
  std::optional<Rigid3d> right_from_left;  // translation in length_unit
  std::optional<LengthUnit> length_unit;   // of right_from_left; of .cameramodel and OpenCV YAML inputs
  std::optional<RectifyOptions> rectify;
};
Outcome Assemble(const AssembleRequest& request, const Provenance& provenance);

// solve: a rig from two correspondences@1 files of the same target poses (vstcal/calib/stereo_solve.h).
// A camera file (any format assemble reads) gives a camera's start and, held, its intrinsics.
struct SolveRequest {
  std::string left, right, output;
  std::string left_camera, right_camera;  // empty: none
  StereoSolveOptions options;
  std::optional<RectifyOptions> rectify;
  // Check images: every view pair both files name images for, rectified side by side with
  // epipolar lines (RectifiedPairImage; the rig's rectification, else OpenCV's default one), as
  // FOLDER/<view key>.rectified.png; empty: none.
  std::string undistort_folder;
  // Neither options.calibration.refinement's lens model nor its terms were chosen by the user: a
  // given camera (left_camera, right_camera) of another family than the default terms' model (a
  // fisheye) then sets both, its own terms estimated (docs/tools/calib-stereo.md).
  bool lens_model_from_cameras = false;
};
Outcome Solve(const SolveRequest& request, const Provenance& provenance);

// export: the rig as OpenCV stereo YAML and/or two mrcal .cameramodel files (at least one).
struct ExportRequest {
  std::string rig;
  std::string opencv;                      // empty: not written
  std::string mrcal_left, mrcal_right;     // both or neither
  std::optional<RectifyOptions> rectify;   // computed for the YAML (replaces the rig's own)
  std::optional<LengthUnit> mrcal_length_unit;
};
Outcome Export(const ExportRequest& request, const Provenance& provenance);

// simulate: synthetic tracks with known truth for a rig.
struct SimulateRequest {
  std::string rig, output;
  SyntheticTracksSpec spec;
};
Outcome Simulate(const SimulateRequest& request, const Provenance& provenance);

// register: binocular registration of every frame of a tracks file.
struct RegisterRequest {
  std::string rig, tracks, output;
  RegistrationOptions options;
};
Outcome Register(const RegisterRequest& request, const Provenance& provenance);

// plan: stereo display planning, from flags or with the baseline, focal length and capture width of a rig.
struct DisplayPlanRequest {
  std::string rig;  // empty: none
  DisplayPlanInput input;
  LengthUnit length_unit = LengthUnit::kMillimetre;  // of the flags' lengths (the rig's when a rig is given)
  std::string output;
};
Outcome Plan(const DisplayPlanRequest& request, const Provenance& provenance);

}  // namespace vstcal::app
