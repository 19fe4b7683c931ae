// calib-synth: synthetic calibration volumes with ground truth (docs/tools/calib-synth.md).
#include <iostream>

#include "common/run_tool.h"
#include "flags.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Writes synthetic correspondences (vstcal/correspondences@1) with the ground-truth camera (vstcal/camera@1, "
      "method \"synthetic\") beside them. --rig volume (default): a planar grid template moved along its normal "
      "from --near to --far every --interval, plus seed 000's five test points. --rig planar-views: a board shown at "
      "--views poses spread over the field of view. Gaussian pixel noise from a counter-based stream.\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input.",
      "calib-synth"};
  vstcal::tools::SynthFlags flags;
  flags.Add(app);
  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    app::SynthRequest request = flags.Finish(app);
    if (request.truth.empty()) request.truth = app::DefaultTruthPath(request.output);
    DeclareOutputs({request.output, request.truth});
    const app::Outcome outcome =
        app::Synthesize(request, MakeProvenance("calib-synth", argc, argv, request.volume.seed));
    for (const std::string& w : outcome.warnings) std::cerr << tools::ForUser(w) << "\n";
    app::WriteOutcome(outcome);
    if (!flags.quiet) std::cerr << tools::ForUser(outcome.summary) << "\n";
    return 0;
  });
}
