// Flags and output shared by the calibration tools (calib-dlt, calib-tsai): the refinement's
// options, where to report projection uncertainty, and writing the camera file with its solver
// blocks, atomically, plus the stderr summary.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/corner_input.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/formats/calib/calibration_io.h"

namespace vstcal::tools {

struct CalibrationFlags {
  std::string distortion = "k1,k2,p1,p2";
  bool skew = false;
  std::string loss = "none";
  double loss_scale_px = 1.0;
  int max_iterations = 100;
  std::vector<std::string> priors;  // NAME=VALUE,SIGMA per --prior
  std::vector<std::string> holds;   // lens parameter names, --hold (comma-separated, repeatable)

  std::optional<double> grid_depth;
  std::string grid_size = "16x9";
  // One list per occurrence of the flag (CLI11 2.1 would refill a std::array from the previous
  // item's values when one occurrence gives 4 numbers): checked to be X,Y,Z and U,V,DEPTH.
  std::vector<std::vector<double>> at_world;  // X,Y,Z per --uncertainty-at
  std::vector<std::vector<double>> at_pixel;  // U,V,DEPTH per --uncertainty-pixel

  std::string residuals;
  std::string undistort;  // --undistort DIR: check images
  bool quiet = false;

  bool reject_views = false;
  double view_false_alarm = 0.01;
  double corner_false_alarm = 0.01;

  CLI::Option* loss_scale_option = nullptr;  // set by AddRefinement: --loss-scale needs a robust --loss
  std::string lens_model;                     // --lens-model: empty = the Brown–Conrady model --distortion calls for
  CLI::Option* distortion_option = nullptr;   // set by AddRefinement: a fisheye's default terms are its own

  // Add the refinement and the uncertainty flags; return them so a tool can tie them to its own
  // switch (calib-dlt: they need --refine; calib-tsai: they exclude --no-refine).
  std::vector<CLI::Option*> AddRefinement(CLI::App& app);
  std::vector<CLI::Option*> AddUncertainty(CLI::App& app);
  void AddOutput(CLI::App& app);
  // --reject-views and its false-alarm probabilities (docs/tools/calib-tsai.md#reject-views).
  void AddRejection(CLI::App& app);
  ViewRejectionOptions Rejection() const;

  // Throws InputError for a flag that would do nothing (--loss-scale with --loss none), a malformed
  // --prior, or a --hold that contradicts another flag. The priors' parameters are checked against
  // the model by the refinement (ResolvePriors), before anything is written.
  RefineOptions Refinement() const;
  // The uncertainty flags checked against the data before any solve: throws InputError naming the
  // flag for malformed values, pixels outside the image, and world points for planar views.
  UncertaintyRequest Uncertainty(const Correspondences& corners) const;
};

// app::CalibrationOutcome, printed and written: a failed result throws its exit code and one-line
// message (no warnings printed then); else the warnings, OUTPUT (and --residuals) all or nothing,
// and unless --quiet the summary.
// `read` and `input`: the corners solved and where they came from (corner_input.h): a detection's
// files and --html's page are written with the camera; so are `extra`'s files (calib-tsai
// --split-halves' cameras), its summary after the camera's.
int FinishCalibration(const std::string& tool, const CornerInput& input, const ReadCorners& read, const std::string& output,
                      const CalibrationResult& result, const CalibrationOptions& options, const CalibrationFlags& flags,
                      const UncertaintyRequest& request, int argc, char** argv, app::Outcome extra = {});

}  // namespace vstcal::tools
