#include "vstcal/report/reprojection_report.h"

#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "vstcal/estimators/uncertainty.h"
#include "vstcal/core/error.h"
#include "vstcal/geometry/registration_error.h"

namespace vstcal {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

// How the normalized residual is formed for one camera, or why it is not.
struct Normalization {
  bool enabled = false;
  double sigma_px = 0;
  std::string description;
};

Normalization NormalizationFor(const ReportCamera& rc, const Correspondences& c) {
  const CalibratedCamera& cam = rc.camera;
  if (!cam.covariance || cam.covariance->empty()) return {false, 0, "none: the camera has no covariance"};
  if (!rc.sigma_px) return {false, 0, "none: the camera file has no refinement.sigma_px"};
  if (c.rig != Rig::kVolume || !cam.camera_from_world) {
    return {false, 0, "none: planar views (the projection uncertainty needs one camera_from_world)"};
  }
  return {true, *rc.sigma_px,
          "z = sqrt(r' inv(S) r), S = sigma^2/w I - Sigma_p (calibration points), sigma^2 I + Sigma_p (test points)"};
}

// The error of one point at `point_cam` (camera frame) measured at `measured`; `sign` +1 adds the
// projection uncertainty to the noise (test points), −1 subtracts it (the fit's own points).
PointError MeasurePoint(const ReportCamera& rc, const Normalization& norm, const Eigen::Vector3d& point_in_world,
                        const Eigen::Vector3d& point_cam, const Eigen::Vector2d& measured, double weight, double sign) {
  PointError e;
  e.measured = measured;
  e.predicted = rc.camera.camera.Project(point_cam);
  if (!e.predicted) {
    e.excluded = Exclusion::kBehindCamera;
    return e;
  }
  const auto ray = rc.camera.camera.UnprojectRay(measured);  // a direction: a fisheye's may be past 90°
  e.depth = point_cam.norm();
  e.z = point_cam.z();
  const Eigen::Vector3d sight = point_cam / e.depth;
  const double along = ray ? ray->normalized().dot(sight) : 0.0;
  if (!ray || !(along > 0)) {  // the measured pixel has no ray, or one 90° or more away
    e.predicted.reset();
    e.excluded = Exclusion::kNoRay;
    return e;
  }
  const Eigen::Vector2d r = *e.predicted - measured;
  e.error_px = r.norm();
  // The measured ray meets the plane through X_c normal to the sight line at ray·d/(ray·ℓ).
  const Eigen::Vector3d seen = ray->normalized() * (e.depth / along);
  const RegistrationErrorOf<double> reg = RegistrationError<double>(Vec3<double>::Zero(), point_cam, seen - point_cam);
  e.lateral = reg.lateral;
  e.angular_rad = reg.angular;
  if (norm.enabled) {
    const auto ellipse = ProjectionUncertaintyAtWorldPoint(rc.camera, point_in_world);
    if (ellipse) {
      const Eigen::Matrix2d S = norm.sigma_px * norm.sigma_px / weight * Eigen::Matrix2d::Identity() + sign * ellipse->covariance;
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(S);
      // A point whose leverage takes nearly all of its noise (S ≈ 0) says nothing about σ.
      if (eig.eigenvalues()(0) > 1e-6 * norm.sigma_px * norm.sigma_px) e.normalized = std::sqrt(r.dot(S.ldlt().solve(r)));
    }
  }
  return e;
}

struct Collected {
  std::vector<double> error_px, lateral, angular_deg, normalized, z;
  std::vector<Eigen::Vector2d> pixels;
  void Add(const PointError& e) {
    if (e.excluded != Exclusion::kNone) return;
    error_px.push_back(e.error_px);
    lateral.push_back(e.lateral);
    angular_deg.push_back(e.angular_deg());
    z.push_back(e.z);
    pixels.push_back(e.measured);
    if (e.normalized) normalized.push_back(*e.normalized);
  }
  MeasureStats Stats() const {
    return {ComputeErrorStats(error_px), ComputeErrorStats(lateral), ComputeErrorStats(angular_deg)};
  }
};

void CheckCameraFits(const ReportCamera& rc, const Correspondences& c, const std::string& corr_file) {
  const ImageSize& a = rc.camera.camera.image_size;
  if (!(a == c.image_size)) {
    throw InputError(rc.file + ": image_size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                     " differs from " + corr_file + "'s " + std::to_string(c.image_size.width) + "x" +
                     std::to_string(c.image_size.height) + "; give the camera calibrated from images of that size");
  }
  if (rc.camera.length_unit != c.length_unit) {
    throw InputError(rc.file + ": length_unit: \"" + std::string(LengthUnitName(rc.camera.length_unit)) +
                     "\" differs from " + corr_file + "'s \"" + std::string(LengthUnitName(c.length_unit)) +
                     "\"; convert one of them (calib-convert) so that both use one unit");
  }
  if (c.rig == Rig::kVolume && !rc.camera.camera_from_world) {
    throw InputError(rc.file + ": camera_from_world: missing, but " + corr_file +
                     " is a volume rig; give a camera solved from a volume (calib-dlt) or with its pose");
  }
  if (c.rig == Rig::kPlanarViews && rc.camera.views.empty()) {
    throw InputError(rc.file + ": views: missing, but " + corr_file +
                     " has planar views, each with its own pose; give the camera solved from these views (calib-tsai)");
  }
}

// The pose of view v in camera `rc`: camera_from_world for a volume, the camera file's view of the
// same name for planar views (nullopt when the solver dropped it).
std::optional<Rigid3d> ViewPoseOf(const ReportCamera& rc, const Correspondences& c, size_t v) {
  if (c.rig == Rig::kVolume) return rc.camera.camera_from_world;
  for (const ViewPose& p : rc.camera.views) {
    if (p.name == c.views[v].name) return p.camera_from_board;
  }
  return std::nullopt;
}

CameraReport ReportOne(const ReportCamera& rc, const Correspondences& c, const ImageGrid& grid,
                       const MeasuredVolume& volume) {
  CameraReport out;
  out.file = rc.file;
  out.name = rc.camera.name;
  out.method = rc.camera.method;
  const auto names = LensModelParamNames(rc.camera.camera.model);
  for (size_t i = 0; i < names.size(); ++i) {
    ParameterEstimate& p = out.parameters.emplace_back(ParameterEstimate{std::string(names[i]), rc.camera.camera.params[i], {}});
    if (const auto k = rc.camera.covariance ? rc.camera.covariance->Find(p.name) : std::nullopt) {
      p.sigma = std::sqrt(std::max(0.0, rc.camera.covariance->matrix(*k, *k)));
    }
  }
  const Normalization norm = NormalizationFor(rc, c);
  out.normalization = norm.description;
  Collected all;
  for (size_t v = 0; v < c.views.size(); ++v) {
    const View& view = c.views[v];
    const std::optional<Rigid3d> pose = ViewPoseOf(rc, c, v);
    ViewReport vr;
    vr.name = view.name;
    Collected in_view;
    for (const Observation& o : view.observations) {
      PointError e;
      if (!pose) {
        e.measured = o.pixel;
        e.excluded = Exclusion::kNoPose;
      } else {
        e = MeasurePoint(rc, norm, o.point, *pose * o.point, o.pixel, o.weight, -1.0);
      }
      out.n_behind_camera += e.excluded == Exclusion::kBehindCamera;
      out.n_no_pose += e.excluded == Exclusion::kNoPose;
      out.n_no_ray += e.excluded == Exclusion::kNoRay;
      in_view.Add(e);
      all.Add(e);
      vr.points.push_back(e);
    }
    vr.error_px = ComputeErrorStats(in_view.error_px);
    out.views.push_back(std::move(vr));
  }
  out.overall = all.Stats();
  if (rc.camera.covariance && !rc.camera.covariance->empty() && !all.z.empty()) {
    out.uncertainty_depth = ComputeErrorStats(all.z)->median;
    for (int row = 0; row < grid.rows; ++row) {
      for (int col = 0; col < grid.cols; ++col) {
        const auto e = ProjectionUncertaintyAtPixel(rc.camera, grid.CellCentre(col, row), out.uncertainty_depth);
        out.uncertainty_px.push_back(e ? std::optional<double>(e->sigma_major_px) : std::nullopt);
      }
    }
  }
  out.grid = ComputeGridStats(grid, all.pixels, all.error_px);
  if (norm.enabled) {
    out.normalized = ComputeErrorStats(all.normalized);
    if (!all.normalized.empty()) {
      double sum2 = 0;
      for (const double z : all.normalized) sum2 += z * z;
      out.chi2_per_dof = sum2 / (2.0 * static_cast<double>(all.normalized.size()));
    }
  }
  Collected inside, outside;
  std::vector<double> test_normalized;
  for (const TestPoint& t : c.test_points) {
    TestPointReport tr;
    tr.name = t.name;
    tr.point_in_world = t.point_in_world;
    tr.inside_volume = volume.Contains(t.point_in_world);
    if (!t.pixel) {
      tr.error.excluded = Exclusion::kNotMeasured;
    } else if (!rc.camera.camera_from_world) {
      tr.error.measured = *t.pixel;
      tr.error.excluded = Exclusion::kNoPose;
    } else {
      tr.error = MeasurePoint(rc, norm, t.point_in_world, *rc.camera.camera_from_world * t.point_in_world, *t.pixel,
                              1.0, +1.0);
    }
    if (tr.inside_volume) (*tr.inside_volume ? inside : outside).Add(tr.error);
    if (tr.error.normalized) test_normalized.push_back(*tr.error.normalized);
    out.test_points.push_back(std::move(tr));
  }
  out.test_inside = inside.Stats();
  out.test_outside = outside.Stats();
  out.test_normalized = ComputeErrorStats(test_normalized);
  return out;
}

CameraDifference Compare(const ReprojReport& report, size_t k) {
  const CameraReport& a = report.cameras[k];
  const CameraReport& b = report.cameras[0];
  CameraDifference d;
  d.camera = k;
  std::vector<double> shift;
  for (size_t v = 0; v < a.views.size(); ++v) {
    for (size_t i = 0; i < a.views[v].points.size(); ++i) {
      const PointError& pa = a.views[v].points[i];
      const PointError& pb = b.views[v].points[i];
      if (pa.predicted && pb.predicted) shift.push_back((*pa.predicted - *pb.predicted).norm());
    }
  }
  d.prediction_shift_px = ComputeErrorStats(shift);
  if (a.overall.error_px && b.overall.error_px) {
    d.rms_change_px = a.overall.error_px->rms - b.overall.error_px->rms;
    d.median_change_px = a.overall.error_px->median - b.overall.error_px->median;
    d.p95_change_px = a.overall.error_px->p95 - b.overall.error_px->p95;
  }
  return d;
}

}  // namespace

double PointError::angular_deg() const { return angular_rad * kDegPerRad; }

std::string_view ExclusionName(Exclusion e) {
  return NameOf(kExclusionNames, e);
}

std::vector<std::string> ExclusionNotes(const ReprojReport& report) {
  std::vector<std::string> notes;
  for (const CameraReport& camera : report.cameras) {
    size_t total = 0;
    std::string unposed;
    for (const ViewReport& view : camera.views) {
      total += view.points.size();
      if (!view.points.empty() && view.points.front().excluded == Exclusion::kNoPose) unposed += (unposed.empty() ? "" : ", ") + view.name;
    }
    const size_t left_out = camera.n_behind_camera + camera.n_no_pose + camera.n_no_ray;
    if (left_out == 0) continue;
    std::string why;
    const auto add = [&why](size_t n, const std::string& what) {
      if (n > 0) why += (why.empty() ? "" : ", ") + std::to_string(n) + " " + what;
    };
    add(camera.n_behind_camera, "behind the camera");
    add(camera.n_no_pose, "in views the camera has no pose for (" + unposed + ": its solver dropped them)");
    add(camera.n_no_ray, "measured at pixels without a ray through the lens");
    notes.push_back(camera.file + ": " + std::to_string(left_out) + " of " + std::to_string(total) +
                    " points left out of the statistics: " + why);
  }
  return notes;
}

ReprojReport BuildReprojReport(std::span<const ReportCamera> cameras, Correspondences c, std::string corr_file,
                               const ReprojReportOptions& options) {
  VSTCAL_CHECK(!cameras.empty(), "at least one camera");
  VSTCAL_CHECK(options.grid_cols > 0 && options.grid_rows > 0, "a grid of at least one cell");
  for (const ReportCamera& rc : cameras) CheckCameraFits(rc, c, corr_file);
  ReprojReport report;
  report.correspondences_file = std::move(corr_file);
  report.grid = ImageGrid{c.image_size, options.grid_cols, options.grid_rows};
  const Correspondences* files[] = {&c};
  report.volume = MeasuredVolumeOf(files);
  for (const ReportCamera& rc : cameras) report.cameras.push_back(ReportOne(rc, c, report.grid, report.volume));
  for (size_t k = 1; k < report.cameras.size(); ++k) report.differences.push_back(Compare(report, k));
  report.correspondences = std::move(c);
  return report;
}

}  // namespace vstcal
