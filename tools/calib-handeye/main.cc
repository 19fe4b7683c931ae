// calib-handeye: the camera's place on the tracked headset, the board in the tracker's frame and
// the two clocks' offset, with their covariance; the tracker's jitter (docs/tools/calib-handeye.md).
#include <cstdint>
#include <iostream>
#include <optional>

#include "common/run_tool.h"
#include "flags.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Measures the links of a VST headset's registration chain that no camera calibration measures: where the camera "
      "sits on the tracked body, where the tracker's frame is, the offset between the two clocks (solve), and the "
      "tracker's noise (noise).\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input, 3 degenerate motion (rotation about one axis, too "
      "few views) or a 'static' segment in which the headset moved.",
      "calib-handeye"};
  vstcal::tools::HandEyeFlags f;
  f.Add(app);
  return vstcal::tools::RunTool(app, argc, argv, [&] {
    const bool solving = app.got_subcommand(f.solve_app);
    vstcal::DeclareOutputs({solving ? f.solve.output : f.noise.output, solving ? f.solve.opencv : std::string()});
    // Only a bootstrap draws random numbers: the app keeps the seed in the provenance if one ran.
    const vstcal::Provenance provenance =
        vstcal::MakeProvenance("calib-handeye", argc, argv, solving ? std::optional<uint64_t>(f.solve.seed) : std::nullopt);
    const vstcal::app::Outcome outcome =
        solving ? vstcal::app::SolveHandEyeFiles(f.solve, provenance) : vstcal::app::MeasureTrackerNoise(f.noise, provenance);
    vstcal::app::WriteOutcome(outcome);
    if (!f.quiet) std::cerr << vstcal::tools::ForUser(outcome.summary);
    return 0;
  });
}
