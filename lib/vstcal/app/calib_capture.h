// What each calib-capture subcommand does, as library calls (docs/tools/calib-capture.md): the
// tool's main parses flags into these requests, calls one function and writes the files it
// returns with WriteOutcome. A C++ user gets the same files without the tool.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "vstcal/capture/synthetic_camera.h"
#include "vstcal/capture/detect_run.h"
#include "vstcal/capture/plan.h"
#include "vstcal/capture/render_scene.h"
#include "vstcal/app/outcome.h"
#include "vstcal/capture/paper.h"
#include "vstcal/capture/target.h"
#include "vstcal/json/provenance.h"

namespace vstcal::app {

// calib-capture target: OUTPUT.target.json, OUTPUT.svg and (dpi > 0) OUTPUT.png.
// With a paper, a target whose size (square_size, or tag_size) is 0 gets the largest size whose
// sheet fits on it, the lengths not in `given` following the size (paper.h); a target with a size
// that does not fit is refused with the size that would. Without a paper, a sheet larger than both
// A4 and Letter gets a warning naming the paper it needs.
struct TargetRequest {
  Target target;
  std::string output;  // path prefix, e.g. "board" or "prints/board"
  double dpi = 300;    // 0: no PNG
  std::optional<Paper> paper;
  TargetLengths given;  // with a paper: the lengths given outright
  // Kalibr's target YAML (formats/capture/kalibr_target.h): when set, the target's type, counts and
  // sizes (metres) come from it, `target` only lends its margin (given.margin) and the paper fit.
  std::string kalibr_file;
};
Outcome MakeTarget(const TargetRequest& request, const Provenance& provenance);

// calib-capture detect.
struct DetectCommand {
  std::string target_file;
  std::vector<std::string> images;  // files, folders (their images, sorted) or globs (sorted)
  std::string manifest;             // volume: a vstcal/volume-manifest@1 file instead of images
  std::string offset_pattern;       // volume: the plane offset read from each image's name
  VideoRequest video;               // frames instead of images (file, or camera_index ≥ 0)
  DetectRequest detect;             // target, target_file and rig are filled in here
  std::string output;
  std::string overlay_folder;       // a PNG per image with its corners drawn (images only)
  std::string tool = "calib-capture";  // names the summary's line
  std::string times_file;           // images: when each was taken (formats/capture/image_times.h)
  std::string times_unit = "s";     // the times file's unit: s, ms, us or ns
};
Outcome RunDetect(DetectCommand command, const Provenance& provenance, const Progress& progress = {});

// detect for a solver given images (calib-tsai, calib-dlt --target): the corners in memory, read
// back from the very text the correspondences file holds, so that solving them is solving the
// file; and the outcome — the correspondences file when command.output is given (else none), the
// overlays, the summary that accounts for every image.
struct DetectedCorners {
  Correspondences correspondences;
  Outcome outcome;
};
DetectedCorners DetectCorners(DetectCommand command, const Provenance& provenance, const Progress& progress = {});

// Files, folders and globs → image paths, in the order given, each folder and glob sorted by name.
// The overlays detect --overlay writes (<view>.overlay.png) are left out of folders and globs, and
// counted: corners drawn on a photograph are no new view of the board. Throws InputError for an
// argument that names nothing, a device or a pipe, an overlay named on its own, a folder without
// images, a glob that matches no file.
struct ImageArguments {
  std::vector<std::string> images;
  size_t overlays_left_out = 0;
};
ImageArguments ExpandImageArguments(const std::vector<std::string>& arguments);

// The file name detect --overlay gives the overlay of a view.
std::string OverlayFileName(const std::string& view);

// calib-capture render: DIR/<name>.png for every view, DIR/truth.json (the true corners),
// DIR/camera.truth.json (the camera and its poses) and, for a volume, DIR/manifest.json.
struct RenderCommand {
  std::string target_file;
  std::string camera_file;
  std::string output_folder;
  SceneSpec scene;
};
Outcome RunRender(const RenderCommand& command, const Provenance& provenance);

// calib-capture plan: OUTPUT, a vstcal/capture-plan@1 file (or its text form). The camera comes
// from camera_file, or else from `nominal` (image size and fx or hfov_deg, or focal_mm with
// pixel_pitch_um: fx = fy = 1000 · focal_mm / pitch_µm px). A volume's test points default to
// seed 000's five (default_test_points); pixels are predicted only where request.pixel_points asks.
struct PlanCommand {
  std::string target_file;
  std::string camera_file;
  SyntheticCameraSpec nominal;
  std::optional<double> focal_mm, pixel_pitch_um;
  PlanRequest request;  // camera and target are read into it here
  bool default_test_points = true;
  std::string output;
  bool text = false;
  // Two vstcal/capture-plan@1 files to put side by side instead of planning
  // (vstcal/capture-plan-comparison@1, or text).
  std::vector<std::string> compare;
};
Outcome RunPlan(PlanCommand command, const Provenance& provenance);

}  // namespace vstcal::app
