// calib-dlt: camera from a calibration volume by DLT, optionally refined (docs/tools/calib-dlt.md).
#include "common/calibration_flags.h"
#include "common/run_tool.h"
#include "common/validators.h"
#include "vstcal/formats/camera/correspondences_io.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Solves a camera (K with skew, camera_from_world, P) from a calibration volume by the direct linear "
      "transformation on the Hartley-normalized system, and reports residuals per point, per view and at the "
      "test points, with the DLT's first-order covariance of P and of K, R, C (docs/math/dlt.md#covariance). With "
      "--refine, the DLT camera starts a maximum-likelihood refinement (distortion, robust loss, covariance and "
      "projection uncertainty). Input: vstcal/correspondences@1 with rig \"volume\", or --target with the images and "
      "their --manifest (the corners found first, as calib-capture detect does). "
      "Output: vstcal/camera@1.\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input, 3 degenerate geometry (coplanar, collinear, "
      "ill-conditioned) or a refinement that does not converge.",
      "calib-dlt"};
  vstcal::tools::CornerInput input;
  std::string output;
  std::string solver = "normal-equations";
  vstcal::CalibrationOptions options;
  options.start = vstcal::CalibrationOptions::Start::kDlt;
  options.refine = false;  // DLT alone unless --refine
  vstcal::tools::CalibrationFlags flags;
  input.Add(app, "rig \"volume\"");
  app.add_option("-o,--output", output, "camera file to write (vstcal/camera@1)")->required()->check(vstcal::tools::kNonEmpty);
  app.add_option("--solver", solver, "normal-equations (fast, default) or svd (2N×12 SVD, reference)")
      ->check(CLI::IsMember(vstcal::NamesOf(vstcal::DltOptions::kSolverNames)));
  app.add_option("--min-extent-ratio", options.dlt.min_extent_ratio,
                 "refuse point clouds thinner than this along a principal axis (coplanar/collinear)")
      ->check(vstcal::tools::kPositiveFinite)
      ->capture_default_str();
  app.add_option("--min-conditioning", options.dlt.min_conditioning,
                 "refuse when sigma11/||A||_F of the normalized system is below this (critical configuration)")
      ->check(vstcal::tools::kPositiveFinite)
      ->capture_default_str();
  CLI::Option* refine = app.add_flag("--refine", options.refine, "refine the DLT camera to maximum likelihood");
  for (CLI::Option* o : flags.AddRefinement(app)) o->needs(refine);
  flags.AddUncertainty(app);  // the DLT camera has its own first-order covariance
  flags.AddRejection(app);
  flags.AddOutput(app);
  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    DeclareOutputs({output, flags.residuals, input.corners, input.html});
    options.dlt.exact_diagnostics = true;  // the camera file reports sigma_11
    options.dlt.solver = *FromName(DltOptions::kSolverNames, solver);
    options.refinement = flags.Refinement();
    options.reject_views = flags.Rejection();
    const tools::ReadCorners read = input.Read("calib-dlt", flags.quiet, argc, argv);
    if (read.corners.rig != Rig::kVolume) {
      throw InputError(input.Name() + ": rig: DLT needs one world frame (rig \"volume\"), got \"planar-views\"; " +
                       (input.FromImages() ? "give the images' plane offsets with --manifest, or calibrate planar views with calib-tsai"
                                           : "calibrate planar views with calib-tsai"));
    }
    const UncertaintyRequest request = flags.Uncertainty(read.corners);
    const CalibrationResult result = Calibrate(read.corners, options);
    return tools::FinishCalibration("calib-dlt", input, read, output, result, options, flags, request, argc, argv);
  });
}
