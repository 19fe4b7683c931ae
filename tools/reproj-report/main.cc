// reproj-report: reprojection and registration-error report of cameras against correspondences
// (docs/tools/reproj-report.md).
#include <cstdio>

#include "common/run_tool.h"
#include "common/validators.h"
#include "vstcal/app/reproj_report.h"
#include "vstcal/core/error.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Reports how well one or more cameras reproject a set of correspondences, and what that means in space: "
      "residuals per point, per view, per image cell and overall (mean, RMS, median, p95, max); the lateral "
      "error at each point's depth and the angular error; test points inside vs outside the convex hull of the "
      "calibration points; residuals normalized by a camera's own covariance; several cameras side by side with "
      "their differences (the first is the reference).\n"
      "With a stereo rig: the 3-D error of the points both cameras saw, triangulated through the rig, per axis in the "
      "left camera's frame and as Holloway's linear, lateral, depth and angular terms.\n"
      "Input: vstcal/camera@1 files, then a vstcal/correspondences@1 file (the last argument); or a vstcal/stereo@1 "
      "rig, then the left and the right camera's correspondences@1 files. "
      "Output: vstcal/reproj-report@1, and with --html a page with the charts.\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input.",
      "reproj-report"};
  vstcal::app::ReprojReportRequest r;
  std::string format = "json", grid = "8x6";
  app.add_option("CAMERA... CORRESPONDENCES", r.inputs, "camera@1 files, then the correspondences@1 file; or RIG LEFT RIGHT")
      ->required()
      ->expected(2, -1)
      ->check(vstcal::tools::kNonEmpty);
  app.add_option("-o,--output", r.output, "report to write (vstcal/reproj-report@1)")->required()->check(vstcal::tools::kNonEmpty);
  app.add_option("--html", r.html,
                 "also write a self-contained HTML page (charts by gnuplot, residual overlays by OpenCV; opens offline)")
      ->check(vstcal::tools::kNonEmpty);
  app.add_option("--format", format, "also print to stdout: json (nothing) or text (a table)")
      ->check(CLI::IsMember({"json", "text"}))
      ->capture_default_str();
  app.add_option("--match-views", r.match_views,
                 "with a rig: match views by the first group of this regular expression in their names ('([0-9]+)$')");
  app.add_option("--grid", grid, "image cells COLSxROWS of the per-region statistics (1 to 64 each; a rig: each camera's)")->capture_default_str();

  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    DeclareOutputs({r.output, r.html});
    std::tie(r.grid_cols, r.grid_rows) = tools::ParseSize(grid, "--grid", "8x6", 64);
    r.text = format == "text";
    if (!r.match_views.empty() && !app::IsRigRequest(r)) {
      throw InputError("--match-views: goes with a stereo rig (RIG LEFT RIGHT); leave it out");
    }
    const app::Outcome outcome = app::RunReprojReport(r, MakeProvenance("reproj-report", argc, argv));
    if (r.text) tools::PrintToStdout(tools::ForUser(outcome.stdout_text));  // first: a lost table leaves no file
    app::WriteOutcome(outcome);
    std::fputs(outcome.summary.c_str(), stderr);
    return 0;
  });
}
