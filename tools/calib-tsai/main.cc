// calib-tsai: camera by Tsai's two-stage method (volumes) or Zhang's method (planar views), refined
// to maximum likelihood with covariance and projection uncertainty (docs/tools/calib-tsai.md).
#include "common/calibration_flags.h"
#include "common/run_tool.h"
#include "common/validators.h"
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
  std::string input, output, variant = "auto", free_pp = "no";
  std::array<double, 2> principal_point{};
  bool no_refine = false;
  vstcal::CalibrationOptions options;
  vstcal::tools::CalibrationFlags flags;
  app.add_option("CORNERS", input, "vstcal/correspondences@1 file")->required()->check(vstcal::tools::kNonEmpty);
  app.add_option("-o,--output", output, "camera file to write (vstcal/camera@1)")->required()->check(vstcal::tools::kNonEmpty);
  app.add_option("--variant", variant, "Tsai's variant for volumes: auto, coplanar or non-coplanar")
      ->check(CLI::IsMember(vstcal::NamesOf(vstcal::TsaiOptions::kVariantNames)))
      ->capture_default_str();
  app.add_option("--principal-point", principal_point, "U,V in px for Tsai's stages (default: the image centre)")
      ->delimiter(',')
      ->check(vstcal::tools::kFinite)
      ->type_name("U,V");
  app.add_option("--sx", options.tsai.sx, "the coplanar variant's fixed horizontal scale factor")
      ->check(vstcal::tools::kPositiveFinite)
      ->capture_default_str();
  CLI::Option* raw = app.add_flag("--no-refine", no_refine, "write the closed-form camera without refinement");
  app.add_option("--free-principal-point", free_pp,
                 "one plane, refined: no (hold it where Tsai assumed it), yes, or auto (free it when the scaled "
                 "information determines it to 0.5% of the image diagonal)")
      ->check(CLI::IsMember(vstcal::NamesOf(vstcal::CalibrationOptions::kPlanePrincipalPointNames)))
      ->capture_default_str()
      ->excludes(raw);
  for (CLI::Option* o : flags.AddRefinement(app)) o->excludes(raw);
  for (CLI::Option* o : flags.AddUncertainty(app)) o->excludes(raw);
  flags.AddOutput(app);

  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    DeclareOutputs({output, flags.residuals});
    options.refine = !no_refine;
    options.refinement = flags.Refinement();
    options.tsai.variant = *FromName(TsaiOptions::kVariantNames, variant);
    if (app.count("--principal-point") > 0) {
      options.tsai.principal_point = Eigen::Vector2d(principal_point[0], principal_point[1]);
    }
    options.plane_principal_point = *FromName(CalibrationOptions::kPlanePrincipalPointNames, free_pp);
    Correspondences corners = ReadCorrespondences(input);
    if (corners.rig == Rig::kPlanarViews) {
      for (const char* flag : {"--variant", "--principal-point", "--sx", "--free-principal-point"}) {
        if (app.count(flag) > 0) {
          throw InputError(std::string(flag) + ": applies to rig \"volume\" only (planar views start from Zhang's "
                           "method); remove it");
        }
      }
    }
    const UncertaintyRequest request = flags.Uncertainty(corners);
    const CalibrationResult result = Calibrate(std::move(corners), options);
    if (app.count("--sx") > 0 && result.tsai && result.tsai->variant == TsaiOptions::Variant::kNonCoplanar) {
      throw InputError("--sx: the points are not coplanar, so Tsai's non-coplanar variant estimates sx and --sx would "
                       "not be used; drop it, or force --variant coplanar");
    }
    return tools::FinishCalibration("calib-tsai", input, output, result, options, flags, request, argc, argv);
  });
}
