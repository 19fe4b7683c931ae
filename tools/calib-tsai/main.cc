// calib-tsai: camera by Tsai's two-stage method (volumes) or Zhang's method (planar views), refined
// to maximum likelihood with covariance and projection uncertainty (docs/tools/calib-tsai.md).
#include "common/run_tool.h"
#include "flags.h"
#include "vstcal/formats/camera/correspondences_io.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Calibrates a camera from vstcal/correspondences@1. Rig \"volume\": Tsai's two-stage method (non-coplanar "
      "or coplanar, chosen from the points' planarity unless --variant says), Tsai's kappa1 kept and converted to "
      "k1, k2, k3. Rig \"planar-views\": Zhang's closed form from per-view homographies. Then (unless "
      "--no-refine) the maximum-likelihood refinement: distortion terms by name (OpenCV's default k1,k2,p1,p2), "
      "optional skew and robust loss, outliers listed, parameter covariance, projection uncertainty. Output: "
      "vstcal/camera@1.\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input (too few points or views), 3 degenerate data "
      "(coplanar data forced into the non-coplanar variant, a plane parallel to the image, parallel boards) or "
      "no convergence. One plane is refined with Tsai's sx held, and the principal point held unless "
      "--free-principal-point frees it.",
      "calib-tsai"};
  vstcal::tools::TsaiFlags f;
  f.Add(app);
  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    DeclareOutputs({f.output, f.calibration.residuals});
    const CalibrationOptions options = f.Options(app);
    Correspondences corners = ReadCorrespondences(f.input);
    f.CheckRig(app, corners);
    const UncertaintyRequest request = f.calibration.Uncertainty(corners);
    const CalibrationResult result = Calibrate(std::move(corners), options);
    f.CheckUsed(app, result);
    return tools::FinishCalibration("calib-tsai", f.input, f.output, result, options, f.calibration, request, argc, argv);
  });
}
