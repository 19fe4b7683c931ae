// calib-convert: a camera or a stereo rig between vstcal, OpenCV, mrcal, ROS and Kalibr files
// (docs/tools/calib-convert.md).
#include <iostream>

#include "common/run_tool.h"
#include "flags.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Converts a camera between vstcal/camera@1 (.json), OpenCV FileStorage YAML, ROS camera_info YAML, Kalibr "
      "camchain.yaml (.yaml, .yml: told apart by their keys) and mrcal .cameramodel files, and a stereo rig between "
      "vstcal/stereo@1, a Kalibr camchain of two cameras and a left and right ROS camera_info. Numbers are copied "
      "exactly. Lens models: none, radial-tangential, rational, as each format can hold them. What the output "
      "cannot hold is refused (skew; a model the format lacks) or said on stderr (a pose, a name).\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input.",
      "calib-convert"};
  vstcal::tools::ConvertFlags flags;
  flags.Add(app);
  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    DeclareOutputs({flags.output, flags.output_right});
    const app::Outcome outcome = flags.Convert(MakeProvenance("calib-convert", argc, argv));
    app::WriteOutcome(outcome);
    std::cerr << tools::ForUser(outcome.summary) << "\n";
    return 0;
  });
}
