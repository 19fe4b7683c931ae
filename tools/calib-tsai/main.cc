// calib-tsai, also installed as calib-camera: camera by Tsai's two-stage method (volumes) or Zhang's
// method (planar views), refined to maximum likelihood with covariance and projection uncertainty,
// from corners or straight from images (docs/tools/calib-tsai.md).
#include "common/run_tool.h"
#include "flags.h"
#include "vstcal/app/calibration.h"
#include "vstcal/formats/camera/correspondences_io.h"

int main(int argc, char** argv) {
  // "calib-tsai" names the method, which a newcomer calibrating a camera from chessboard photos
  // (Zhang's method) would not look for; both names run this tool and it answers to either.
  const std::string name = vstcal::tools::InvokedAs(argc, argv, {"calib-tsai", "calib-camera"});
  CLI::App app{
      "Calibrates a camera from vstcal/correspondences@1, or from images with --target (their corners found first, "
      "as calib-capture detect does). Rig \"volume\": Tsai's two-stage method (non-coplanar "
      "or coplanar, chosen from the points' planarity unless --variant says), Tsai's kappa1 kept and converted to "
      "k1, k2, k3. Rig \"planar-views\": Zhang's closed form from per-view homographies. Then (unless "
      "--no-refine) the maximum-likelihood refinement: distortion terms by name (OpenCV's default k1,k2,p1,p2), "
      "optional skew and robust loss, outliers listed, parameter covariance, projection uncertainty. Output: "
      "vstcal/camera@1.\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input (too few points or views), 3 degenerate data "
      "(coplanar data forced into the non-coplanar variant, a plane parallel to the image, parallel boards) or "
      "no convergence. One plane is refined with Tsai's sx held, and the principal point under a prior at Tsai's "
      "(--free-principal-point).",
      name};
  vstcal::tools::TsaiFlags f;
  f.Add(app);
  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    DeclareOutputs({f.output, f.calibration.residuals, f.input.corners, f.input.html});
    const CalibrationOptions options = f.Options(app);
    const tools::ReadCorners read = f.input.Read(name, f.calibration.quiet, argc, argv);
    f.CheckRig(app, read.corners);
    const UncertaintyRequest request = f.calibration.Uncertainty(read.corners);
    const CalibrationResult result = Calibrate(read.corners, options);
    f.CheckUsed(app, result);
    app::Outcome halves;
    if (f.split_halves && result.exit_code == ExitCode::kOk) {
      halves = app::CalibrateHalves(read.corners, options, {name, f.input.Name(), f.output, "", request, ""}, MakeProvenance(name, argc, argv));
    }
    return tools::FinishCalibration(name, f.input, read, f.output, result, options, f.calibration, request, argc, argv, std::move(halves));
  });
}
