#include "vstcal/report/stereo_report.h"

#include <map>
#include <set>
#include <tuple>

#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/geometry/registration_error.h"
#include "vstcal/estimators/pose_refine.h"
#include "vstcal/scene/view_keys.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

std::string SizeText(const ImageSize& s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

void CheckInputs(const StereoRig& rig, const Correspondences& left, const Correspondences& right,
                 const std::string& rig_file, const std::string& left_file, const std::string& right_file) {
  const auto check = [&](const CalibratedCamera& cam, const char* eye, const Correspondences& c, const std::string& file) {
    if (!(cam.camera.image_size == c.image_size)) {
      throw InputError(file + ": image_size: " + SizeText(c.image_size) + " differs from " + rig_file + "'s " + eye +
                       " camera (" + SizeText(cam.camera.image_size) + "); give the " + eye +
                       " camera's correspondences of the images the rig was calibrated from");
    }
    if (c.length_unit != rig.length_unit) {
      throw InputError(file + ": length_unit: \"" + std::string(LengthUnitName(c.length_unit)) + "\" differs from " +
                       rig_file + "'s \"" + std::string(LengthUnitName(rig.length_unit)) +
                       "\"; convert one of them (calib-convert) so that both use one unit");
    }
    std::set<std::string> names;
    for (const View& v : c.views) {
      if (!names.insert(v.name).second) {
        throw InputError(file + ": views: the view key \"" + v.name + "\" is given twice (views are matched by name, or by " VSTCAL_OPT("match_views") "' key): rename one");
      }
    }
  };
  check(rig.left, "left", left, left_file);
  check(rig.right, "right", right, right_file);
  if (left.rig != right.rig) {
    throw InputError(left_file + " and " + right_file +
                     ": rig: one is a volume and the other planar views; give both cameras' views of the same target");
  }
}

using Key = std::tuple<double, double, double>;
Key KeyOf(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// Target point → its observation's index in the view; a point twice is bad input.
std::map<Key, size_t> IndexPoints(const View& view, const std::string& file) {
  std::map<Key, size_t> index;
  for (size_t i = 0; i < view.observations.size(); ++i) {
    if (!index.emplace(KeyOf(view.observations[i].point), i).second) {
      const Eigen::Vector3d& p = view.observations[i].point;
      throw InputError(file + ": views[\"" + view.name + "\"].points[" + std::to_string(i) + "]: the target point (" +
                       std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " + std::to_string(p.z()) +
                       ") is listed twice; points are matched between the cameras by their target coordinates: "
                       "remove the duplicate");
    }
  }
  return index;
}

// The left camera's pose from the left pixels of `views` (all of a volume's, or one planar view's).
PoseRefinement LeftPose(const StereoRig& rig, std::span<const View* const> views) {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> pixels;
  for (const View* v : views) {
    for (const Observation& o : v->observations) {
      points.push_back(o.point);
      pixels.push_back(o.pixel);
    }
  }
  return SolvePnp(rig.left.camera, points, pixels);
}

// The 3-D error of the point seen at `left_px` and `right_px` whose true left-frame position is `truth`.
StereoPointError Measure(const StereoRig& rig, const Eigen::Vector3d& truth, const Eigen::Vector2d& left_px,
                         const Eigen::Vector2d& right_px) {
  StereoPointError e;
  e.truth = truth;
  const auto ray_left = rig.left.camera.UnprojectRay(left_px);  // directions (a fisheye's may be past 90°)
  const auto ray_right = rig.right.camera.UnprojectRay(right_px);
  const Eigen::Matrix3d left_from_right_R = rig.right_from_left.R.transpose();
  const Eigen::Vector3d right_centre = -(left_from_right_R * rig.right_from_left.t);
  Eigen::Vector3d seen;
  if (!ray_left || !ray_right ||
      !TriangulateMidpoint<double>(Eigen::Vector3d::Zero(), *ray_left, right_centre, left_from_right_R * *ray_right, &seen)) {
    e.excluded = StereoExclusion::kNoRay;
    return e;
  }
  if (!(seen.z() > 0)) {
    e.excluded = StereoExclusion::kBehind;
    return e;
  }
  e.triangulated = seen;
  const RegistrationErrorOf<double> reg = RegistrationError<double>(0.5 * right_centre, truth, seen - truth);
  e.linear = reg.linear;
  e.lateral = reg.lateral;
  e.depth = reg.depth;
  e.angular_rad = reg.angular;
  return e;
}

struct Collected {
  std::vector<double> x, y, z, linear, lateral, depth, angular_deg;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double depth_sum = 0;
  void Add(const StereoPointError& e) {
    if (e.excluded != StereoExclusion::kNone) return;
    const Eigen::Vector3d d = e.error();
    x.push_back(std::abs(d.x()));
    y.push_back(std::abs(d.y()));
    z.push_back(std::abs(d.z()));
    linear.push_back(e.linear);
    lateral.push_back(e.lateral);
    depth.push_back(std::abs(e.depth));
    angular_deg.push_back(e.angular_deg());
    sum += d;
    depth_sum += e.depth;
  }
  StereoStats Stats() const {
    StereoStats s{ComputeErrorStats(x),       ComputeErrorStats(y),     ComputeErrorStats(z),
                  ComputeErrorStats(linear),  ComputeErrorStats(lateral), ComputeErrorStats(depth),
                  ComputeErrorStats(angular_deg)};
    if (!x.empty()) {
      const double n = static_cast<double>(x.size());
      s.bias = sum / n;
      s.depth_bias = depth_sum / n;
    }
    return s;
  }
};

// One camera's reprojected points over all common views, for its grid of cells.
struct Reprojected {
  std::vector<Eigen::Vector2d> pixels;
  std::vector<double> error_px;
};

// `view` of `camera`'s file (index `file_view`) reprojected through `camera_from_target` (nullopt:
// the view has no left pose); its points are added to `all`.
StereoReprojection Reproject(const CalibratedCamera& camera, const std::optional<Rigid3d>& camera_from_target,
                             const View& view, size_t file_view, Reprojected* all) {
  StereoReprojection out;
  out.file_view = file_view;
  out.image = view.image;
  std::vector<double> error_px;
  for (const Observation& o : view.observations) {
    PointError e;
    e.measured = o.pixel;
    if (camera_from_target) e.predicted = camera.camera.Project(*camera_from_target * o.point);
    if (!e.predicted) {
      e.excluded = camera_from_target ? Exclusion::kBehindCamera : Exclusion::kNoPose;
    } else {
      e.error_px = (*e.predicted - o.pixel).norm();
      error_px.push_back(e.error_px);
      all->pixels.push_back(o.pixel);
      all->error_px.push_back(e.error_px);
    }
    out.points.push_back(e);
  }
  out.error_px = ComputeErrorStats(error_px);
  return out;
}

// A volume's test points, matched by name, measured where both files give a pixel.
void AddTestPoints(const StereoRig& rig, const PoseRefinement& pose, const Correspondences& left,
                   const Correspondences& right, StereoReport* report) {
  std::map<std::string, const TestPoint*> right_by_name;
  for (const TestPoint& t : right.test_points) right_by_name.emplace(t.name, &t);
  std::set<std::string> left_names;
  Collected measured, inside, outside;
  for (const TestPoint& t : left.test_points) {
    left_names.insert(t.name);
    StereoTestPoint out{t.name, t.point_in_world, {}, {}};
    out.inside_volume = report->volume.Contains(t.point_in_world);
    const auto it = right_by_name.find(t.name);
    const bool in_right = it != right_by_name.end() && it->second->pixel;
    if (!t.pixel || !in_right) {
      out.error.excluded = t.pixel ? StereoExclusion::kLeftOnly
                                   : (in_right ? StereoExclusion::kRightOnly : StereoExclusion::kNotMeasured);
    } else if (pose.status != PoseStatus::kOk) {
      out.error.excluded = StereoExclusion::kNoPose;
    } else {
      out.error = Measure(rig, pose.body_from_world * t.point_in_world, *t.pixel, *it->second->pixel);
    }
    out.error.target = t.point_in_world;
    measured.Add(out.error);
    if (out.inside_volume) (*out.inside_volume ? inside : outside).Add(out.error);
    report->test_points.push_back(std::move(out));
  }
  for (const TestPoint& t : right.test_points) {
    if (left_names.contains(t.name)) continue;
    StereoTestPoint out{t.name, t.point_in_world, {}, {}};
    out.inside_volume = report->volume.Contains(t.point_in_world);
    out.error.target = t.point_in_world;
    out.error.excluded = t.pixel ? StereoExclusion::kRightOnly : StereoExclusion::kNotMeasured;
    report->test_points.push_back(std::move(out));
  }
  report->test_stats = measured.Stats();
  report->test_inside = inside.Stats();
  report->test_outside = outside.Stats();
}

}  // namespace

double StereoPointError::angular_deg() const { return RadToDeg(angular_rad); }

std::string_view StereoExclusionName(StereoExclusion e) {
  return NameOf(kStereoExclusionNames, e);
}

std::vector<std::string> ExclusionNotes(const StereoReport& report) {
  std::vector<std::string> notes;
  size_t total = 0;
  for (const StereoViewReport& view : report.views) total += view.points.size();
  const size_t left_out = report.n_left_only + report.n_right_only + report.n_no_pose + report.n_no_ray + report.n_behind;
  if (left_out > 0) {
    std::string why;
    const auto add = [&why](size_t n, const std::string& what) {
      if (n > 0) why += (why.empty() ? "" : ", ") + std::to_string(n) + " " + what;
    };
    add(report.n_left_only, "seen by the left camera only");
    add(report.n_right_only, "seen by the right camera only");
    add(report.n_no_pose, "in views without a left pose");
    add(report.n_no_ray, "without two rays that meet");
    add(report.n_behind, "triangulated behind the left camera");
    notes.push_back(report.left_file + " and " + report.right_file + ": " + std::to_string(left_out) + " of " +
                    std::to_string(total) + " points of the views both cameras saw left out of the 3-D statistics: " + why);
  }
  for (const auto& [views, file] : {std::pair{&report.left_only_views, &report.left_file}, std::pair{&report.right_only_views, &report.right_file}}) {
    if (views->empty()) continue;
    std::string names;
    for (const std::string& v : *views) names += (names.empty() ? "" : ", ") + v;
    notes.push_back(*file + ": " + std::to_string(views->size()) + " views the other camera did not see left out (" + names + ")");
  }
  return notes;
}

StereoReport BuildStereoReport(const StereoRig& rig, Correspondences left, Correspondences right,
                               const std::string& rig_file, const std::string& left_file,
                               const std::string& right_file, const StereoReportOptions& options) {
  // The pairing asked for, else the one the rig's solve used.
  const std::string pattern = !options.view_key_pattern.empty() ? options.view_key_pattern
                              : rig.view_pairing                 ? rig.view_pairing->match_views
                                                                 : std::string();
  const std::vector<std::string> names_left = ViewNames(left), names_right = ViewNames(right);
  if (!pattern.empty()) {
    KeyViews(pattern, left_file, &left);
    KeyViews(pattern, right_file, &right);
  }
  CheckInputs(rig, left, right, rig_file, left_file, right_file);
  StereoReport report;
  report.rig_file = rig_file;
  report.left_file = left_file;
  report.right_file = right_file;
  report.length_unit = rig.length_unit;
  report.rig_kind = left.rig;
  report.baseline = rig.baseline();
  const Correspondences* files[] = {&left, &right};
  report.volume = MeasuredVolumeOf(files);

  std::map<std::string, const View*> right_by_name;
  for (const View& v : right.views) right_by_name.emplace(v.name, &v);
  std::vector<std::pair<const View*, const View*>> common;
  std::set<std::string> left_names;
  for (const View& v : left.views) {
    left_names.insert(v.name);
    const auto it = right_by_name.find(v.name);
    if (it == right_by_name.end()) {
      report.left_only_views.push_back(v.name);
    } else {
      common.emplace_back(&v, it->second);
    }
  }
  for (const View& v : right.views) {
    if (!left_names.contains(v.name)) report.right_only_views.push_back(v.name);
  }
  if (common.empty()) {
    const DerivedPairing derived = pattern.empty() ? DeriveViewPairing(names_left, names_right) : DerivedPairing{};
    throw InputError(left_file + " and " + right_file + ": views: no view " + (pattern.empty() ? "name" : "key") +
                     " is in both files; views are matched by name" + (pattern.empty() ? "" : " through \"" + pattern + "\"") +
                     ", as calib-stereo solve matches them: " +
                     (derived.suggestion.empty() ? std::string("give both cameras' views of the same target poses under the same names")
                                                 : "pair them by the number in their names with " VSTCAL_OPT("match_views") " '" + derived.suggestion + "'"));
  }

  // A volume has one world frame: one left pose from every common view's left pixels.
  std::optional<PoseRefinement> volume_pose;
  if (left.rig == Rig::kVolume) {
    std::vector<const View*> lefts;
    for (const auto& [l, r] : common) lefts.push_back(l);
    volume_pose = LeftPose(rig, lefts);
  }

  Collected all;
  Reprojected left_reprojected, right_reprojected;
  for (const auto& [lv, rv] : common) {
    StereoViewReport vr;
    vr.name = lv->name;
    const PoseRefinement pose = volume_pose ? *volume_pose : LeftPose(rig, std::span<const View* const>(&lv, 1));
    vr.pose_status = pose.status == PoseStatus::kOk ? "ok" : std::string(PoseStatusText(pose.status));
    const std::optional<Rigid3d> left_from_target =
        pose.status == PoseStatus::kOk ? std::optional<Rigid3d>(pose.body_from_world) : std::nullopt;
    vr.left = Reproject(rig.left, left_from_target, *lv, static_cast<size_t>(lv - left.views.data()), &left_reprojected);
    vr.right = Reproject(rig.right, left_from_target ? std::optional<Rigid3d>(rig.right_from_left * *left_from_target) : std::nullopt,
                         *rv, static_cast<size_t>(rv - right.views.data()), &right_reprojected);
    const std::map<Key, size_t> right_index = IndexPoints(*rv, right_file);
    IndexPoints(*lv, left_file);  // for its check: a point twice in the left view
    std::vector<bool> right_used(rv->observations.size(), false);
    Collected in_view;
    for (const Observation& o : lv->observations) {
      StereoPointError e;
      const auto it = right_index.find(KeyOf(o.point));
      if (it == right_index.end()) {
        e.excluded = StereoExclusion::kLeftOnly;
      } else {
        right_used[it->second] = true;
        if (pose.status != PoseStatus::kOk) {
          e.excluded = StereoExclusion::kNoPose;
        } else {
          e = Measure(rig, pose.body_from_world * o.point, o.pixel, rv->observations[it->second].pixel);
        }
      }
      e.target = o.point;
      vr.points.push_back(e);
    }
    for (size_t i = 0; i < rv->observations.size(); ++i) {
      if (right_used[i]) continue;
      StereoPointError e;
      e.target = rv->observations[i].point;
      e.excluded = StereoExclusion::kRightOnly;
      vr.points.push_back(e);
    }
    for (const StereoPointError& e : vr.points) {
      report.n_left_only += e.excluded == StereoExclusion::kLeftOnly;
      report.n_right_only += e.excluded == StereoExclusion::kRightOnly;
      report.n_no_pose += e.excluded == StereoExclusion::kNoPose;
      report.n_no_ray += e.excluded == StereoExclusion::kNoRay;
      report.n_behind += e.excluded == StereoExclusion::kBehind;
      in_view.Add(e);
      all.Add(e);
    }
    vr.stats = in_view.Stats();
    report.views.push_back(std::move(vr));
  }
  report.overall = all.Stats();
  for (auto [out, camera, reprojected] : {std::tuple{&report.left_grid, &rig.left, &left_reprojected},
                                          std::tuple{&report.right_grid, &rig.right, &right_reprojected}}) {
    out->grid = ImageGrid{camera->camera.image_size, options.grid_cols, options.grid_rows};
    out->error_px = ComputeGridStats(out->grid, reprojected->pixels, reprojected->error_px);
    out->overall_px = ComputeErrorStats(reprojected->error_px);
  }
  if (volume_pose) AddTestPoints(rig, *volume_pose, left, right, &report);
  return report;
}

}  // namespace vstcal
