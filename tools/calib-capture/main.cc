// calib-capture: from a printed target to correspondences — target, detect, render
// (docs/tools/calib-capture.md).
#include <iostream>

#include "common/progress.h"
#include "common/run_tool.h"
#include "flags.h"

int main(int argc, char** argv) {
  CLI::App app{"From a printed calibration target to vstcal/correspondences@1.\n"
               "  target  write a printable board (SVG at exact size, PNG at a DPI) and its vstcal/target@1 description\n"
               "  detect  find the board's corners in images, a video or a camera; account for every image\n"
               "  plan    predict each planned position's coverage and the calibration's σ's before capturing\n"
               "  render  draw the board through a camera@1 model at the poses of a volume or of planar views, with the truth\n"
               "Exit codes: 0 ok, 1 internal error, 2 bad usage or input, 3 too few usable images (degenerate data).",
               "calib-capture"};
  app.require_subcommand(1);
  vstcal::tools::TargetFlags target;
  target.Add(app.add_subcommand("target", "write a printable target and its vstcal/target@1 description"));
  vstcal::tools::DetectFlags detect;
  CLI::App* detect_app = app.add_subcommand("detect", "detect a target's corners and write vstcal/correspondences@1");
  detect.Add(detect_app);
  vstcal::tools::RenderFlags render;
  CLI::App* render_app = app.add_subcommand("render", "render a target through a camera model, with the true corners");
  render.Add(render_app);
  vstcal::tools::PlanFlags plan;
  CLI::App* plan_app = app.add_subcommand("plan", "predict a capture's image coverage and the calibration it will give");
  plan.Add(plan_app);

  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    const CLI::App* used = app.get_subcommands().front();
    const Provenance provenance = MakeProvenance("calib-capture", argc, argv,
                                                         used == render_app ? std::optional<uint64_t>(render.command.scene.render.seed)
                                                                            : std::nullopt);
    app::Outcome outputs;
    bool quiet = false;
    if (used == detect_app) {
      quiet = detect.quiet;
      tools::ProgressBar bar("calib-capture detect", !quiet);
      outputs = app::RunDetect(detect.Finish(), provenance, [&](double f) { bar.Update(f); });
    } else if (used == plan_app) {
      outputs = app::RunPlan(plan.Finish(plan_app), provenance);
    } else if (used == render_app) {
      outputs = app::RunRender(render.Finish(render_app), provenance);
    } else {
      outputs = app::MakeTarget(target.Finish(), provenance);
    }
    for (const std::string& w : outputs.warnings) std::cerr << tools::ForUser(w) << "\n";
    app::WriteOutcome(outputs);
    if (!quiet) std::cerr << tools::ForUser(outputs.summary) << "\n";
    return 0;
  });
}
