// calib-handeye's subcommands and their flags: solve (the camera on the headset, the board, the
// clocks' offset) and noise (the tracker's jitter from a static segment).
#pragma once

#include <CLI/CLI.hpp>

#include "vstcal/app/calib_handeye.h"

namespace vstcal::tools {

struct HandEyeFlags {
  app::HandEyeRequest solve;
  app::TrackerNoiseRequest noise;
  bool quiet = false;
  int bootstrap_replicates = 0;  // --bootstrap as given; solve.bootstrap stays unset when it is not
  CLI::App* solve_app = nullptr;
  CLI::App* noise_app = nullptr;

  void Add(CLI::App& app);
};

}  // namespace vstcal::tools
