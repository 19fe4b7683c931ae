// calib-capture's flags, one function per subcommand, filling the library's requests
// (lib/vstcal/capture/commands.h). Kept apart from main.cc so that main stays a dispatcher.
#pragma once

#include <CLI/CLI.hpp>

#include "common/calibration_flags.h"
#include "vstcal/capture/commands.h"

namespace vstcal::tools {

struct TargetFlags {
  capture::TargetRequest request;
  std::string type = "chessboard", unit = "mm";
  std::optional<double> marker_size, tag_gap, margin;
  void Add(CLI::App* app);
  capture::TargetRequest Finish();  // defaults that depend on other flags
};

struct DetectFlags {
  capture::DetectCommand command;
  std::string finder = "classic+sector-based", refiner = "symmetry";
  bool quiet = false;
  void Add(CLI::App* app);
  capture::DetectCommand Finish();
};

struct RenderFlags {
  capture::RenderCommand command;
  std::string rig = "volume";
  void Add(CLI::App* app);
  capture::RenderCommand Finish(CLI::App* app);  // refuses flags of the other rig
};

struct PlanFlags {
  capture::PlanCommand command;
  CalibrationFlags calibration;  // --distortion, --skew parsed as calib-dlt and calib-tsai parse them
  std::string rig = "volume", image_size, format = "json";
  std::vector<std::vector<double>> test_points, pixel_points, depth_of_field;
  void Add(CLI::App* app);
  capture::PlanCommand Finish(CLI::App* app);  // refuses flags of the other rig
};

}  // namespace vstcal::tools
