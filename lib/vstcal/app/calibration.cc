#include "vstcal/app/calibration.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "vstcal/capture/target_drawing.h"
#include "vstcal/core/error.h"
#include "vstcal/image/image_io.h"
#include "vstcal/image/undistort.h"
#include "vstcal/formats/calib/calibration_io.h"
#include "vstcal/formats/calib/residuals_io.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/report/fit_summary.h"
#include "vstcal/core/option_name.h"

namespace vstcal::app {

std::string UncertaintySummary(const CalibrationResult& result, const UncertaintyRequest& request) {
  const CalibratedCamera& c = result.camera;
  if (!c.covariance || !c.fit) return "";
  std::vector<double> depths;
  for (size_t v = 0; v < result.used.views.size(); ++v) {
    const Rigid3d pose = c.camera_from_world ? *c.camera_from_world : c.views[v].camera_from_board;
    for (const Observation& o : result.used.views[v].observations) depths.push_back((pose * o.point).z());
  }
  if (depths.empty()) return "";
  std::nth_element(depths.begin(), depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2), depths.end());
  const ImageSize& size = c.camera.image_size;
  std::vector<Eigen::Vector3d> at = {{0.5 * (size.width - 1), 0.5 * (size.height - 1), depths[depths.size() / 2]}};
  at.insert(at.end(), request.pixel_depths.begin(), request.pixel_depths.end());
  std::string text = "  projection 1-sigma (major axis), with poses = tied to the calibration object, intrinsics only = "
                     "what using the camera elsewhere inherits:\n";
  for (const Eigen::Vector3d& q : at) {
    const auto tied = ProjectionUncertaintyAtPixel(c, q.head<2>(), q.z(), ProjectionUncertaintyKind::kWithPoses);
    const auto alone = ProjectionUncertaintyAtPixel(c, q.head<2>(), q.z(), ProjectionUncertaintyKind::kIntrinsicsOnly);
    if (!tied || !alone) continue;
    char buf[200];
    std::snprintf(buf, sizeof buf, "    at pixel (%.1f, %.1f), depth %.4g %s: %.4f px with poses, %.4f px intrinsics only\n",
                  q.x(), q.y(), q.z(), std::string(LengthUnitName(c.length_unit)).c_str(), tied->sigma_major_px,
                  alone->sigma_major_px);
    text += buf;
  }
  return text;
}

namespace {

// What every σ above includes and what it is conditional on: the priors (in the covariance) and
// the held values (not in it: were they wrong, the error would be a bias no σ contains).
std::string PriorsAndConditioningText(const Refinement& r) {
  std::string text;
  if (!r.priors.empty()) {
    text += "  priors (their uncertainty is in every sigma):";
    for (size_t i = 0; i < r.priors.size(); ++i) {
      char buf[120];
      std::snprintf(buf, sizeof buf, "%s %s = %.6g +- %.4g", i == 0 ? "" : ",", r.priors[i].parameter.c_str(), r.priors[i].value,
                    r.priors[i].sigma);
      text += buf;
    }
    text += "\n";
  }
  if (!r.held.empty()) {
    text += "  sigmas are conditional on the held";
    for (size_t i = 0; i < r.held.size(); ++i) {
      char buf[120];
      std::snprintf(buf, sizeof buf, "%s %s = %.6g", i == 0 ? "" : ",", r.held[i].parameter.c_str(), r.held[i].value);
      text += buf;
    }
    text += "\n";
  }
  return text;
}

// The fisheye start's decision: the candidate taken, among how many, and its RMS.
std::string FisheyeStartText(const CalibrationResult& result) {
  if (!result.fisheye_start) return "";
  const FisheyeStartDecision& d = *result.fisheye_start;
  if (d.chosen.empty()) return "  fisheye start: no candidate succeeded; Zhang's pinhole start was used\n";
  char buf[240];
  std::snprintf(buf, sizeof buf, "  fisheye start: %s, %s, RMS %.4g px (best of %zu candidates)\n", d.chosen.c_str(),
                d.coefficients_fitted ? "k1..k4 fitted" : "k1..k4 = 0", d.RmsPx(d.cost), d.candidates.size());
  return buf;
}

// FOLDER/<view>.undistorted.png for every view that names its image; the count of those that do not.
size_t AddUndistortedImages(const CalibrationResult& result, const CalibrationFiles& files, Outcome* outcome) {
  namespace fs = std::filesystem;
  const Camera& camera = result.camera.camera;
  const PixelMap map = UndistortMap(camera);
  size_t without = 0;
  for (size_t v = 0; v < result.used.views.size(); ++v) {
    const View& view = result.used.views[v];
    if (view.image.empty()) {
      ++without;
      continue;
    }
    const std::string field = files.input + ": views[" + std::to_string(v) + "].image: ";
    fs::path path = view.image;
    if (!fs::exists(path) && path.is_relative()) path = fs::path(files.input).parent_path() / view.image;
    if (!fs::is_regular_file(path)) {
      throw InputError(field + "\"" + view.image + "\" not found (as given or beside the correspondences); run from the folder the path is " +
                       "relative to, or leave out " VSTCAL_OPT("undistort"));
    }
    const LoadedImage loaded = LoadImageFile(path);
    if (!loaded.problem.empty()) throw InputError(field + path.string() + ": " + loaded.problem + "; give a PNG or JPEG");
    if (loaded.image.width != camera.image_size.width || loaded.image.height != camera.image_size.height) {
      throw InputError(field + path.string() + " is " + std::to_string(loaded.image.width) + "x" + std::to_string(loaded.image.height) +
                       " px but image_size is " + std::to_string(camera.image_size.width) + "x" +
                       std::to_string(camera.image_size.height) + "; give the image the corners were detected in");
    }
    outcome->files.emplace_back(fs::path(files.undistort_folder) / (view.name + ".undistorted.png"), EncodePng(Remap(loaded.image, map)));
  }
  if (without == result.used.views.size()) {
    throw InputError(VSTCAL_OPT("undistort") ": " + files.input + " names no image (views[].image); detect the corners with calib-capture detect, "
                     "which records each view's image, or leave out " VSTCAL_OPT("undistort"));
  }
  outcome->folders.push_back(files.undistort_folder);
  return without;
}

}  // namespace

Outcome CalibrationOutcome(const CalibrationResult& result, const CalibrationOptions& options,
                           const CalibrationFiles& files, const Provenance& provenance) {
  if (result.exit_code != ExitCode::kOk) throw Error(result.exit_code, files.input + ": " + result.message);
  Outcome outcome;
  for (const std::string& w : result.warnings) outcome.warnings.push_back(files.tool + ": warning: " + w);
  for (const Rejection& x : result.rejections) {
    const std::string what = x.kind == Rejection::Kind::kView
                                 ? "view \"" + x.view_name + "\" (views[" + std::to_string(x.view) + "])"
                                 : "views[" + std::to_string(x.view) + "].points[" + std::to_string(*x.point) +
                                       "] (view \"" + x.view_name + "\")";
    outcome.warnings.push_back(files.tool + ": warning: " VSTCAL_OPT("reject_views") ": rejected " + what + " in round " +
                               std::to_string(x.round) + ": " + x.because);
  }
  OrderedJson blocks = CalibrationBlocksToJson(result, options);
  if (result.camera.covariance) blocks["projection_uncertainty"] = UncertaintyToJson(result.camera, files.uncertainty);
  outcome.files.emplace_back(files.output, DumpJson(CameraToJson(result.camera, provenance, blocks)));
  if (!files.residuals.empty()) {
    outcome.files.emplace_back(files.residuals, DumpJson(ResidualsToJson(result.used, *result.camera.fit, provenance)));
  }
  const size_t before = outcome.files.size();
  const size_t without_image = files.undistort_folder.empty() ? 0 : AddUndistortedImages(result, files, &outcome);
  std::string& text = outcome.summary;
  text = files.tool + ": " + files.input + ": " + std::to_string(NumObservations(result.used)) + " points in " +
         std::to_string(result.used.views.size()) + " views, method " + result.camera.method + "\n" +
         FitSummaryText(result.camera) +
         ParametersText(result.camera, result.refinement ? std::span<const HeldIntrinsic>(result.refinement->held)
                                                         : std::span<const HeldIntrinsic>());
  text += FisheyeStartText(result);
  if (result.refinement) {
    const Refinement& r = *result.refinement;
    char buf[200];
    std::snprintf(buf, sizeof buf, "  refinement: %d iterations, sigma %.4f px (%d dof), %zu outliers\n", r.iterations,
                  r.sigma_px, r.dof, r.outliers.size());
    text += buf;
    text += PriorsAndConditioningText(r);
  }
  if (options.reject_views.enabled && result.rejection_sigma_px) {
    const auto views = std::count_if(result.rejections.begin(), result.rejections.end(),
                                     [](const Rejection& x) { return x.kind == Rejection::Kind::kView; });
    char buf[240];
    std::snprintf(buf, sizeof buf, "  view rejection: %td views and %td corners rejected in %d rounds, robust sigma %.4f px\n",
                  views, static_cast<std::ptrdiff_t>(result.rejections.size()) - views, result.rejection_rounds,
                  *result.rejection_sigma_px);
    text += buf;
  }
  text += UncertaintySummary(result, files.uncertainty);
  text += "  wrote " + files.output + (files.residuals.empty() ? "" : " and " + files.residuals) + "\n";
  if (!files.undistort_folder.empty()) {
    text += "  wrote " + std::to_string(outcome.files.size() - before) + " undistorted images (<view>.undistorted.png) in " +
            files.undistort_folder + (without_image ? " (" + std::to_string(without_image) + " views name no image)" : "") + "\n";
  }
  return outcome;
}

Outcome CalibrateHalves(const Correspondences& corners, const CalibrationOptions& options, const CalibrationFiles& files,
                        const Provenance& provenance) {
  if (corners.views.size() < 2) {
    throw InputError(VSTCAL_OPT("split_halves") ": " + files.input + " has " + std::to_string(corners.views.size()) +
                     " view; halves need at least one view each (two calibrations need twice the views one needs)");
  }
  Outcome out;
  const std::filesystem::path output(files.output);
  for (int half = 0; half < 2; ++half) {
    const std::string name = half == 0 ? "a" : "b";
    Correspondences part = corners;
    part.views.clear();
    for (size_t v = static_cast<size_t>(half); v < corners.views.size(); v += 2) part.views.push_back(corners.views[v]);
    const CalibrationResult result = Calibrate(part, options);
    const std::string where = VSTCAL_OPT("split_halves") ": half " + name + " (" + std::to_string(part.views.size()) + " views)";
    if (result.exit_code != ExitCode::kOk) throw Error(result.exit_code, where + ": " + result.message + "; give more views");
    CalibrationFiles half_files = files;
    half_files.input = files.input + " (half " + name + ")";
    half_files.output = (output.parent_path() / (output.stem().string() + ".half-" + name + ".json")).string();
    half_files.residuals.clear();
    half_files.undistort_folder.clear();  // the check images are the whole's
    Outcome one = CalibrationOutcome(result, options, half_files, provenance);
    out.files.push_back(std::move(one.files.front()));
    for (std::string& w : one.warnings) out.warnings.push_back(std::move(w));
    char line[160];
    std::snprintf(line, sizeof line, "  half %s: %zu views, RMS %.4f px; wrote %s\n", name.c_str(), part.views.size(),
                  result.camera.fit ? result.camera.fit->overall.rms_px : 0.0, half_files.output.c_str());
    out.summary += line;
  }
  return out;
}

}  // namespace vstcal::app
