#include "vstcal/formats/report/report_format.h"

#include <cstdio>

#include "vstcal/core/string_printf.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/report/report_keys.h"

namespace vstcal {
namespace {

OrderedJson StatsJson(const std::optional<ErrorStats>& s) {
  if (!s) return nullptr;
  namespace key = reproj_key;
  return {{key::kN, s->n}, {key::kMean, s->mean}, {key::kRms, s->rms}, {key::kMedian, s->median}, {key::kP95, s->p95}, {key::kMax, s->max}};
}

OrderedJson MeasureJson(const MeasureStats& m) {
  return {{reproj_key::kErrorPx, StatsJson(m.error_px)}, {reproj_key::kLateral, StatsJson(m.lateral)},
          {reproj_key::kAngularDeg, StatsJson(m.angular_deg)}};
}

OrderedJson Optional(const std::optional<double>& v) { return v ? OrderedJson(*v) : OrderedJson(nullptr); }

// [u, v, du, dv, lateral, angular_deg, z]: the measured pixel, then null from du on when excluded.
OrderedJson PointJson(const PointError& e) {
  OrderedJson p = {e.measured.x(), e.measured.y()};
  if (e.excluded != Exclusion::kNone) {
    for (int i = 0; i < 5; ++i) p.push_back(nullptr);
    return p;
  }
  const Eigen::Vector2d r = *e.predicted - e.measured;
  for (const double x : {r.x(), r.y(), e.lateral, e.angular_deg()}) p.push_back(x);
  p.push_back(Optional(e.normalized));
  return p;
}

OrderedJson ExclusionsJson(const std::vector<PointError>& points) {
  OrderedJson out = OrderedJson::array();
  for (size_t i = 0; i < points.size(); ++i) {
    if (points[i].excluded != Exclusion::kNone) out.push_back({{"index", i}, {"reason", ExclusionName(points[i].excluded)}});
  }
  return out;
}

OrderedJson TestPointJson(const TestPointReport& t) {
  const PointError& e = t.error;
  const bool measured = e.excluded == Exclusion::kNone;
  OrderedJson j;
  j["name"] = t.name;
  j["world"] = MatrixToJson(t.point_in_world);
  j["inside_volume"] = t.inside_volume ? OrderedJson(*t.inside_volume) : OrderedJson(nullptr);
  j["measured"] = e.excluded == Exclusion::kNotMeasured ? OrderedJson(nullptr) : MatrixToJson(e.measured);
  j["predicted"] = measured ? MatrixToJson(*e.predicted) : OrderedJson(nullptr);
  j[reproj_key::kErrorPx] = measured ? OrderedJson(e.error_px) : OrderedJson(nullptr);
  j[reproj_key::kLateral] = measured ? OrderedJson(e.lateral) : OrderedJson(nullptr);
  j[reproj_key::kAngularDeg] = measured ? OrderedJson(e.angular_deg()) : OrderedJson(nullptr);
  j["normalized"] = Optional(e.normalized);
  j["excluded"] = measured ? OrderedJson(nullptr) : OrderedJson(ExclusionName(e.excluded));
  return j;
}

// Cells `{col, row, error_px}` row-major, as the format's cameras[k].grid.
OrderedJson GridJson(const ImageGrid& grid, const std::vector<std::optional<ErrorStats>>& stats) {
  OrderedJson cells = OrderedJson::array();
  const size_t cols = static_cast<size_t>(grid.cols);
  for (size_t i = 0; i < stats.size(); ++i) cells.push_back({{"col", i % cols}, {"row", i / cols}, {"error_px", StatsJson(stats[i])}});
  return cells;
}

OrderedJson CameraJson(const CameraReport& c, const ImageGrid& grid) {
  OrderedJson j;
  j["file"] = c.file;
  j["name"] = c.name;
  j["method"] = c.method;
  OrderedJson parameters = OrderedJson::array();
  for (const ParameterEstimate& p : c.parameters) {
    parameters.push_back(
        {{"name", p.name}, {reproj_key::kValue, p.value}, {reproj_key::kSigma, p.sigma ? OrderedJson(*p.sigma) : OrderedJson(nullptr)}});
  }
  j[reproj_key::kParameters] = std::move(parameters);
  j[reproj_key::kOverall] = MeasureJson(c.overall);
  j[reproj_key::kExcluded] = {{reproj_key::kBehindCamera, c.n_behind_camera}, {"no_pose", c.n_no_pose}, {"no_ray", c.n_no_ray}};
  j[reproj_key::kNormalized] = {{"how", c.normalization},
                     {reproj_key::kCalibrationPoints, StatsJson(c.normalized)},
                     {reproj_key::kChi2PerDof, Optional(c.chi2_per_dof)},
                     {"test_points", StatsJson(c.test_normalized)}};
  OrderedJson views = OrderedJson::array();
  for (const ViewReport& v : c.views) {
    OrderedJson points = OrderedJson::array();
    for (const PointError& e : v.points) points.push_back(PointJson(e));
    views.push_back({{"name", v.name}, {reproj_key::kErrorPx, StatsJson(v.error_px)}, {reproj_key::kExcluded, ExclusionsJson(v.points)},
                     {reproj_key::kPoints, std::move(points)}});
  }
  j[reproj_key::kViews] = std::move(views);
  j["grid"] = GridJson(grid, c.grid);
  if (c.uncertainty_px.empty()) {
    j["projection_uncertainty"] = nullptr;
  } else {
    OrderedJson sigma = OrderedJson::array();
    for (const auto& v : c.uncertainty_px) sigma.push_back(Optional(v));
    j["projection_uncertainty"] = {{"kind", "with_poses"}, {"depth", c.uncertainty_depth}, {"sigma_major_px", std::move(sigma)}};
  }
  OrderedJson tests = OrderedJson::array();
  for (const TestPointReport& t : c.test_points) tests.push_back(TestPointJson(t));
  j[reproj_key::kTestPoints] = {{reproj_key::kInside, MeasureJson(c.test_inside)}, {reproj_key::kOutside, MeasureJson(c.test_outside)},
                      {reproj_key::kPoints, std::move(tests)}};
  return j;
}

void Append(std::string* out, const char* fmt, auto... args) { *out += StringPrintf(fmt, args...); }

void AppendStatsRow(std::string* out, const std::string& label, const std::optional<ErrorStats>& s) {
  if (!s) {
    Append(out, "  %-24s %6s  (no measured point)\n", label.c_str(), "0");
    return;
  }
  Append(out, "  %-24s %6zu %10.4f %10.4f %10.4f %10.4f %10.4f\n", label.c_str(), s->n, s->mean, s->rms, s->median,
         s->p95, s->max);
}

OrderedJson StereoStatsJson(const StereoStats& s) {
  return {{reproj_key::kX, StatsJson(s.x)},
          {reproj_key::kY, StatsJson(s.y)},
          {reproj_key::kZ, StatsJson(s.z)},
          {reproj_key::kLinear, StatsJson(s.linear)},
          {reproj_key::kLateral, StatsJson(s.lateral)},
          {reproj_key::kDepth, StatsJson(s.depth)},
          {reproj_key::kAngularDeg, StatsJson(s.angular_deg)},
          {"bias", MatrixToJson(s.bias)},
          {"depth_bias", s.depth_bias}};
}

// [X, Y, Z, dx, dy, dz, linear, lateral, depth, angular_deg]: the target point, then null from dx
// on when excluded.
OrderedJson StereoPointJson(const StereoPointError& e) {
  OrderedJson p = {e.target.x(), e.target.y(), e.target.z()};
  const bool measured = e.excluded == StereoExclusion::kNone;
  const Eigen::Vector3d d = e.error();
  for (const double x : {d.x(), d.y(), d.z(), e.linear, e.lateral, e.depth, e.angular_deg()}) {
    p.push_back(measured ? OrderedJson(x) : OrderedJson(nullptr));
  }
  return p;
}

// {error_px, excluded, points}: `points[j]` = [u, v, du, dv], du and dv null when excluded.
OrderedJson StereoReprojectionJson(const StereoReprojection& r) {
  OrderedJson points = OrderedJson::array();
  for (const PointError& e : r.points) {
    const bool measured = e.excluded == Exclusion::kNone;
    const Eigen::Vector2d d = measured ? Eigen::Vector2d(*e.predicted - e.measured) : Eigen::Vector2d::Zero();
    points.push_back({e.measured.x(), e.measured.y(), measured ? OrderedJson(d.x()) : OrderedJson(nullptr),
                      measured ? OrderedJson(d.y()) : OrderedJson(nullptr)});
  }
  return {{reproj_key::kErrorPx, StatsJson(r.error_px)}, {reproj_key::kExcluded, ExclusionsJson(r.points)},
          {reproj_key::kPoints, std::move(points)}};
}

void AppendStereoRows(std::string* out, const std::string& prefix, const std::string& unit, const StereoStats& s) {
  AppendStatsRow(out, prefix + "|dx| " + unit, s.x);
  AppendStatsRow(out, prefix + "|dy| " + unit, s.y);
  AppendStatsRow(out, prefix + "|dz| " + unit, s.z);
  AppendStatsRow(out, prefix + "linear " + unit, s.linear);
  AppendStatsRow(out, prefix + "lateral " + unit, s.lateral);
  AppendStatsRow(out, prefix + "|depth| " + unit, s.depth);
  AppendStatsRow(out, prefix + "angular deg", s.angular_deg);
}

}  // namespace

ReportCamera ReadReportCamera(const std::filesystem::path& path) { return ReportCameraFrom(JsonDocument::Load(path), path.string()); }

ReportCamera ReportCameraFrom(const JsonDocument& doc, const std::string& name) {
  ReportCamera rc{name, CameraFromJson(doc), std::nullopt};
  if (const auto refinement = doc.root().find("refinement")) {
    if (const auto sigma = refinement->find("sigma_px")) {
      const double s = sigma->NonNegativeNumber();
      if (s > 0) rc.sigma_px = s;
    }
  }
  // An unrefined DLT camera's σ̂ (its covariance is the DLT's first-order one).
  if (const auto dlt = doc.root().find("dlt"); dlt && !rc.sigma_px) {
    if (const auto u = dlt->find("uncertainty")) {
      const double s = u->at("sigma_px").NonNegativeNumber();
      if (s > 0) rc.sigma_px = s;
    }
  }
  return rc;
}

OrderedJson ReprojReportToJson(const ReprojReport& r, const Provenance& provenance) {
  const Correspondences& c = r.correspondences;
  OrderedJson j;
  j["format"] = "vstcal/reproj-report@1";
  j["correspondences"] = {{"file", r.correspondences_file},
                          {"camera", c.camera},
                          {"image_size", {c.image_size.width, c.image_size.height}},
                          {"length_unit", LengthUnitName(c.length_unit)},
                          {"rig", c.rig == Rig::kVolume ? "volume" : "planar-views"},
                          {"n_views", c.views.size()},
                          {"n_points", NumObservations(c)},
                          {"n_test_points", c.test_points.size()}};
  OrderedJson images = OrderedJson::array();
  for (const View& v : c.views) images.push_back(v.image.empty() ? OrderedJson(nullptr) : OrderedJson(v.image));
  j["correspondences"]["images"] = std::move(images);
  j["grid"] = {{"cols", r.grid.cols}, {"rows", r.grid.rows}};
  j["volume"] = MeasuredVolumeToJson(r.volume);
  OrderedJson cameras = OrderedJson::array();
  for (const CameraReport& cam : r.cameras) cameras.push_back(CameraJson(cam, r.grid));
  j[reproj_key::kCameras] = std::move(cameras);
  OrderedJson differences = OrderedJson::array();
  for (const CameraDifference& d : r.differences) {
    differences.push_back({{"camera", d.camera},
                           {"reference", d.reference},
                           {reproj_key::kPredictionShiftPx, StatsJson(d.prediction_shift_px)},
                           {"rms_change_px", Optional(d.rms_change_px)},
                           {"median_change_px", Optional(d.median_change_px)},
                           {"p95_change_px", Optional(d.p95_change_px)}});
  }
  j[reproj_key::kDifferences] = std::move(differences);
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

std::string ReprojReportText(const ReprojReport& r) {
  std::string out;
  const std::string unit(LengthUnitName(r.correspondences.length_unit));
  Append(&out, "%s: %zu points in %zu views, %zu test points; volume: %s\n", r.correspondences_file.c_str(),
         NumObservations(r.correspondences), r.correspondences.views.size(), r.correspondences.test_points.size(),
         r.volume.status.c_str());
  for (size_t k = 0; k < r.cameras.size(); ++k) {
    const CameraReport& c = r.cameras[k];
    Append(&out, "\ncamera %zu: %s (%s)\n", k, c.file.c_str(), c.method.empty() ? "?" : c.method.c_str());
    Append(&out, "  %-24s %6s %10s %10s %10s %10s %10s\n", "", "n", "mean", "rms", "median", "p95", "max");
    AppendStatsRow(&out, "residual px", c.overall.error_px);
    AppendStatsRow(&out, "lateral " + unit, c.overall.lateral);
    AppendStatsRow(&out, "angular deg", c.overall.angular_deg);
    for (const ViewReport& v : c.views) AppendStatsRow(&out, "view " + v.name + " px", v.error_px);
    if (!c.test_points.empty()) {
      AppendStatsRow(&out, "test inside px", c.test_inside.error_px);
      AppendStatsRow(&out, "test outside px", c.test_outside.error_px);
      AppendStatsRow(&out, "test inside " + unit, c.test_inside.lateral);
      AppendStatsRow(&out, "test outside " + unit, c.test_outside.lateral);
    }
    if (c.chi2_per_dof) {
      Append(&out, "  normalized residuals: chi2 per dof %.3f (1 = consistent with the covariance)\n", *c.chi2_per_dof);
    } else {
      Append(&out, "  normalized residuals: %s\n", c.normalization.c_str());
    }
    const size_t excluded = c.n_behind_camera + c.n_no_pose + c.n_no_ray;
    if (excluded > 0) {
      Append(&out, "  excluded: %zu behind the camera, %zu without a pose, %zu without a ray\n", c.n_behind_camera,
             c.n_no_pose, c.n_no_ray);
    }
  }
  for (const CameraDifference& d : r.differences) {
    Append(&out, "\ncamera %zu vs camera %zu:", d.camera, d.reference);
    if (d.rms_change_px) Append(&out, " rms %+.4f px, median %+.4f px, p95 %+.4f px;", *d.rms_change_px, *d.median_change_px, *d.p95_change_px);
    if (d.prediction_shift_px) {
      Append(&out, " predictions apart by %.4f px mean, %.4f px max\n", d.prediction_shift_px->mean, d.prediction_shift_px->max);
    } else {
      out += " no point predicted by both\n";
    }
  }
  return out;
}

OrderedJson StereoReportToJson(const StereoReport& r, const Provenance& provenance) {
  OrderedJson j;
  j["format"] = "vstcal/reproj-report@1";
  OrderedJson views = OrderedJson::array();
  for (const StereoViewReport& v : r.views) {
    OrderedJson points = OrderedJson::array(), excluded = OrderedJson::array();
    for (size_t i = 0; i < v.points.size(); ++i) {
      points.push_back(StereoPointJson(v.points[i]));
      if (v.points[i].excluded != StereoExclusion::kNone) {
        excluded.push_back({{"index", i}, {"reason", StereoExclusionName(v.points[i].excluded)}});
      }
    }
    views.push_back({{"name", v.name}, {"left_pose", v.pose_status}, {reproj_key::kStats, StereoStatsJson(v.stats)},
                     {reproj_key::kExcluded, std::move(excluded)}, {reproj_key::kPoints, std::move(points)},
                     {reproj_key::kReprojection,
                      {{reproj_key::kLeft, StereoReprojectionJson(v.left)}, {reproj_key::kRight, StereoReprojectionJson(v.right)}}}});
  }
  j[reproj_key::kStereo] = {{"rig", r.rig_file},
                 {"left", r.left_file},
                 {"right", r.right_file},
                 {"length_unit", LengthUnitName(r.length_unit)},
                 {"target", r.rig_kind == Rig::kVolume ? "volume" : "planar-views"},
                 {"baseline", r.baseline},
                 {"volume", MeasuredVolumeToJson(r.volume)},
                 {reproj_key::kOverall, StereoStatsJson(r.overall)},
                 {"excluded",
                  {{"left_only", r.n_left_only},
                   {"right_only", r.n_right_only},
                   {"no_pose", r.n_no_pose},
                   {"no_ray", r.n_no_ray},
                   {"behind", r.n_behind}}},
                 {"left_only_views", r.left_only_views},
                 {"right_only_views", r.right_only_views},
                 {reproj_key::kViews, std::move(views)},
                 {"grid", {{"cols", r.left_grid.grid.cols}, {"rows", r.left_grid.grid.rows}}},
                 {"reprojection",
                  {{"left", {{"error_px", StatsJson(r.left_grid.overall_px)}, {"grid", GridJson(r.left_grid.grid, r.left_grid.error_px)}}},
                   {"right", {{"error_px", StatsJson(r.right_grid.overall_px)}, {"grid", GridJson(r.right_grid.grid, r.right_grid.error_px)}}}}}};
  OrderedJson tests = OrderedJson::array();
  for (const StereoTestPoint& t : r.test_points) {
    const bool measured = t.error.excluded == StereoExclusion::kNone;
    OrderedJson point = StereoPointJson(t.error);
    point.erase(point.begin(), point.begin() + 3);  // the target point is `world`
    tests.push_back({{"name", t.name},
                     {"world", MatrixToJson(t.point_in_world)},
                     {"inside_volume", t.inside_volume ? OrderedJson(*t.inside_volume) : OrderedJson(nullptr)},
                     {reproj_key::kError, std::move(point)},
                     {"excluded", measured ? OrderedJson(nullptr) : OrderedJson(StereoExclusionName(t.error.excluded))}});
  }
  j[reproj_key::kStereo][reproj_key::kTestPoints] = {{reproj_key::kStats, StereoStatsJson(r.test_stats)},
                                {reproj_key::kInside, StereoStatsJson(r.test_inside)},
                                {reproj_key::kOutside, StereoStatsJson(r.test_outside)},
                                {reproj_key::kPoints, std::move(tests)}};
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

std::string StereoReportText(const StereoReport& r) {
  std::string out;
  const std::string unit(LengthUnitName(r.length_unit));
  Append(&out, "rig %s (baseline %.4f %s), %s and %s: %zu views seen by both cameras\n", r.rig_file.c_str(), r.baseline,
         unit.c_str(), r.left_file.c_str(), r.right_file.c_str(), r.views.size());
  Append(&out, "  %-24s %6s %10s %10s %10s %10s %10s\n", "", "n", "mean", "rms", "median", "p95", "max");
  AppendStereoRows(&out, "", unit, r.overall);
  AppendStatsRow(&out, "left reprojection px", r.left_grid.overall_px);
  AppendStatsRow(&out, "right reprojection px", r.right_grid.overall_px);
  for (const StereoViewReport& v : r.views) {
    AppendStatsRow(&out, "view " + v.name + " linear " + unit, v.stats.linear);
    AppendStatsRow(&out, "view " + v.name + " left px", v.left.error_px);
    AppendStatsRow(&out, "view " + v.name + " right px", v.right.error_px);
  }
  if (!r.test_points.empty()) {
    AppendStatsRow(&out, "test |dz| " + unit, r.test_stats.z);
    AppendStatsRow(&out, "test linear " + unit, r.test_stats.linear);
    AppendStatsRow(&out, "test inside linear " + unit, r.test_inside.linear);
    AppendStatsRow(&out, "test outside linear " + unit, r.test_outside.linear);
  }
  Append(&out, "  bias (left frame) x %+.4f, y %+.4f, z %+.4f %s; depth %+.4f %s\n", r.overall.bias.x(), r.overall.bias.y(),
         r.overall.bias.z(), unit.c_str(), r.overall.depth_bias, unit.c_str());
  const size_t excluded = r.n_left_only + r.n_right_only + r.n_no_pose + r.n_no_ray + r.n_behind;
  if (excluded > 0) {
    Append(&out, "  excluded: %zu seen by the left camera only, %zu by the right only, %zu without a left pose, %zu without "
           "a ray, %zu behind\n", r.n_left_only, r.n_right_only, r.n_no_pose, r.n_no_ray, r.n_behind);
  }
  if (!r.left_only_views.empty() || !r.right_only_views.empty()) {
    Append(&out, "  views seen by one camera only: %zu left, %zu right\n", r.left_only_views.size(), r.right_only_views.size());
  }
  return out;
}

}  // namespace vstcal
