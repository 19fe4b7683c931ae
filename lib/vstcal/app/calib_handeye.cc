#include "vstcal/app/calib_handeye.h"

#include <cmath>
#include <cstdio>

#include "vstcal/core/error.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/handeye/handeye_io.h"
#include "vstcal/formats/handeye/pose_log_io.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/handeye/refine.h"

namespace vstcal::app {
namespace {

std::string Line(const char* format, double a, double b, const char* unit) {
  char buf[120];
  std::snprintf(buf, sizeof buf, format, a, b, unit);
  return buf;
}

}  // namespace

Outcome MeasureTrackerNoise(const TrackerNoiseRequest& request, const Provenance& provenance) {
  const auto tum_unit = LengthUnitFromName(request.tum_unit);
  if (!tum_unit) throw InputError("--tum-unit: \"" + request.tum_unit + "\" is not a length unit; use mm, cm, m or in");
  if (!(request.to > request.from)) throw InputError("--to: must be after --from (the static segment, in the tracker's seconds)");
  if (!(request.max_motion > 0)) throw InputError("--max-motion: give the largest drift (mm) a held headset may show, > 0");
  // The σ's are reported in millimetres whatever the log's unit.
  const PoseLog log = InUnit(ReadPoseLog(request.poses, *tum_unit), LengthUnit::kMillimetre);
  const TrackerNoise n = [&] {
    try {
      return EstimateTrackerNoise(log.poses, request.from, request.to, request.max_motion);
    } catch (const DegenerateError& e) {
      throw DegenerateError(request.poses + ": " + e.what());
    }
  }();
  Outcome out;
  if (!request.output.empty()) out.files.emplace_back(request.output, DumpJson(TrackerNoiseToJson(n, LengthUnit::kMillimetre, provenance)));
  const double deg = 180 / M_PI;
  char buf[300];
  std::snprintf(buf, sizeof buf,
                "calib-handeye noise: %zu reports from %.3f to %.3f s, the headset held still\n"
                "  rotation σ %.4f° (95%% interval %.4f … %.4f°; per axis %.4f, %.4f, %.4f°)\n"
                "  translation σ %.4f mm (95%% interval %.4f … %.4f mm; per axis %.4f, %.4f, %.4f mm)\n",
                n.reports, n.from, n.to, n.rotation.sigma * deg, n.rotation.lower * deg, n.rotation.upper * deg, n.rotation.per_axis.x() * deg,
                n.rotation.per_axis.y() * deg, n.rotation.per_axis.z() * deg, n.translation.sigma, n.translation.lower, n.translation.upper,
                n.translation.per_axis.x(), n.translation.per_axis.y(), n.translation.per_axis.z());
  out.summary = buf;
  out.summary += "  the interval assumes independent reports; a tracker that filters its output correlates them, and the σ is then the "
                 "jitter of one report, not of an average\n";
  if (!request.output.empty()) out.summary += "  wrote " + request.output + "\n";
  return out;
}

Outcome SolveHandEyeFiles(const HandEyeRequest& request, const Provenance& provenance) {
  if (request.output.empty()) throw InputError("-o/--output: give the handeye@1 file to write");
  const auto tum_unit = LengthUnitFromName(request.tum_unit);
  if (!tum_unit) throw InputError("--tum-unit: \"" + request.tum_unit + "\" is not a length unit; use mm, cm, m or in");
  if (!(request.max_time_offset > 0 && request.max_time_offset <= 10)) {
    throw InputError("--max-time-offset: " + MessageNumber(request.max_time_offset) + " s; give the largest offset to search, > 0 and ≤ 10 s");
  }
  const CalibratedCamera camera = ReadCamera(request.camera);
  const Correspondences corners = ReadCorrespondences(request.corners);
  if (corners.rig != Rig::kPlanarViews) {
    throw InputError(request.corners + ": rig: hand-eye calibration takes a board seen from a moving headset (rig \"planar-views\")");
  }
  if (corners.image_size.width != camera.camera.image_size.width || corners.image_size.height != camera.camera.image_size.height) {
    throw InputError(request.corners + ": image_size: the views are " + std::to_string(corners.image_size.width) + "x" +
                     std::to_string(corners.image_size.height) + " but " + request.camera + " is a camera of " +
                     std::to_string(camera.camera.image_size.width) + "x" + std::to_string(camera.camera.image_size.height) +
                     "; give the camera that took the images");
  }
  std::vector<TimedView> views;
  for (size_t i = 0; i < corners.views.size(); ++i) {
    const View& v = corners.views[i];
    if (!v.time) {
      throw InputError(request.corners + ": views[" + std::to_string(i) + "].time: missing (view \"" + v.name +
                       "\"); every view needs the time its image was taken (calib-capture detect writes it for video frames)");
    }
    views.push_back({v.name, *v.time, v.observations});
  }
  const PoseLog log = InUnit(ReadPoseLog(request.poses, *tum_unit), corners.length_unit);
  HandEyeOptions options;
  options.max_time_offset = request.max_time_offset;
  options.rejection.enabled = !request.keep_all_views;
  const HandEyeSolution s = [&] {
    try {
      return SolveHandEye(camera.camera, log.poses, views, options);
    } catch (const DegenerateError& e) {
      throw DegenerateError(request.corners + " with " + request.poses + ": " + e.what());
    } catch (const InputError& e) {
      throw InputError(request.corners + " with " + request.poses + ": " + e.what());
    }
  }();
  Outcome out;
  out.files.emplace_back(request.output, DumpJson(HandEyeToJson(s, corners.length_unit, provenance)));
  if (!request.opencv.empty()) out.files.emplace_back(request.opencv, HandEyeOpenCvYaml(s, corners.length_unit, provenance));
  const std::string unit(LengthUnitName(corners.length_unit));
  const auto sigma = [&](int i) { return std::sqrt(s.covariance(i, i)); };
  // A translation's σ: the left perturbation moves t by dt = −[t]× ω + ρ, so the rotation's
  // uncertainty reaches it through its lever (docs/math/handeye.md#refinement).
  const auto translation_sigma = [&](const Rigid3d& pose, int first) {
    Eigen::Matrix<double, 3, 6> J;
    J << -Hat(pose.t), Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d cov = J * s.covariance.block<6, 6>(first, first) * J.transpose();
    return Eigen::Vector3d(std::sqrt(cov(0, 0)), std::sqrt(cov(1, 1)), std::sqrt(cov(2, 2)));
  };
  const Eigen::Vector3d sx = translation_sigma(s.hmd_from_camera, 0), sz = translation_sigma(s.tracker_from_board, 6);
  const double deg = 180 / M_PI;
  std::string& t = out.summary;
  t = "calib-handeye: " + std::to_string(s.views) + " views" +
      (s.rejected.empty() ? std::string() : " (of " + std::to_string(s.views + s.rejected.size()) + "; bad frames dropped below)") + ", " + std::to_string(s.corners) + " corners, " +
      std::to_string(log.poses.size()) + " tracker reports\n";
  t += Line("  time offset: %.4f ms ± %.4f ms%s (the tracker's clock reads t + offset at the camera's t)\n", s.time_offset * 1000,
            sigma(12) * 1000, "");
  const Eigen::Vector3d rx = RotvecFromRotation(s.hmd_from_camera.R) * deg;
  char buf[200];
  std::snprintf(buf, sizeof buf, "  hmd_from_camera: t (%.3f, %.3f, %.3f) %s ± (%.3f, %.3f, %.3f); rotation %.3f° ± (%.3f, %.3f, %.3f)°\n",
                s.hmd_from_camera.t.x(), s.hmd_from_camera.t.y(), s.hmd_from_camera.t.z(), unit.c_str(), sx.x(), sx.y(), sx.z(),
                rx.norm(), sigma(0) * deg, sigma(1) * deg, sigma(2) * deg);
  t += buf;
  std::snprintf(buf, sizeof buf, "  tracker_from_board: t (%.3f, %.3f, %.3f) %s ± (%.3f, %.3f, %.3f)\n", s.tracker_from_board.t.x(),
                s.tracker_from_board.t.y(), s.tracker_from_board.t.z(), unit.c_str(), sz.x(), sz.y(), sz.z());
  t += buf;
  t += Line("  fit: RMS %.4f px, sigma %.4f px%s\n", s.rms_px, s.sigma_px, "");
  for (const Rejection& r : s.rejected) {
    t += "  dropped view \"" + r.view_name + "\" (RMS " + MessageNumber(r.rms_px) + " px, threshold " + MessageNumber(r.threshold_px) +
         " px): " + r.because + "\n";
  }
  for (const std::string& w : s.warnings) t += "  warning: " + w + "\n";
  t += "  wrote " + request.output + (request.opencv.empty() ? "" : " and " + request.opencv) + "\n";
  return out;
}

}  // namespace vstcal::app
