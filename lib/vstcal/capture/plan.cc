#include "vstcal/capture/plan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "vstcal/estimators/principal_point_prior.h"
#include "vstcal/estimators/uncertainty.h"
#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

std::string Fmt(const char* format, double a, double b = 0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, format, a, b);
  return buf;
}

// Sutherland–Hodgman against one axis-aligned half plane: keep x[axis]·sign ≤ bound·sign.
Polygon ClipHalfPlane(const Polygon& in, int axis, double bound, double sign) {
  Polygon out;
  for (size_t i = 0; i < in.size(); ++i) {
    const Eigen::Vector2d& a = in[i];
    const Eigen::Vector2d& b = in[(i + 1) % in.size()];
    const bool a_in = sign * (a[axis] - bound) <= 0, b_in = sign * (b[axis] - bound) <= 0;
    if (a_in) out.push_back(a);
    if (a_in != b_in) out.push_back(a + (b - a) * ((bound - a[axis]) / (b[axis] - a[axis])));
  }
  return out;
}

double Area(const Polygon& p) {
  double twice = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d& a = p[i];
    const Eigen::Vector2d& b = p[(i + 1) % p.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * std::abs(twice);
}

// The outline's area inside [x0, x1] × [y0, y1]. Exact for a convex outline (a pinhole view of
// the pattern); a distorted outline is a slightly non-convex polygon, whose clipped area the
// same construction still gives, its degenerate edges having no area.
double ClippedArea(Polygon p, double x0, double y0, double x1, double y1) {
  p = ClipHalfPlane(p, 0, x0, -1);
  p = ClipHalfPlane(p, 0, x1, 1);
  p = ClipHalfPlane(p, 1, y0, -1);
  p = ClipHalfPlane(p, 1, y1, 1);
  return p.size() < 3 ? 0 : Area(p);
}

// The pattern's outline (the extent of its squares or tags) through the camera, 32 samples per
// side so that distortion bends it; samples behind the camera are left out.
Polygon ProjectedOutline(const Camera& camera, const Target& target, const Rigid3d& camera_from_board) {
  const Rect r = PatternExtent(target);
  const Eigen::Vector2d corners[4] = {{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}};
  constexpr int kSamples = 32;
  Polygon outline;
  for (int side = 0; side < 4; ++side) {
    for (int k = 0; k < kSamples; ++k) {
      const Eigen::Vector2d xy = corners[side] + (corners[(side + 1) % 4] - corners[side]) * (double(k) / kSamples);
      const Eigen::Vector3d p = camera_from_board * Eigen::Vector3d(xy.x(), xy.y(), 0);
      if (p.z() <= 0) continue;
      if (const auto px = camera.Project(p)) outline.push_back(*px);
    }
  }
  return outline;
}

// Neighbouring corners of a target: chessboard and ChArUco corners one square apart along rows
// and columns; the four sides of every AprilTag (Kalibr's aprilgrid: its corner grid's rows and
// columns, tag sides and gaps).
std::vector<std::pair<int, int>> Neighbours(const Target& target) {
  std::vector<std::pair<int, int>> pairs;
  if (target.type == TargetType::kAprilGrid) {
    const int rows = 2 * target.rows, cols = 2 * target.cols;
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        if (c + 1 < cols) pairs.emplace_back(r * cols + c, r * cols + c + 1);
        if (r + 1 < rows) pairs.emplace_back(r * cols + c, (r + 1) * cols + c);
      }
    }
    return pairs;
  }
  if (target.type == TargetType::kAprilTagGrid) {
    for (int tag = 0; tag < target.rows * target.cols; ++tag) {
      for (int k = 0; k < 4; ++k) pairs.emplace_back(4 * tag + k, 4 * tag + (k + 1) % 4);
    }
    return pairs;
  }
  for (int r = 0; r < target.rows; ++r) {
    for (int c = 0; c < target.cols; ++c) {
      if (c + 1 < target.cols) pairs.emplace_back(r * target.cols + c, r * target.cols + c + 1);
      if (r + 1 < target.rows) pairs.emplace_back(r * target.cols + c, (r + 1) * target.cols + c);
    }
  }
  return pairs;
}

void Measure(const PlanRequest& request, const std::vector<TargetCorner>& corners, PositionPlan* p) {
  const Camera& camera = request.camera;
  const double w = camera.image_size.width, h = camera.image_size.height;
  // The image is the pixels' squares: centres at integers, borders half a pixel out.
  const double x0 = -0.5, y0 = -0.5, x1 = w - 0.5, y1 = h - 0.5;
  const Polygon outline = ProjectedOutline(camera, request.target, p->camera_from_board);
  p->coverage = ClippedArea(outline, x0, y0, x1, y1) / (w * h);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double rx0 = x0 + j * w / 3, ry0 = y0 + i * h / 3;
      p->region_coverage(i, j) = ClippedArea(outline, rx0, ry0, rx0 + w / 3, ry0 + h / 3) / (w * h / 9);
    }
  }
  std::vector<std::optional<Eigen::Vector2d>> pixels(corners.size());
  p->corners = static_cast<int>(corners.size());
  p->depth_min = INFINITY;
  p->depth_max = -INFINITY;
  for (size_t k = 0; k < corners.size(); ++k) {
    const Eigen::Vector3d q = p->camera_from_board * Eigen::Vector3d(corners[k].xy.x(), corners[k].xy.y(), 0);
    p->depth_min = std::min(p->depth_min, q.z());
    p->depth_max = std::max(p->depth_max, q.z());
    if (q.z() > 0) pixels[k] = camera.Project(q);
    if (!pixels[k] || !camera.InImage(*pixels[k])) {
      ++p->corners_outside;
      if (pixels[k]) {
        const Eigen::Vector2d& u = *pixels[k];
        p->outside_px = std::max({p->outside_px, x0 - u.x(), u.x() - x1, y0 - u.y(), u.y() - y1});
      } else {
        p->outside_px = INFINITY;  // behind the camera
      }
    }
  }
  p->smallest_square_px = INFINITY;
  for (const auto& [a, b] : Neighbours(request.target)) {
    if (pixels[a] && pixels[b]) p->smallest_square_px = std::min(p->smallest_square_px, (*pixels[a] - *pixels[b]).norm());
  }
  if (!std::isfinite(p->smallest_square_px)) p->smallest_square_px = 0;
  const Rect r = PatternExtent(request.target);
  const Eigen::Vector3d centre = p->camera_from_board * Eigen::Vector3d(0.5 * (r.x0 + r.x1), 0.5 * (r.y0 + r.y1), 0);
  const Eigen::Vector3d normal = p->camera_from_board.R.col(2);
  p->obliquity_deg = RadToDeg(std::acos(std::min(1.0, std::abs(normal.dot(centre.normalized())))));

  const bool whole_board_needed = request.target.type == TargetType::kChessboard;
  if (p->corners_outside > 0) {
    std::string line = std::to_string(p->corners_outside) + " of " + std::to_string(p->corners) + " corners leave the image";
    line += std::isfinite(p->outside_px) ? Fmt(" (by up to %.0f px)", p->outside_px) : " (some behind the camera)";
    line += whole_board_needed ? ": a chessboard is found only whole, so this position gives nothing; move the camera back or "
                                 "use a ChArUco or AprilTag target (partial views allowed)"
                               : ": only the corners inside count; move the camera back to use them all";
    p->warnings.push_back(line);
    if (whole_board_needed) p->used = false;
  }
  if (p->smallest_square_px < kSmallestReliableSquarePx) {
    p->warnings.push_back(Fmt("squares of %.1f px, below the %.0f px at which detection was measured reliable "
                              "(docs/experiments/corners.md); use larger squares or bring the camera closer",
                              p->smallest_square_px, kSmallestReliableSquarePx));
  }
  if (p->obliquity_deg > kMaxReliableObliquityDeg) {
    p->warnings.push_back(Fmt("seen %.0f° off its normal, beyond %.0f° corners are foreshortened too far for reliable "
                              "detection; tilt the board (or the camera) less",
                              p->obliquity_deg, kMaxReliableObliquityDeg));
  }
  if (request.sharp_near && request.sharp_far && (p->depth_min < *request.sharp_near || p->depth_max > *request.sharp_far)) {
    p->warnings.push_back(Fmt("corners at depths %.4g … ", p->depth_min) +
                          Fmt("%.4g lie outside the depth of field ", p->depth_max) +
                          Fmt("[%.4g, %.4g]: they will be blurred; focus or stop down the lens, or move the template",
                              *request.sharp_near, *request.sharp_far));
  }
}

void Require(bool ok, const std::string& message) {
  if (!ok) throw InputError(message);
}

// What the solve the user will run estimates: RefineOptions as given; Tsai on one plane holds the
// aspect as calib-tsai does and, unless the options place the principal point themselves, puts it
// under calib-tsai's default prior at the nominal camera's principal point
// (calib/pipeline.cc, docs/math/uncertainty.md#one-plane).
RefineOptions SolveOptions(const PlanRequest& request, bool one_plane) {
  RefineOptions o = request.options;
  if (request.method == "tsai" && one_plane) {
    const Eigen::Matrix3d K = request.camera.K();
    o.focal_aspect = K(0, 0) / K(1, 1);
    if (!PlacesPrincipalPoint(o)) {
      AddPrincipalPointPrior(Eigen::Vector2d(K(0, 2), K(1, 2)),
                             PrincipalPointPriorSigmaPx(request.camera.image_size, kPlanePrincipalPointPriorSigma),
                             "one plane: calib-tsai's default prior", &o);
    }
  }
  return o;
}

}  // namespace

CapturePlan PlanCapture(const PlanRequest& request) {
  Require(request.method == "dlt" || request.method == "tsai", VSTCAL_OPT("method") ": give dlt or tsai, got \"" + request.method + "\"");
  Require(std::isfinite(request.pixel_sigma) && request.pixel_sigma > 0,
          VSTCAL_OPT("pixel_sigma") ": the corner noise σ must be a positive number of pixels");
  if (request.sharp_near || request.sharp_far) {
    Require(request.sharp_near && request.sharp_far && *request.sharp_near < *request.sharp_far,
            VSTCAL_OPT("depth_of_field") ": give NEAR,FAR with NEAR < FAR (length unit)");
  }
  CapturePlan plan;
  plan.request = request;
  const std::vector<TargetCorner> corners = TargetCorners(request.target);
  const Rect extent = PatternExtent(request.target);
  const Eigen::Vector2d centre(0.5 * (extent.x0 + extent.x1), 0.5 * (extent.y0 + extent.y1));
  std::vector<Rigid3d> poses;
  Correspondences c;
  c.image_size = request.camera.image_size;
  c.length_unit = request.target.length_unit;
  c.rig = request.rig;
  if (request.rig == Rig::kVolume) {
    VolumeSpec spec = request.volume;
    spec.length_unit = request.target.length_unit;
    spec.noise_px = 0;
    // The same checks of the volume as calib-synth's, on a 3 × 3 grid spanning the target: its
    // centre corner is seen whenever the camera looks at the template; whether the target's own
    // corners are is this plan's to report, position by position.
    spec.grid_cols = 3;
    spec.grid_rows = 3;
    spec.spacing = 0.5 * std::max(extent.width(), extent.height());
    (void)SynthesizeVolume(request.camera, spec, {});
    plan.camera_from_world = VolumeCameraPose(spec);
    const double planes = std::floor((spec.far - spec.near) / spec.interval + 1e-9) + 1;
    for (int k = 0; k < static_cast<int>(planes); ++k) {
      PositionPlan p;
      p.plane_offset = spec.near + k * spec.interval;
      p.name = Fmt("z=%.6g", *p.plane_offset);
      // Board centred on the world's Z axis, at the plane's offset.
      p.camera_from_board = plan.camera_from_world * Rigid3d{Eigen::Matrix3d::Identity(),
                                                              Eigen::Vector3d(-centre.x(), -centre.y(), *p.plane_offset)};
      plan.positions.push_back(std::move(p));
    }
    poses = {plan.camera_from_world};
  } else {
    PlanarViewsSpec spec = request.views;
    spec.length_unit = request.target.length_unit;
    spec.noise_px = 0;
    // PlanarViewPose aims the centre of a grid of (cols − 1) × (rows − 1) spacings: with no
    // spacing, the board origin; moved below to the pattern's centre.
    spec.grid_cols = 2;
    spec.grid_rows = 2;
    spec.spacing = 0;
    Require(spec.num_views >= 1 && static_cast<size_t>(spec.num_views) <= limits::kMaxViews,
            VSTCAL_OPT("views") ": give 1 to " + std::to_string(limits::kMaxViews) + " views");
    Require(spec.distance > 0 && spec.distance <= limits::kMaxSyntheticScale, VSTCAL_OPT("distance") ": must be positive, at most 1e9");
    Require(spec.max_tilt_deg >= 0 && spec.max_tilt_deg < 80, VSTCAL_OPT("max_tilt_deg") ": must lie in [0, 80)");
    for (int k = 0; k < spec.num_views; ++k) {
      PositionPlan p;
      p.name = "view " + std::to_string(k);
      Rigid3d pose = PlanarViewPose(request.camera, spec, k);
      pose.t -= pose.R * Eigen::Vector3d(centre.x(), centre.y(), 0);
      p.camera_from_board = pose;
      plan.positions.push_back(std::move(p));
    }
  }
  for (PositionPlan& p : plan.positions) {
    Measure(request, corners, &p);
    if (!p.used) continue;
    View view;
    view.name = p.name;
    view.plane_offset = p.plane_offset;
    for (const TargetCorner& corner : corners) {
      const Eigen::Vector3d board(corner.xy.x(), corner.xy.y(), 0);
      const Eigen::Vector3d q = p.camera_from_board * board;
      if (q.z() <= 0) continue;
      const auto px = request.camera.Project(q);
      if (!px || !request.camera.InImage(*px)) continue;
      const Eigen::Vector3d point = request.rig == Rig::kVolume ? Eigen::Vector3d(board.x() - centre.x(), board.y() - centre.y(), *p.plane_offset) : board;
      view.observations.push_back({point, *px, 1.0});
    }
    plan.used_corners += static_cast<int>(view.observations.size());
    if (request.rig == Rig::kPlanarViews) poses.push_back(p.camera_from_board);
    c.views.push_back(std::move(view));
  }
  if (c.views.empty()) {
    throw DegenerateError("no planned position shows the target usably (see the positions' warnings); "
                                       "move the camera back or change the volume");
  }
  const bool one_plane = request.rig == Rig::kVolume && c.views.size() == 1;
  plan.prediction = CovarianceAt(c, request.camera, poses, SolveOptions(request, one_plane), request.pixel_sigma);
  plan.corners = c;
  plan.poses = poses;
  if (!plan.prediction.observable) {
    plan.warnings.push_back("the plan cannot determine the calibration: " + plan.prediction.message);
    return plan;
  }
  if (!plan.prediction.weakest.empty()) plan.warnings.push_back(plan.prediction.weakest);

  CalibratedCamera predicted;
  // The prediction's model may be larger than the nominal camera's (free k1 of a pinhole): the
  // same camera in the promoted layout, its extra terms 0.
  predicted.camera = request.camera;
  predicted.camera.model = plan.prediction.model;
  predicted.camera.params = PromotedParams(request.camera, plan.prediction.model);
  predicted.length_unit = request.target.length_unit;
  predicted.covariance = plan.prediction.covariance;
  if (request.rig == Rig::kVolume) {
    predicted.camera_from_world = plan.camera_from_world;
  } else {
    for (size_t v = 0; v < poses.size(); ++v) predicted.views.push_back({c.views[v].name, poses[v], {}});
  }
  const ParameterCovariance& cov = plan.prediction.covariance;
  const std::vector<double>& values = predicted.camera.params;
  const std::vector<std::string_view> names = LensModelParamNames(plan.prediction.model);
  for (size_t i = 0; i < cov.parameters.size(); ++i) {
    const auto at = std::find(names.begin(), names.end(), cov.parameters[i]);
    // Pose tangents are deviations from the planned pose: their value is 0.
    plan.sigmas.push_back({cov.parameters[i], at == names.end() ? 0.0 : values[at - names.begin()], std::sqrt(cov.matrix(i, i))});
  }
  for (const TestPoint& t : request.test_points) {
    const auto tied = ProjectionUncertaintyAtWorldPoint(predicted, t.point_in_world, ProjectionUncertaintyKind::kWithPoses);
    const auto alone = ProjectionUncertaintyAtWorldPoint(predicted, t.point_in_world, ProjectionUncertaintyKind::kIntrinsicsOnly);
    Require(tied && alone, VSTCAL_OPT("test_point") " " + t.name + ": behind the camera; give points in front of it");
    plan.points.push_back({t.name, t.point_in_world, std::nullopt, tied->sigma_major_px, alone->sigma_major_px});
  }
  for (const Eigen::Vector3d& q : request.pixel_points) {
    const auto tied = ProjectionUncertaintyAtPixel(predicted, q.head<2>(), q.z(), ProjectionUncertaintyKind::kWithPoses);
    const auto alone = ProjectionUncertaintyAtPixel(predicted, q.head<2>(), q.z(), ProjectionUncertaintyKind::kIntrinsicsOnly);
    Require(tied && alone, Fmt(VSTCAL_OPT("uncertainty_pixel") ": (%.6g, %.6g) has no ray in this lens model; give a pixel inside the image", q.x(), q.y()));
    plan.points.push_back({Fmt("pixel (%.6g, %.6g)", q.x(), q.y()), std::nullopt, q, tied->sigma_major_px, alone->sigma_major_px});
  }
  return plan;
}

}  // namespace vstcal
