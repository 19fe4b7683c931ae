#include "common/corner_input.h"

#include <filesystem>
#include <utility>

#include "common/progress.h"
#include "common/validators.h"
#include "vstcal/app/calib_capture.h"
#include "vstcal/app/reproj_report.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/correspondences_io.h"

namespace vstcal::tools {

void CornerInput::Add(CLI::App& app, const std::string& what) {
  app.add_option("INPUT", inputs,
                 "vstcal/correspondences@1 file (" + what + "); with --target: the images (files, folders, quoted globs)")
      ->required(false);
  app.add_option("--target", target, "find the corners in the images first, on this board (vstcal/target@1), as calib-capture detect does")
      ->check(kNonEmpty);
  app.add_option("--manifest", manifest, "with --target, a volume: vstcal/volume-manifest@1, each image with its plane_offset")
      ->check(kNonEmpty);
  app.add_option("--video", video, "with --target: a video file instead of images (planar views)")->check(kNonEmpty);
  app.add_option("--every", every, "with --video: keep every k-th frame")->check(kPositiveCount)->capture_default_str();
  app.add_option("--frames", frames, "with --video: frames to keep (0: the whole video)")->check(kCount);
  app.add_option("--threads", threads, "with --target: detection threads (0: all cores; the output does not depend on it)");
  app.add_option("--min-views", min_views, "with --target: fewer usable images is an error (exit code 3)")->check(kPositiveCount)->capture_default_str();
  app.add_flag("--skip-unreadable", skip_unreadable, "with --target: list unreadable images as rejected instead of stopping");
  app.add_option("--corners", corners, "with --target: also write the corners found (vstcal/correspondences@1)")->check(kNonEmpty);
  app.add_option("--overlay", overlay, "with --target: write each image with its corners drawn into this folder")->check(kNonEmpty);
  app.add_option("--html", html, "also write reproj-report's page of the camera (residuals on every view, σ's)")->check(kNonEmpty);
}

std::vector<std::string> CornerInput::Outputs() const { return {corners, html}; }

std::string CornerInput::Name() const {
  if (FromImages()) return "the corners found in the images";
  return inputs.empty() ? std::string() : inputs.front();
}

ReadCorners CornerInput::Read(const std::string& tool, bool quiet, int argc, char** argv) const {
  if (!FromImages()) {
    for (const auto& [flag, given] : {std::pair{"--manifest", !manifest.empty()}, {"--video", !video.empty()}, {"--corners", !corners.empty()},
                                      {"--overlay", !overlay.empty()}, {"--skip-unreadable", skip_unreadable},
                                      {"--min-views", min_views != 3}}) {
      if (given) throw InputError(std::string(flag) + ": applies to images; give the board with --target TARGET.json");
    }
    if (inputs.size() != 1) {
      throw InputError(inputs.empty() ? "INPUT: give the correspondences file, or --target TARGET.json and the images"
                                      : std::to_string(inputs.size()) + " inputs: give one correspondences file, or --target TARGET.json "
                                        "before images to find their corners first");
    }
    return {ReadCorrespondences(inputs.front()), {}};
  }
  app::DetectCommand command;
  command.tool = tool;
  command.target_file = target;
  command.images = inputs;
  command.manifest = manifest;
  command.video.file = video;
  command.video.every = every;
  command.video.max_frames = frames;
  command.detect.threads = threads;
  command.detect.skip_unreadable = skip_unreadable;
  command.detect.min_views = min_views;
  command.output = corners;
  command.overlay_folder = overlay;
  ProgressBar bar(tool + " (finding corners)", !quiet);
  app::DetectedCorners detected =
      app::DetectCorners(std::move(command), MakeProvenance(tool, argc, argv), [&](double f) { bar.Update(f); });
  return {std::move(detected.correspondences), std::move(detected.outcome)};
}

app::Outcome WithCornersAndPage(app::Outcome solved, const ReadCorners& read, const CornerInput& input) {
  app::Outcome out = std::move(solved);
  if (!input.html.empty()) {
    const auto& [camera_file, camera_json] = out.files.front();
    // A corners file written by this run or read by it names the page and is the folder of its
    // images' relative paths; corners kept in memory name their images as given.
    const std::string corners_file = input.FromImages() ? input.corners : input.inputs.front();
    const std::string folder = corners_file.empty() ? std::string() : std::filesystem::path(corners_file).parent_path().string();
    out.files.emplace_back(input.html, app::ReprojReportPageOf(camera_file.string(), camera_json, read.corners,
                                                               corners_file.empty() ? input.Name() : corners_file, folder));
    out.summary += "  wrote " + input.html + " (reproj-report's page: residuals on every view, the parameters ± σ)\n";
  }
  for (const auto& file : read.detected.files) out.files.push_back(file);
  out.folders.insert(out.folders.end(), read.detected.folders.begin(), read.detected.folders.end());
  out.summary = read.detected.summary + (read.detected.summary.empty() ? "" : "\n") + out.summary;
  return out;
}

}  // namespace vstcal::tools
