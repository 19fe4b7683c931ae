// reproj-report: reprojection and registration-error report of cameras against correspondences
// (docs/tools/reproj-report.md).
#include <cstdio>

#include "common/run_tool.h"
#include "common/validators.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/pages/html.h"
#include "vstcal/formats/report/report_format.h"
#include "vstcal/pages/stereo_html.h"

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
  std::vector<std::string> inputs;
  std::string output, html, format = "json", grid = "8x6", match_views;
  app.add_option("CAMERA... CORRESPONDENCES", inputs, "camera@1 files, then the correspondences@1 file; or RIG LEFT RIGHT")
      ->required()
      ->expected(2, -1)
      ->check(vstcal::tools::kNonEmpty);
  app.add_option("-o,--output", output, "report to write (vstcal/reproj-report@1)")->required()->check(vstcal::tools::kNonEmpty);
  app.add_option("--html", html,
                 "also write a self-contained HTML page (charts by gnuplot, residual overlays by OpenCV; opens offline)")
      ->check(vstcal::tools::kNonEmpty);
  app.add_option("--format", format, "also print to stdout: json (nothing) or text (a table)")
      ->check(CLI::IsMember({"json", "text"}))
      ->capture_default_str();
  app.add_option("--match-views", match_views,
                 "with a rig: match views by the first group of this regular expression in their names ('([0-9]+)$')");
  app.add_option("--grid", grid, "image cells COLSxROWS of the per-region statistics (1 to 64 each; a rig: each camera's)")->capture_default_str();

  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    DeclareOutputs({output, html});
    ReprojReportOptions options;
    std::tie(options.grid_cols, options.grid_rows) = tools::ParseSize(grid, "--grid", "8x6", 64);
    const JsonDocument first = JsonDocument::Load(inputs.front());
    if (IsStereoRigDocument(first)) {  // RIG LEFT RIGHT: the triangulated 3-D error
      if (inputs.size() != 3) {
        throw InputError(inputs.front() + ": a stereo rig takes two correspondences files after it, LEFT then RIGHT; got " +
                         std::to_string(inputs.size() - 1));
      }
      const StereoReport report = BuildStereoReport(StereoRigFromJson(first), ReadCorrespondences(inputs[1]),
                                                    ReadCorrespondences(inputs[2]), inputs[0], inputs[1], inputs[2],
                                                    {match_views, options.grid_cols, options.grid_rows});
      std::vector<std::pair<std::filesystem::path, std::string>> files = {
          {output, DumpJson(StereoReportToJson(report, MakeProvenance("reproj-report", argc, argv)))}};
      if (!html.empty()) files.emplace_back(html, StereoReportHtml(report, std::filesystem::path(inputs[1]).parent_path(),
                                                                 std::filesystem::path(inputs[2]).parent_path()));
      if (format == "text") tools::PrintToStdout(StereoReportText(report));
      WriteFilesAtomically(files);
      for (const std::string& note : ExclusionNotes(report)) std::fprintf(stderr, "reproj-report: note: %s\n", note.c_str());
      return 0;
    }
    if (!match_views.empty()) throw InputError("--match-views: goes with a stereo rig (RIG LEFT RIGHT); leave it out");
    const std::string corr_file = inputs.back();
    inputs.pop_back();
    std::vector<ReportCamera> cameras;
    for (const std::string& file : inputs) cameras.push_back(ReadReportCamera(file));
    const ReprojReport report = BuildReprojReport(cameras, ReadCorrespondences(corr_file), corr_file, options);
    std::vector<std::pair<std::filesystem::path, std::string>> files = {
        {output, DumpJson(ReprojReportToJson(report, MakeProvenance("reproj-report", argc, argv)))}};
    if (!html.empty()) files.emplace_back(html, ReprojReportHtml(report, std::filesystem::path(corr_file).parent_path()));
    if (format == "text") tools::PrintToStdout(ReprojReportText(report));
    WriteFilesAtomically(files);
    for (const std::string& note : ExclusionNotes(report)) std::fprintf(stderr, "reproj-report: note: %s\n", note.c_str());
    return 0;
  });
}
