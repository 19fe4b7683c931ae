#include "flags.h"

#include "common/validators.h"
#include "vstcal/core/error.h"

namespace vstcal::tools {

void TsaiFlags::Add(CLI::App& app) {
  input.Add(app, "a volume or planar views");
  app.add_option("-o,--output", output, "camera file to write (vstcal/camera@1)")->required()->check(kNonEmpty);
  app.add_option("--variant", variant, "Tsai's variant for volumes: auto, coplanar or non-coplanar")
      ->check(CLI::IsMember(NamesOf(TsaiOptions::kVariantNames)))
      ->capture_default_str();
  app.add_option("--principal-point", principal_point, "U,V in px for Tsai's stages (default: the image centre)")
      ->delimiter(',')
      ->check(kFinite)
      ->type_name("U,V");
  app.add_option("--sx", options.tsai.sx, "the coplanar variant's fixed horizontal scale factor")
      ->check(kPositiveFinite)
      ->capture_default_str();
  CLI::Option* raw = app.add_flag("--no-refine", no_refine, "write the closed-form camera without refinement");
  app.add_option("--free-principal-point", free_pp,
                 "one plane, refined: prior (estimate it under a Gaussian prior at Tsai's principal point, "
                 "sigma --principal-point-sigma of the image diagonal; its uncertainty reaches every sigma), no "
                 "(hold it there: sigmas conditional on it) or yes (estimate it without a prior)")
      ->check(CLI::IsMember(NamesOf(CalibrationOptions::kPlanePrincipalPointNames)))
      ->capture_default_str()
      ->excludes(raw);
  app.add_option("--principal-point-sigma", options.plane_principal_point_prior_sigma,
                 "one plane, --free-principal-point prior: the prior's sigma per coordinate, as a fraction of the image "
                 "diagonal")
      ->check(kPositiveFinite)
      ->capture_default_str()
      ->excludes(raw);
  app.add_flag("--split-halves", split_halves,
               "also calibrate each half of the views (1st, 3rd, … and 2nd, 4th, …) into OUTPUT's <stem>.half-a.json and "
               ".half-b.json, for calib-compare --cross-validate")
      ->excludes(raw);
  for (CLI::Option* o : calibration.AddRefinement(app)) o->excludes(raw);
  for (CLI::Option* o : calibration.AddUncertainty(app)) o->excludes(raw);
  calibration.AddRejection(app);
  calibration.AddOutput(app);
}

CalibrationOptions TsaiFlags::Options(const CLI::App& app) {
  options.refine = !no_refine;
  options.refinement = calibration.Refinement();
  options.reject_views = calibration.Rejection();
  options.tsai.variant = *FromName(TsaiOptions::kVariantNames, variant);
  if (app.count("--principal-point") > 0) {
    options.tsai.principal_point = Eigen::Vector2d(principal_point[0], principal_point[1]);
  }
  options.plane_principal_point = *FromName(CalibrationOptions::kPlanePrincipalPointNames, free_pp);
  if (app.count("--principal-point-sigma") > 0 && options.plane_principal_point != CalibrationOptions::PlanePrincipalPoint::kPrior) {
    throw InputError("--principal-point-sigma: applies to --free-principal-point prior only; drop it or choose prior");
  }
  if (PlacesPrincipalPoint(options.refinement)) {  // the user's own prior or hold replaces the one-plane rule
    for (const char* flag : {"--free-principal-point", "--principal-point-sigma"}) {
      if (app.count(flag) > 0) {
        throw InputError(std::string(flag) + ": the principal point already has a --prior or --hold of its own, which "
                         "replaces the one-plane rule; give one of the two");
      }
    }
  }
  return options;
}

void TsaiFlags::CheckRig(const CLI::App& app, const Correspondences& corners) const {
  if (corners.rig == Rig::kPlanarViews) {
    for (const char* flag : {"--variant", "--principal-point", "--sx", "--free-principal-point", "--principal-point-sigma"}) {
      if (app.count(flag) > 0) {
        throw InputError(std::string(flag) + ": applies to rig \"volume\" only (planar views start from Zhang's "
                         "method); remove it");
      }
    }
  }
}

void TsaiFlags::CheckUsed(const CLI::App& app, const CalibrationResult& result) const {
  if (app.count("--principal-point-sigma") > 0 && result.tsai && result.tsai->variant == TsaiOptions::Variant::kNonCoplanar) {
    throw InputError("--principal-point-sigma: the points are not coplanar, so the principal point is estimated without a "
                     "prior; drop it");
  }
  if (app.count("--sx") > 0 && result.tsai && result.tsai->variant == TsaiOptions::Variant::kNonCoplanar) {
    throw InputError("--sx: the points are not coplanar, so Tsai's non-coplanar variant estimates sx and --sx would "
                     "not be used; drop it, or force --variant coplanar");
  }
}

}  // namespace vstcal::tools
