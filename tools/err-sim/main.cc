// err-sim: Monte Carlo and sensitivity analysis of the seven VST error sources through the
// registration chain of seed 001 (docs/tools/err-sim.md).
#include <iostream>

#include "common/run_tool.h"
#include "err-sim/command_line.h"
#include "vstcal/files/input_protection.h"
#include "vstcal/app/outcome.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/pages/errsim_html.h"

int main(int argc, char** argv) {
  CLI::App app{"Propagates the seven VST error sources (tracker_alignment, tracking, camera_extrinsic, camera_intrinsic, "
               "rendering, display, virtual_object_alignment) through the registration chain of a stereo video see-through "
               "system: image misregistration (px), the 3-D misregistration the user sees and the misperception of where "
               "things are (Holloway's terms), each source's contribution and an error budget ranked for each.\n"
               "Exit codes: 0 ok, 1 internal error, 2 bad usage or input, 3 degenerate model (every sample of a test point undefined), "
               "4 a check failed (err-sim check).",
               "err-sim"};
  vstcal::tools::ErrSimCommandLine command_line(app);
  return vstcal::tools::RunTool(app, argc, argv, [&] {
    if (command_line.checking()) {
      vstcal::DeclareOutputs({command_line.junit()});
      const vstcal::app::Outcome outcome = command_line.Check(argc, argv);
      vstcal::app::WriteOutcome(outcome);
      if (!command_line.quiet()) std::cout << vstcal::tools::ForUser(outcome.stdout_text);
      return vstcal::app::ExitStatus(outcome);
    }
    vstcal::DeclareOutputs({command_line.output(), command_line.html()});
    const vstcal::app::ErrSimDocument outcome = command_line.Run(argc, argv);
    std::vector<std::pair<std::filesystem::path, std::string>> files = {{command_line.output(), outcome.Text()}};
    if (!command_line.html().empty()) files.emplace_back(command_line.html(), vstcal::ErrSimHtml(outcome.json));
    vstcal::WriteFilesAtomically(files);
    if (!command_line.quiet()) std::cerr << vstcal::tools::ForUser(outcome.text) << "  wrote " << command_line.output() << (command_line.html().empty() ? "" : " and " + command_line.html()) << "\n";
    return 0;
  });
}
