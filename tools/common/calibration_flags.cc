#include "common/calibration_flags.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "common/run_tool.h"
#include "common/validators.h"
#include "vstcal/camera/camera.h"
#include "vstcal/core/limits.h"
#include "vstcal/app/calibration.h"

namespace vstcal::tools {
namespace {

void ExpectThree(const std::vector<double>& numbers, const std::string& flag, const std::string& form) {
  if (numbers.size() == 3) return;
  std::string got;
  for (const double n : numbers) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", n);
    got += (got.empty() ? "" : ",") + std::string(buf);
  }
  throw InputError(flag + ": expected three numbers " + form + ", got " + std::to_string(numbers.size()) + " (" + got +
                   "); give each point as its own " + flag);
}

// "NAME=VALUE,SIGMA" (--prior) as a prior; throws InputError naming the flag and the form.
IntrinsicPrior ParsePrior(const std::string& text) {
  const std::string form = "give NAME=VALUE,SIGMA in the parameter's unit (px for fx, fy, cx, cy, s), e.g. cx=639.5,32";
  const size_t eq = text.find('='), comma = text.find(',');
  if (eq == std::string::npos || eq == 0 || comma == std::string::npos || comma < eq) {
    throw InputError("--prior: \"" + text + "\" is not NAME=VALUE,SIGMA; " + form);
  }
  IntrinsicPrior prior = StatedPrior(text.substr(0, eq), 0, 0);
  const auto number = [&](const std::string& part, const char* what) {
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (part.empty() || end != part.c_str() + part.size() || !std::isfinite(v)) {
      throw InputError("--prior " + prior.parameter + ": the " + what + " \"" + part + "\" is not a finite number; " + form);
    }
    return v;
  };
  prior.value = number(text.substr(eq + 1, comma - eq - 1), "value");
  prior.sigma = number(text.substr(comma + 1), "sigma");
  if (!(prior.sigma > 0)) {
    throw InputError("--prior " + prior.parameter + ": the sigma must be > 0, got " + text.substr(comma + 1) +
                     "; give a positive sigma, or hold the parameter with --hold " + prior.parameter);
  }
  return prior;
}

}  // namespace

std::vector<CLI::Option*> CalibrationFlags::AddRefinement(CLI::App& app) {
  std::string models;
  ForEachLensModel([&](auto model) { models += (models.empty() ? "" : ", ") + std::string(decltype(model)::kName); });
  distortion_option = app.add_option("--distortion", distortion,
                     "distortion terms to estimate, comma-separated names (k1,k2,p1,p2,k3 radial-tangential; also "
                     "k4,k5,k6: the rational model, OpenCV's CALIB_RATIONAL_MODEL; with --lens-model "
                     "kannala-brandt its k1,k2,k3,k4, the default there) or \"none\"")
          ->capture_default_str();
  std::vector<CLI::Option*> options = {
      distortion_option,
      app.add_option("--lens-model", lens_model,
                     "solve this lens model (" + models + "): kannala-brandt for a fisheye (OpenCV's cv::fisheye, "
                     "Kalibr's equidistant); by default the Brown–Conrady model --distortion calls for"),
      app.add_flag("--skew", skew, "also estimate the skew s (K[0][1])"),
      app.add_option("--loss", loss, "robust loss: none, huber or cauchy")
          ->check(CLI::IsMember(NamesOf(RefineOptions::kLossNames)))
          ->capture_default_str()};
  loss_scale_option = app.add_option("--loss-scale", loss_scale_px, "where the robust loss departs from the square, px")
                          ->check(kPositiveFinite)
                          ->capture_default_str();
  options.push_back(loss_scale_option);
  options.push_back(app.add_option("--max-iterations", max_iterations, "refinement iteration limit")
                        ->check(CLI::Range(1, 100000))
                        ->capture_default_str());
  options.push_back(app.add_option("--prior", priors,
                                   "a Gaussian prior on a lens parameter, NAME=VALUE,SIGMA in its unit (repeatable): the "
                                   "parameter stays estimated and its uncertainty reaches every sigma")
                        ->type_name("NAME=VALUE,SIGMA"));
  options.push_back(app.add_option("--hold", holds,
                                   "hold lens parameters at the closed-form start's values (fx,fy together; cx,cy "
                                   "together; s; distortion terms): the sigmas are then conditional on them")
                        ->delimiter(',')
                        ->type_name("NAMES"));
  return options;
}

std::vector<CLI::Option*> CalibrationFlags::AddUncertainty(CLI::App& app) {
  CLI::Option* grid = app.add_option("--uncertainty-grid", grid_depth,
                                     "report the projection's 1-sigma ellipse over a grid of the image at this depth "
                                     "(length unit)")
                          ->check(kPositiveFinite);
  return {grid,
          app.add_option("--grid-size", grid_size, "COLSxROWS of --uncertainty-grid")->capture_default_str()->needs(grid),
          app.add_option("--uncertainty-at", at_world, "report the ellipse at world point X,Y,Z (repeatable)")
              ->delimiter(',')
              ->check(kFinite)
              ->type_name("X,Y,Z"),
          app.add_option("--uncertainty-pixel", at_pixel,
                         "report the ellipse at pixel U,V and depth D: U,V,D (repeatable)")
              ->delimiter(',')
              ->check(kFinite)
              ->type_name("U,V,DEPTH")};
}

void CalibrationFlags::AddOutput(CLI::App& app) {
  app.add_option("--residuals", residuals, "also write per-point residuals (vstcal/residuals@1)")->check(kNonEmpty);
  app.add_option("--undistort", undistort, "check images: write each view's image undistorted through the camera as DIR/<view>.undistorted.png")
      ->check(kNonEmpty)
      ->type_name("DIR");
  app.add_flag("-q,--quiet", quiet, "print only warnings and errors");
}

void CalibrationFlags::AddRejection(CLI::App& app) {
  CLI::Option* on = app.add_flag("--reject-views", reject_views,
                                 "reject views whose residual RMS is inconsistent with the median view's noise, then "
                                 "single corners beyond a chi-square threshold, re-solving until none is (off by "
                                 "default)");
  app.add_option("--view-false-alarm", view_false_alarm,
                 "--reject-views: probability that a clean calibration loses a view")
      ->check(CLI::Range(1e-12, 0.5))
      ->capture_default_str()
      ->needs(on);
  app.add_option("--corner-false-alarm", corner_false_alarm,
                 "--reject-views: probability that a clean calibration loses a corner")
      ->check(CLI::Range(1e-12, 0.5))
      ->capture_default_str()
      ->needs(on);
}

ViewRejectionOptions CalibrationFlags::Rejection() const {
  ViewRejectionOptions o;
  o.enabled = reject_views;
  o.view_false_alarm = view_false_alarm;
  o.corner_false_alarm = corner_false_alarm;
  return o;
}

RefineOptions CalibrationFlags::Refinement() const {
  RefineOptions o;
  o.lens_model = lens_model;
  const auto model = lens_model.empty() ? std::nullopt : LensModelFromName(lens_model);
  if (!lens_model.empty() && !model) {
    throw InputError("--lens-model: unknown lens model \"" + lens_model + "\"; use one of " + KnownLensModelNames());
  }
  if (model && distortion_option && distortion_option->count() == 0) {
    // A model of another family (the fisheye) estimates its own terms unless told otherwise.
    o.free_distortion.clear();
    const auto names = LensModelParamNames(*model);
    for (auto it = names.begin() + kNumIntrinsicParams; it != names.end(); ++it) o.free_distortion.emplace_back(*it);
  } else {
    o.free_distortion = DistortionTermsFromList(distortion);
  }
  o.free_skew = skew;
  o.loss = *FromName(RefineOptions::kLossNames, loss);
  if (o.loss == RefineOptions::Loss::kNone && loss_scale_option != nullptr && loss_scale_option->count() > 0) {
    throw InputError("--loss-scale: has no effect with --loss none; give --loss huber or --loss cauchy, or drop it");
  }
  o.loss_scale_px = loss_scale_px;
  o.max_iterations = max_iterations;
  for (const std::string& text : priors) o.priors.push_back(ParsePrior(text));
  HoldIntrinsics(holds, &o);
  return o;
}

UncertaintyRequest CalibrationFlags::Uncertainty(const Correspondences& corners) const {
  UncertaintyRequest r;
  if (!at_world.empty() && corners.rig != Rig::kVolume) {
    throw InputError("--uncertainty-at: planar views have no world frame; use --uncertainty-pixel U,V,DEPTH");
  }
  r.grid_depth = grid_depth;
  std::tie(r.grid_cols, r.grid_rows) =
      ParseSize(grid_size, "--grid-size", "COLSxROWS (e.g. 16x9)", static_cast<int>(limits::kMaxGridCells));
  if (static_cast<size_t>(r.grid_cols) * static_cast<size_t>(r.grid_rows) > limits::kMaxGridCells) {
    throw InputError("--grid-size: " + grid_size + " is " +
                     std::to_string(static_cast<size_t>(r.grid_cols) * static_cast<size_t>(r.grid_rows)) +
                     " cells, more than the " + std::to_string(limits::kMaxGridCells) +
                     " vstcal computes (docs/reliability.md#limits); give a coarser grid");
  }
  for (const std::vector<double>& p : at_world) {
    ExpectThree(p, "--uncertainty-at", "X,Y,Z (e.g. 0,0,1000)");
    r.world_points.emplace_back(p[0], p[1], p[2]);
  }
  for (const std::vector<double>& p : at_pixel) {
    ExpectThree(p, "--uncertainty-pixel", "U,V,DEPTH (e.g. 320,240,1000)");
    const double u = p[0], v = p[1], depth = p[2];
    char point[120];
    std::snprintf(point, sizeof point, "%g,%g,%g", u, v, depth);
    if (!(depth > 0)) {
      throw InputError("--uncertainty-pixel: the depth in \"" + std::string(point) +
                       "\" must be positive; give the distance along the optical axis in the length unit");
    }
    const ImageSize& size = corners.image_size;
    if (u < -0.5 || u > size.width - 0.5 || v < -0.5 || v > size.height - 0.5) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "--uncertainty-pixel: (%g, %g) lies outside the %d×%d image; give U in [-0.5, %g] "
                    "and V in [-0.5, %g]", u, v, size.width, size.height, size.width - 0.5, size.height - 0.5);
      throw InputError(buf);
    }
    r.pixel_depths.emplace_back(u, v, depth);
  }
  return r;
}

int FinishCalibration(const std::string& tool, const CornerInput& input, const ReadCorners& read, const std::string& output,
                      const CalibrationResult& result, const CalibrationOptions& options, const CalibrationFlags& flags,
                      const UncertaintyRequest& request, int argc, char** argv, app::Outcome extra) {
  app::Outcome outcome = WithCornersAndPage(
      app::CalibrationOutcome(result, options, {tool, input.Name(), output, flags.residuals, request, flags.undistort},
                              MakeProvenance(tool, argc, argv)),
      read, input);
  for (auto& file : extra.files) outcome.files.push_back(std::move(file));
  for (auto& w : extra.warnings) outcome.warnings.push_back(std::move(w));
  outcome.summary += extra.summary;
  for (const std::string& w : outcome.warnings) std::cerr << ForUser(w) << "\n";
  app::WriteOutcome(outcome);
  if (!flags.quiet) std::cerr << ForUser(outcome.summary);
  return 0;
}

}  // namespace vstcal::tools
