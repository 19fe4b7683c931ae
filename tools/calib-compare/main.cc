// calib-compare: how far apart two cameras are, and whether that is within a user's bounds
// (docs/tools/calib-compare.md).
#include <iostream>

#include "common/run_tool.h"
#include "common/validators.h"
#include "vstcal/app/calib_compare.h"
#include "vstcal/app/outcome.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Compares two vstcal/camera@1 files, REFERENCE (e.g. ground truth) and OTHER (e.g. an estimate): "
      "differences of K, of the pose, and the pixel disagreement over a 9x9 grid of the image at a depth; "
      "optionally checks the disagreement against bounds (for CI).\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input, 4 a check failed (--max-px, --max-sigma, --cross-validate).",
      "calib-compare"};
  vstcal::app::CompareRequest request;
  app.add_option("REFERENCE", request.reference, "camera@1 file taken as reference")->required();
  app.add_option("OTHER", request.other, "camera@1 file compared with it")->required();
  app.add_option("--test-points", request.test_points,
                 "also compare the projections of this correspondences file's test points (registration error)");
  app.add_option("--depth", request.depth, "depth of the comparison grid (length unit; default: world origin's depth)")
      ->check(vstcal::tools::kPositiveFinite);
  app.add_option("--max-px", request.max_px,
                 "fail (exit code 4) when the cameras disagree by more than this many px at a grid or test point");
  app.add_option("--max-sigma", request.max_sigma,
                 "fail (exit code 4) when they disagree by more than this many σ of their summed projection "
                 "covariances (both files need a covariance)");
  app.add_flag("--cross-validate", request.cross_validate,
               "two calibrations of one camera from disjoint views (calib-tsai --split-halves): do they agree within "
               "their uncertainty, region by region? (exit code 4 when not; both files need a covariance)");
  app.add_option("--junit", request.junit, "write the checks' verdicts as JUnit XML to this file (for CI)");
  return vstcal::tools::RunTool(app, argc, argv, [&] {
    vstcal::DeclareOutputs({request.junit});
    const vstcal::app::Outcome outcome = vstcal::app::Compare(request);
    vstcal::tools::PrintToStdout(vstcal::tools::ForUser(outcome.stdout_text));
    vstcal::app::WriteOutcome(outcome);
    return vstcal::app::ExitStatus(outcome);
  });
}
