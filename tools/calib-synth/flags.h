// calib-synth's flags, parsed into an app::SynthRequest (the flag-to-field rules live here, so that
// the library's errors name fields).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "vstcal/app/calib_synth.h"

namespace vstcal::tools {

struct SynthFlags {
  app::SynthRequest request;
  std::string grid = "13x9", image_size, unit = "mm", rig = "volume";
  bool no_test_points = false, quiet = false;

  void Add(CLI::App& app);
  // Checks the flags that apply to one set-up only and parses the sizes and the unit.
  app::SynthRequest Finish(const CLI::App& app);
};

}  // namespace vstcal::tools
