#include "vstcal/app/calib_handeye.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdio>

#include "vstcal/core/error.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/handeye/handeye_io.h"
#include "vstcal/formats/handeye/pose_log_io.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/handeye/bootstrap.h"
#include "vstcal/handeye/report_phases.h"
#include "vstcal/handeye/refine.h"
#include "vstcal/scene/view_keys.h"
#include "vstcal/core/option_name.h"

namespace vstcal::app {
namespace {

std::string Line(const char* format, double a, double b, const char* unit) {
  char buf[120];
  std::snprintf(buf, sizeof buf, format, a, b, unit);
  return buf;
}

std::string SizeText(const ImageSize& size) { return std::to_string(size.width) + "x" + std::to_string(size.height); }

// The views must be the camera's: the same image size.
void CheckSize(const Correspondences& views, const std::string& file, const Camera& camera, const std::string& camera_source) {
  if (views.image_size.width != camera.image_size.width || views.image_size.height != camera.image_size.height) {
    throw InputError(file + ": image_size: the views are " + SizeText(views.image_size) + " but " + camera_source + " is a camera of " +
                     SizeText(camera.image_size) + "; give the camera that took the images");
  }
}

std::vector<TimedView> TimedViews(const Correspondences& corners, const std::string& file) {
  if (corners.rig != Rig::kPlanarViews) {
    throw InputError(file + ": rig: hand-eye calibration takes a board seen from a moving headset (rig \"planar-views\")");
  }
  std::vector<TimedView> views;
  for (size_t i = 0; i < corners.views.size(); ++i) {
    const View& v = corners.views[i];
    if (!v.time) {
      throw InputError(file + ": views[" + std::to_string(i) + "].time: missing (view \"" + v.name +
                       "\"); every view needs the time its image was taken (calib-capture detect writes it for video frames)");
    }
    views.push_back({v.name, *v.time, v.observations});
  }
  return views;
}

// Two views of one instant by a rig's cameras are paired by time within this (s).
constexpr double kPairingTolerance = 1e-3;

// Every right view must be the right camera's view of an instant the left camera saw too: paired
// by name (the same name, or names differing by a left/right token: DeriveViewPairing), else by
// time. Returns how they were paired; InputError naming the first view that pairs with none.
std::string PairRightViews(const Correspondences& left, const std::string& left_file, const Correspondences& right, const std::string& right_file) {
  const std::vector<std::string> left_names = ViewNames(left), right_names = ViewNames(right);
  const auto all_paired = [&](const std::vector<std::string>& left_keys, const std::vector<std::string>& right_keys) {
    return std::all_of(right_keys.begin(), right_keys.end(),
                       [&](const std::string& k) { return std::find(left_keys.begin(), left_keys.end(), k) != left_keys.end(); });
  };
  if (ShareAName(left_names, right_names)) {
    if (all_paired(left_names, right_names)) return "by name";
  } else if (const DerivedPairing derived = DeriveViewPairing(left_names, right_names); derived.pairing) {
    Correspondences l = left, r = right;
    KeyViews(derived.pairing->match_views, left_file, &l);
    KeyViews(derived.pairing->match_views, right_file, &r);
    if (all_paired(ViewNames(l), ViewNames(r))) return "by name (" + derived.pairing->rule + ")";
  }
  for (size_t i = 0; i < right.views.size(); ++i) {
    const std::optional<double> t = right.views[i].time;
    const bool paired = t && std::any_of(left.views.begin(), left.views.end(),
                                         [&](const View& v) { return v.time && std::abs(*v.time - *t) <= kPairingTolerance; });
    if (!paired) {
      throw InputError(right_file + ": views[" + std::to_string(i) + "]: the right camera's view \"" + right.views[i].name +
                       "\" pairs with no view of " + left_file + ", by name or by time (within 1 ms); give each instant's two views " +
                       "names differing only by left/right (left01, right01) or the same time");
    }
  }
  return "by time";
}

}  // namespace

Outcome MeasureTrackerNoise(const TrackerNoiseRequest& request, const Provenance& provenance) {
  const auto tum_unit = LengthUnitFromName(request.tum_unit);
  if (!tum_unit) throw InputError(VSTCAL_OPT("tum_unit") ": \"" + request.tum_unit + "\" is not a length unit; use mm, cm, m or in");
  if (!(request.to > request.from)) throw InputError(VSTCAL_OPT("to") ": must be after " VSTCAL_OPT("from") " (the static segment, in the tracker's seconds)");
  if (!(request.max_motion > 0)) throw InputError(VSTCAL_OPT("max_motion") ": give the largest drift (mm) a held headset may show, > 0");
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
  if (request.output.empty()) throw InputError(VSTCAL_OPT("output") ": give the handeye@1 file to write");
  const auto tum_unit = LengthUnitFromName(request.tum_unit);
  if (!tum_unit) throw InputError(VSTCAL_OPT("tum_unit") ": \"" + request.tum_unit + "\" is not a length unit; use mm, cm, m or in");
  if (!(request.max_time_offset > 0 && request.max_time_offset <= 10)) {
    throw InputError(VSTCAL_OPT("max_time_offset") ": " + MessageNumber(request.max_time_offset) + " s; give the largest offset to search, > 0 and ≤ 10 s");
  }
  if (request.rig.empty() != request.right_corners.empty()) {
    throw InputError(request.rig.empty() ? "rig: the right camera's views are given without the rig; give the stereo@1 file whose right_from_left joins them"
                                         : "right_corners: a rig is given without the right camera's views; give their corners (correspondences@1)");
  }
  if (!request.rig.empty() && !request.camera.empty()) {
    throw InputError("camera: a rig is given, whose left camera took the views; give either the rig or a camera, not both");
  }
  if (request.rig.empty() && request.camera.empty()) throw InputError("camera: give the camera that took the views (camera@1), or a rig");
  if (const int b = request.bootstrap.value_or(0); b < 0 || b == 1 || b > 100000) {
    throw InputError(VSTCAL_OPT("bootstrap") ": " + std::to_string(b) + " replicates; give 2 … 100000 (e.g. 100), or 0 for none");
  }
  if (request.threads > 256) throw InputError(VSTCAL_OPT("threads") ": " + std::to_string(request.threads) + "; give 0 (all cores) … 256");
  const std::optional<StereoRig> stereo = request.rig.empty() ? std::nullopt : std::optional<StereoRig>(ReadStereoRig(request.rig));
  const Camera camera = stereo ? stereo->left.camera : ReadCamera(request.camera).camera;
  const Correspondences corners = ReadCorrespondences(request.corners);
  CheckSize(corners, request.corners, camera, stereo ? request.rig + "'s left camera" : request.camera);
  const std::vector<TimedView> views = TimedViews(corners, request.corners);
  std::optional<HandEyeRig> rig;
  HandEyeRigFile rig_file;
  if (stereo) {
    const Correspondences right = ReadCorrespondences(request.right_corners);
    CheckSize(right, request.right_corners, stereo->right.camera, request.rig + "'s right camera");
    if (right.length_unit != corners.length_unit) {
      throw InputError(request.right_corners + ": length_unit: " + std::string(LengthUnitName(right.length_unit)) + ", but " + request.corners +
                       " is in " + std::string(LengthUnitName(corners.length_unit)) + "; give both cameras' boards in one unit");
    }
    rig = HandEyeRig{stereo->right.camera, stereo->right_from_left, TimedViews(right, request.right_corners)};
    // right_from_left's translation in the corners' unit.
    rig->right_from_left.t *= MetresPer(stereo->length_unit) / MetresPer(corners.length_unit);
    rig_file = {request.rig, request.right_corners, PairRightViews(corners, request.corners, right, request.right_corners)};
  }
  const PoseLog log = InUnit(ReadPoseLog(request.poses, *tum_unit), corners.length_unit);
  HandEyeOptions options;
  options.max_time_offset = request.max_time_offset;
  options.rejection.enabled = !request.keep_all_views;
  options.estimate_tracker_noise = !request.tracker_exact;
  const HandEyeSolution s = [&] {
    try {
      return SolveHandEye(camera, log.poses, views, options, rig ? &*rig : nullptr);
    } catch (const DegenerateError& e) {
      throw DegenerateError(request.corners + " with " + request.poses + ": " + e.what());
    } catch (const InputError& e) {
      throw InputError(request.corners + " with " + request.poses + ": " + e.what());
    }
  }();
  // The bootstrap runs only when asked for: with δ instrumented, the first-order σ_δ is as near δ̂'s
  // spread as the bootstrap's wherever the views fall (docs/tools/calib-handeye.md#bootstrap), and
  // costs nothing.
  const int replicates = request.bootstrap.value_or(0);
  std::optional<HandEyeBootstrap> bootstrap;
  if (replicates > 0) {
    try {
      bootstrap = BootstrapHandEye(camera, log.poses, views, s, options, {replicates, request.seed, request.threads}, rig ? &*rig : nullptr);
    } catch (const DegenerateError& e) {
      throw DegenerateError(request.corners + " with " + request.poses + ": " + e.what());  // asked for: its failure is the run's
    }
  }
  // Only a bootstrap that ran drew random numbers: the seed is in the provenance then only.
  Provenance written = provenance;
  if (!bootstrap) written.seed.reset();
  Outcome out;
  out.files.emplace_back(request.output,
                         DumpJson(HandEyeToJson(s, corners.length_unit, written, rig ? &rig_file : nullptr, bootstrap ? &*bootstrap : nullptr)));
  if (!request.opencv.empty()) out.files.emplace_back(request.opencv, HandEyeOpenCvYaml(s, corners.length_unit, written));
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
  const std::string counted = rig ? std::to_string(s.views - s.right_views) + " left + " + std::to_string(s.right_views) + " right" : std::to_string(s.views);
  t = "calib-handeye: " + counted + " views" +
      (s.rejected.empty() ? std::string() : " (of " + std::to_string(s.views + s.rejected.size()) + "; bad frames dropped below)") + ", " + std::to_string(s.corners) + " corners, " +
      std::to_string(log.poses.size()) + " tracker reports\n";
  // The offset's σ is the bootstrap's when one ran (what err-sim's latency takes), else the first
  // order's; the line says which.
  if (bootstrap) {
    char line[300];
    std::snprintf(line, sizeof line,
                  "  time offset: %.4f ms ± %.4f ms, σ by the bootstrap (%d of %d replicates solved; first-order ± %.4f ms, bias %+.4f ms)\n",
                  s.time_offset * 1000, std::sqrt(bootstrap->covariance(12, 12)) * 1000, bootstrap->solved, bootstrap->replicates,
                  sigma(12) * 1000, bootstrap->mean[12] * 1000);
    t += line;
  } else {
    t += Line("  time offset: %.4f ms ± %.4f ms%s, σ first-order (", s.time_offset * 1000, sigma(12) * 1000, "");
    t += VSTCAL_OPT("bootstrap") " B also runs the bootstrap)\n";
  }
  t += "    (the tracker's clock reads t + offset at the camera's t)\n";
  const ReportPhases& phases = s.report_phases;
  char where[160];
  if (phases.Locked()) {
    std::snprintf(where, sizeof where, "    the views sit at one place between the tracker's reports, %.2f of the way (concentration %.2f)\n", phases.mean,
                  phases.concentration);
  } else {
    std::snprintf(where, sizeof where, "    the views fall at many places between the tracker's reports (concentration %.2f)\n", phases.concentration);
  }
  t += where;
  const Eigen::Vector3d rx = RotvecFromRotation(s.hmd_from_camera.R) * deg;
  char buf[400];
  std::snprintf(buf, sizeof buf, "  hmd_from_camera: t (%.3f, %.3f, %.3f) %s ± (%.3f, %.3f, %.3f); rotation %.3f° ± (%.3f, %.3f, %.3f)°\n",
                s.hmd_from_camera.t.x(), s.hmd_from_camera.t.y(), s.hmd_from_camera.t.z(), unit.c_str(), sx.x(), sx.y(), sx.z(),
                rx.norm(), sigma(0) * deg, sigma(1) * deg, sigma(2) * deg);
  t += buf;
  std::snprintf(buf, sizeof buf, "  tracker_from_board: t (%.3f, %.3f, %.3f) %s ± (%.3f, %.3f, %.3f)\n", s.tracker_from_board.t.x(),
                s.tracker_from_board.t.y(), s.tracker_from_board.t.z(), unit.c_str(), sz.x(), sz.y(), sz.z());
  t += buf;
  t += Line("  fit: RMS %.4f px, sigma %.4f px%s\n", s.rms_px, s.sigma_px, "");
  if (s.tracker_noise) {
    const JointTrackerNoise& n = *s.tracker_noise;
    std::snprintf(buf, sizeof buf,
                  "  tracker noise (estimated jointly, %zu instants): rotation %.4f° ± %.4f° (95%% %.4f … %.4f°), translation %.4f %s ± %.4f "
                  "(95%% %.4f … %.4f)\n",
                  n.frames, n.rotation.sigma * deg, n.rotation.sigma_sigma * deg, n.rotation.lower * deg, n.rotation.upper * deg,
                  n.translation.sigma, unit.c_str(), n.translation.sigma_sigma, n.translation.lower, n.translation.upper);
    t += buf;
  } else {
    t += "  tracker noise: not estimated, the poses taken as exact\n";
  }
  if (rig) {
    t += "  rig: " + request.rig + " (right_from_left held; baseline " + MessageNumber(rig->right_from_left.t.norm()) + " " + unit +
         "), the right camera's views paired " + rig_file.pairing + "\n";
  }
  for (const Rejection& r : s.rejected) {
    t += "  dropped view \"" + r.view_name + "\" (RMS " + MessageNumber(r.rms_px) + " px, threshold " + MessageNumber(r.threshold_px) +
         " px): " + r.because + "\n";
  }
  for (const std::string& w : s.warnings) t += "  warning: " + w + "\n";
  t += "  wrote " + request.output + (request.opencv.empty() ? "" : " and " + request.opencv) + "\n";
  return out;
}

}  // namespace vstcal::app
