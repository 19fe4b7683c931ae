// calib-stereo's subcommands: each adds its flags to the app and returns what runs it — the
// conversion of the parsed flags into one library request (vstcal/app/calib_stereo.h).
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

#include "vstcal/json/provenance.h"
#include "vstcal/app/calib_stereo.h"

namespace vstcal::tools {

struct Subcommand {
  CLI::App* app = nullptr;
  std::function<app::Outcome(const Provenance&)> run;
};

Subcommand AddSolve(CLI::App& parent);
Subcommand AddAssemble(CLI::App& parent);
Subcommand AddExport(CLI::App& parent);
Subcommand AddSimulate(CLI::App& parent);
Subcommand AddRegister(CLI::App& parent);
Subcommand AddPlan(CLI::App& parent);

}  // namespace vstcal::tools
