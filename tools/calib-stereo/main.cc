// calib-stereo: stereo rigs — solve, assemble, export to OpenCV and mrcal, binocular registration and
// stereo display planning (docs/tools/calib-stereo.md).
#include <iostream>
#include <sstream>
#include <string>

#include "calib-stereo/subcommands.h"
#include "common/run_tool.h"
#include "vstcal/json/json_writer.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Stereo rigs (vstcal/stereo@1: two cameras and right_from_left): solve one from both cameras' views of a target, "
      "assemble one from two calibrated cameras, "
      "export it to OpenCV's stereo YAML (R, T, E, F, rectification) and to two mrcal .cameramodel files, register "
      "a tracked sequence binocularly (seed 000 §4.3), and plan a stereo display (seed 000 Eq. 3-6, seed 001 §4.6).\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input, 3 degenerate data.",
      "calib-stereo"};
  app.require_subcommand(1);
  const vstcal::tools::Subcommand subcommands[] = {vstcal::tools::AddSolve(app), vstcal::tools::AddAssemble(app), vstcal::tools::AddExport(app),
                                                   vstcal::tools::AddSimulate(app), vstcal::tools::AddRegister(app),
                                                   vstcal::tools::AddPlan(app)};
  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    for (const tools::Subcommand& s : subcommands) {
      if (!s.app->parsed()) continue;
      // Only `simulate` draws random numbers: its seed goes into the provenance.
      const CLI::Option* seed = s.app->get_option_no_throw("--seed");
      const Provenance provenance = MakeProvenance(
          "calib-stereo", argc, argv, seed ? std::optional(seed->as<uint64_t>()) : std::nullopt);
      const app::Outcome outcome = s.run(provenance);
      app::WriteOutcome(outcome);
      // Every line a note gets the tool's name, as every tool's warnings do.
      std::istringstream lines(tools::ForUser(outcome.summary));
      for (std::string line; std::getline(lines, line);) std::cerr << (line.rfind("note: ", 0) == 0 ? "calib-stereo: " : "") << line << "\n";
      for (const auto& [path, text] : outcome.files) std::cerr << "calib-stereo: wrote " << path.string() << "\n";
    }
    return 0;
  });
}
