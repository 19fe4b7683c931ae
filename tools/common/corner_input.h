// The solvers' input (calib-tsai, calib-dlt): a correspondences@1 file, or — with --target — the
// images themselves (files, folders, quoted globs, a --manifest for a volume, or a --video), whose
// corners are found first exactly as calib-capture detect finds them, and solved in the same run
// (docs/tools/calib-tsai.md#from-images). Also --html: reproj-report's page of the camera just
// solved, written with the camera, all or nothing.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "vstcal/app/outcome.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal::tools {

// What CornerInput::Read gives: the correspondences, and for images the detection's outcome.
struct ReadCorners {
  Correspondences corners;
  app::Outcome detected;  // empty unless --target
};

struct CornerInput {
  std::vector<std::string> inputs;  // the positional arguments
  std::string target, manifest, video, corners, overlay, html;
  int every = 1, frames = 0, threads = 0, min_views = 3;  // calib-capture detect's defaults
  bool skip_unreadable = false;

  // `what` describes the correspondences a tool takes ("rig \"volume\"").
  void Add(CLI::App& app, const std::string& what);
  // The files this run writes besides the camera (for DeclareOutputs).
  std::vector<std::string> Outputs() const;
  bool FromImages() const { return !target.empty(); }

  // The correspondences file read, or the images' corners detected (then `detected` holds the
  // --corners file, the overlays and the summary accounting for every image). Throws InputError
  // for flags that need --target without it, or a positional argument count that does not fit.
  ReadCorners Read(const std::string& tool, bool quiet, int argc, char** argv) const;
  // What names the correspondences in messages: the file read, or "the corners found in the images".
  std::string Name() const;
};

// The solver's outcome with the detection's files (written with it, all or nothing) and summary
// before its own, and — with --html — the page of the camera it holds (its first file).
app::Outcome WithCornersAndPage(app::Outcome solved, const ReadCorners& read, const CornerInput& input);

}  // namespace vstcal::tools
