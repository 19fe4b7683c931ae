#include "vstcal/app/calibration.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "vstcal/core/error.h"
#include "vstcal/formats/calib/calibration_io.h"
#include "vstcal/formats/calib/residuals_io.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/report/fit_summary.h"

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
    outcome.warnings.push_back(files.tool + ": warning: --reject-views: rejected " + what + " in round " +
                               std::to_string(x.round) + ": " + x.because);
  }
  OrderedJson blocks = CalibrationBlocksToJson(result, options);
  if (result.camera.covariance) blocks["projection_uncertainty"] = UncertaintyToJson(result.camera, files.uncertainty);
  outcome.files.emplace_back(files.output, DumpJson(CameraToJson(result.camera, provenance, blocks)));
  if (!files.residuals.empty()) {
    outcome.files.emplace_back(files.residuals, DumpJson(ResidualsToJson(result.used, *result.camera.fit, provenance)));
  }
  std::string& text = outcome.summary;
  text = files.tool + ": " + files.input + ": " + std::to_string(NumObservations(result.used)) + " points in " +
         std::to_string(result.used.views.size()) + " views, method " + result.camera.method + "\n" +
         FitSummaryText(result.camera) +
         ParametersText(result.camera, result.refinement ? std::span<const HeldIntrinsic>(result.refinement->held)
                                                         : std::span<const HeldIntrinsic>());
  if (result.refinement) {
    const Refinement& r = *result.refinement;
    char buf[200];
    std::snprintf(buf, sizeof buf, "  refinement: %d iterations, sigma %.4f px (%d dof), %zu outliers\n", r.iterations,
                  r.sigma_px, r.dof, r.outliers.size());
    text += buf;
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
  return outcome;
}

Outcome CalibrateHalves(const Correspondences& corners, const CalibrationOptions& options, const CalibrationFiles& files,
                        const Provenance& provenance) {
  if (corners.views.size() < 2) {
    throw InputError("--split-halves: " + files.input + " has " + std::to_string(corners.views.size()) +
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
    const std::string where = "--split-halves: half " + name + " (" + std::to_string(part.views.size()) + " views)";
    if (result.exit_code != ExitCode::kOk) throw Error(result.exit_code, where + ": " + result.message + "; give more views");
    CalibrationFiles half_files = files;
    half_files.input = files.input + " (half " + name + ")";
    half_files.output = (output.parent_path() / (output.stem().string() + ".half-" + name + ".json")).string();
    half_files.residuals.clear();
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
