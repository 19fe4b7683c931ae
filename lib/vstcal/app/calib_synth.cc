#include "vstcal/app/calib_synth.h"

#include <cstdio>
#include <filesystem>

#include "vstcal/capture/render.h"
#include "vstcal/capture/render_scene.h"
#include "vstcal/capture/target.h"
#include "vstcal/capture/target_drawing.h"
#include "vstcal/capture/target_pattern.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/capture/target_io.h"

#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/handeye/handeye_io.h"
#include "vstcal/formats/handeye/pose_log_io.h"
#include "vstcal/core/option_name.h"

namespace vstcal::app {

std::string DefaultTruthPath(const std::string& output) {
  return std::filesystem::path(output).replace_extension(".truth.json").string();
}

namespace {

// The file beside `output` with its stem and another suffix ("rec.json" → "rec.poses.txt").
std::string Beside(const std::string& output, const std::string& suffix) {
  const std::filesystem::path p(output);
  return (p.parent_path() / (p.stem().string() + suffix)).string();
}

// The views as photographs of the chessboard whose inner corners are the grid (the target's frame
// is the grid's: corner (r, c) at (c, r)·spacing), rendered at their true poses with a little blur
// and sensor noise, named view-NN.png; board.target.json and times.txt (each image's camera time)
// beside them.
void AddHandEyeImages(const SynthRequest& request, const Camera& camera, const HandEyeRecording& r, const Provenance& provenance, Outcome* out) {
  CheckRenderSize(camera.image_size, request.camera_file);
  Target target;
  target.type = TargetType::kChessboard;
  target.length_unit = request.volume.length_unit;
  target.rows = request.volume.grid_rows;
  target.cols = request.volume.grid_cols;
  target.square_size = request.volume.spacing;
  target.margin = request.volume.spacing;
  if (const auto problem = CheckTarget(target)) throw InputError(VSTCAL_OPT("grid") ": the board it draws: " + problem->reason + "; " + problem->fix);
  const std::filesystem::path folder(request.images_folder);
  const PixelCornerRays rays(camera);
  const Pattern pattern = TargetPattern(target);
  RenderOptions options;
  options.blur_px = 0.7;
  options.noise = 2;
  options.seed = request.volume.seed;
  std::string times = "# calib-synth --rig handeye: each image's time on the camera's clock, s\n";  // house-plan: names a command
  for (size_t k = 0; k < r.views.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "view-%02zu.png", k);
    out->files.emplace_back(folder / name, EncodePng(RenderView(rays, pattern, r.camera_from_board[k], options, static_cast<uint32_t>(k))));
    char line[96];
    std::snprintf(line, sizeof line, "%s %.17g\n", name, r.views[k].time);
    times += line;
  }
  out->files.emplace_back(folder / "board.target.json", DumpJson(TargetToJson(target, provenance)));
  out->files.emplace_back(folder / "times.txt", times);
  out->folders.push_back(folder);
}

Outcome SynthesizeHandEyeFiles(const SynthRequest& request, const Camera& camera, const Provenance& provenance) {
  HandEyeSpec spec = request.handeye_spec;
  spec.grid_cols = request.volume.grid_cols;
  spec.grid_rows = request.volume.grid_rows;
  spec.spacing = request.volume.spacing;
  spec.noise_px = request.volume.noise_px;
  spec.seed = request.volume.seed;
  spec.views = request.views.num_views;
  spec.distance = request.views.distance;
  const HandEyeRecording r = SynthesizeHandEye(camera, spec);
  Correspondences corners;
  corners.camera = request.volume.camera_name;
  corners.image_size = camera.image_size;
  corners.length_unit = request.volume.length_unit;
  corners.rig = Rig::kPlanarViews;
  for (const TimedView& v : r.views) corners.views.push_back({v.name, "", std::nullopt, v.observations, v.time});
  CalibratedCamera truth;
  truth.camera = camera;
  truth.length_unit = corners.length_unit;
  truth.method = "synthetic";
  PoseLog log;
  log.length_unit = corners.length_unit;
  log.poses = r.log;
  HandEyeSolution truth_he;
  truth_he.hmd_from_camera = spec.hmd_from_camera;
  truth_he.tracker_from_board = spec.tracker_from_board;
  truth_he.time_offset = spec.time_offset;
  truth_he.views = corners.views.size();
  truth_he.corners = NumObservations(corners);
  const std::string poses = Beside(request.output, ".poses.txt"), handeye = Beside(request.output, ".handeye.truth.json");
  Outcome out;
  out.files = {{request.output, DumpJson(CorrespondencesToJson(corners, provenance))},
               {request.truth, DumpJson(CameraToJson(truth, provenance))},
               {poses, PoseLogToTum(InUnit(log, LengthUnit::kMetre))},
               {handeye, DumpJson(HandEyeToJson(truth_he, corners.length_unit, provenance))}};
  out.summary = "calib-synth: a hand-eye recording: " + std::to_string(corners.views.size()) + " timed views (" +
                std::to_string(NumObservations(corners)) + " corners), " + std::to_string(log.poses.size()) +
                " tracker reports; wrote " + request.output + ", " + request.truth + ", " + poses + " (TUM, m) and " + handeye;
  if (!request.images_folder.empty()) {
    AddHandEyeImages(request, camera, r, provenance, &out);
    out.summary += "; rendered the views into " + request.images_folder + " (with board.target.json and times.txt)";
  }
  return out;
}

}  // namespace

Outcome Synthesize(SynthRequest request, const Provenance& provenance) {
  if (request.truth.empty()) request.truth = DefaultTruthPath(request.output);
  const Camera camera =
      request.camera_file.empty() ? MakeSyntheticCamera(request.camera) : ReadCamera(request.camera_file).camera;
  const VolumeSpec& spec = request.volume;
  Outcome outcome;
  CalibratedCamera truth;
  Correspondences corners;
  if (request.handeye) return SynthesizeHandEyeFiles(request, camera, provenance);
  if (request.planar_views) {
    PlanarViewsSpec views = request.views;
    views.grid_cols = spec.grid_cols;
    views.grid_rows = spec.grid_rows;
    views.spacing = spec.spacing;
    views.noise_px = spec.noise_px;
    views.seed = spec.seed;
    views.length_unit = spec.length_unit;
    views.camera_name = spec.camera_name;
    const SyntheticViews synthetic = SynthesizePlanarViews(camera, views);
    for (const std::string& w : synthetic.warnings) outcome.warnings.push_back("calib-synth: warning: " + w);
    truth = PlanarViewsTruthCamera(camera, views, synthetic);
    corners = synthetic.correspondences;
  } else {
    const SyntheticVolume volume =
        SynthesizeVolume(camera, spec, request.test_points ? Seed000TestPoints(spec) : std::vector<TestPoint>{});
    truth = VolumeTruthCamera(camera, spec, volume);
    corners = volume.correspondences;
  }
  outcome.files = {{request.output, DumpJson(CorrespondencesToJson(corners, provenance))},
                   {request.truth, DumpJson(CameraToJson(truth, provenance))}};
  outcome.summary += "calib-synth: " + std::to_string(NumObservations(corners)) + " points in " +
                     std::to_string(corners.views.size()) + " views, " + std::to_string(corners.test_points.size()) +
                     " test points; wrote " + request.output + " and " + request.truth;
  return outcome;
}

}  // namespace vstcal::app
