// calib-dlt: camera from a calibration volume by DLT (docs/tools/calib-dlt.md).
#include <iostream>

#include "common/run_tool.h"
#include "common/validators.h"
#include "vstcal/calib/dlt_calibration.h"
#include "vstcal/io/camera_io.h"
#include "vstcal/io/correspondences_io.h"
#include "vstcal/io/dlt_io.h"
#include "vstcal/io/residuals_io.h"
#include "vstcal/report/fit_summary.h"


int main(int argc, char** argv) {
  CLI::App app{
      "Solves a camera (K with skew, camera_from_world, P) from a calibration volume by the direct linear "
      "transformation on the Hartley-normalized system, and reports residuals per point, per view and at the "
      "test points. Input: vstcal/correspondences@1 with rig \"volume\". Output: vstcal/camera@1.\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input, 3 degenerate geometry (coplanar, collinear, "
      "ill-conditioned).",
      "calib-dlt"};
  std::string input, output, residuals;
  std::string solver = "normal-equations";
  vstcal::DltOptions options;
  bool quiet = false;
  app.add_option("CORNERS", input, "vstcal/correspondences@1 file (rig \"volume\")")->required()->check(vstcal::tools::kNonEmpty);
  app.add_option("-o,--output", output, "camera file to write (vstcal/camera@1)")->required()->check(vstcal::tools::kNonEmpty);
  app.add_option("--residuals", residuals, "also write per-point residuals (vstcal/residuals@1)")
      ->check(vstcal::tools::kNonEmpty);
  app.add_option("--solver", solver, "normal-equations (fast, default) or svd (2N×12 SVD, reference)")
      ->check(CLI::IsMember({"normal-equations", "svd"}));
  app.add_option("--min-extent-ratio", options.min_extent_ratio,
                 "refuse point clouds thinner than this along a principal axis (coplanar/collinear)")
      ->check(vstcal::tools::kPositiveFinite)
      ->capture_default_str();
  app.add_option("--min-conditioning", options.min_conditioning,
                 "refuse when sigma11/||A||_F of the normalized system is below this (critical configuration)")
      ->check(vstcal::tools::kPositiveFinite)
      ->capture_default_str();
  app.add_flag("-q,--quiet", quiet, "print only warnings and errors");

  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    options.exact_diagnostics = true;  // the camera file reports sigma_11
    options.solver = solver == "svd" ? DltOptions::Solver::kFullSvd : DltOptions::Solver::kNormalEquations;
    const Correspondences corners = io::ReadCorrespondences(input);
    if (corners.rig != Rig::kVolume) {
      throw InputError(input + ": rig: DLT needs one world frame (rig \"volume\"), got \"planar-views\"; "
                       "calibrate planar views with calib-tsai");
    }
    const DltCalibration cal = CalibrateDlt(corners, options);
    if (cal.dlt.status != DltStatus::kOk) throw Error(DltStatusExitCode(cal.dlt.status), input + ": " + cal.dlt.message);

    const io::Provenance provenance = io::MakeProvenance("calib-dlt", argc, argv);
    std::vector<std::pair<std::filesystem::path, std::string>> outputs;
    outputs.emplace_back(output, io::DumpJson(io::CameraToJson(*cal.camera, provenance,
                                                               {{"dlt", io::DltDiagnosticsToJson(cal, options)}})));
    if (!residuals.empty()) {
      outputs.emplace_back(residuals, io::DumpJson(io::ResidualsToJson(corners, *cal.camera->fit, provenance)));
    }
    io::WriteFilesAtomically(outputs);
    for (const std::string& w : cal.dlt.warnings) std::cerr << "calib-dlt: warning: " << w << "\n";
    if (!quiet) {
      std::cerr << "calib-dlt: " << input << ": " << NumObservations(corners) << " points, DLT ("
                << io::DltSolverName(options.solver) << ")\n"
                << FitSummaryText(*cal.camera) << "  wrote " << output << (residuals.empty() ? "" : " and " + residuals)
                << "\n";
    }
    return 0;
  });
}
