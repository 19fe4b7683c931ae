// calib-capture's flags, one function per subcommand, filling the library's requests
// (lib/vstcal/app/calib_capture.h). Kept apart from main.cc so that main stays a dispatcher.
#pragma once

#include <CLI/CLI.hpp>

#include "common/calibration_flags.h"
#include "vstcal/app/calib_capture.h"

namespace vstcal::tools {

struct TargetFlags {
  app::TargetRequest request;
  std::string type = "chessboard", unit = "mm";
  std::optional<double> marker_size, tag_gap, margin;
  static constexpr double kKalibrDefaultSpacing = 0.3;  // kalibr_create_target_pdf's default
  double tag_spacing = kKalibrDefaultSpacing;
  std::string paper;
  void Add(CLI::App* app);
  app::TargetRequest Finish();  // defaults that depend on other flags
};

struct DetectFlags {
  app::DetectCommand command;
  std::string finder = "classic+sector-based", refiner = "symmetry";
  bool quiet = false;
  void Add(CLI::App* app);
  app::DetectCommand Finish();
};

struct RenderFlags {
  app::RenderCommand command;
  std::string rig = "volume";
  void Add(CLI::App* app);
  app::RenderCommand Finish(CLI::App* app);  // refuses flags of the other rig
};

struct PlanFlags {
  app::PlanCommand command;
  CalibrationFlags calibration;  // --distortion, --skew parsed as calib-dlt and calib-tsai parse them
  std::string rig = "volume", image_size, format = "json";
  std::vector<std::vector<double>> test_points, pixel_points, depth_of_field;
  void Add(CLI::App* app);
  app::PlanCommand Finish(CLI::App* app);  // refuses flags of the other rig
};

}  // namespace vstcal::tools
