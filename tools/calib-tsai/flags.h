// calib-tsai's own flags (the refinement's and the uncertainty's are common/calibration_flags.h).
#pragma once

#include <array>
#include <string>

#include <CLI/CLI.hpp>

#include "common/calibration_flags.h"

namespace vstcal::tools {

struct TsaiFlags {
  CornerInput input;
  std::string output, variant = "auto", free_pp = "prior";
  std::array<double, 2> principal_point{};
  bool no_refine = false, split_halves = false;
  CalibrationOptions options;
  CalibrationFlags calibration;

  void Add(CLI::App& app);
  CalibrationOptions Options(const CLI::App& app);
  // Refuses the volume-only flags for planar views.
  void CheckRig(const CLI::App& app, const Correspondences& corners) const;
  // Refuses --sx when the points turned out not coplanar (it would not be used).
  void CheckUsed(const CLI::App& app, const CalibrationResult& result) const;
};

}  // namespace vstcal::tools
