#include "vstcal/calib/pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include <Eigen/Geometry>

#include "vstcal/estimators/information.h"
#include "vstcal/estimators/principal_point_prior.h"
#include "vstcal/core/option_name.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal {
namespace {

// A refined camera whose reprojection RMS exceeds this fraction of the image diagonal is refused
// (ApplyRefinement): 5 % is 73 px on 1280 × 720, beyond any corner noise (extreme_inputs_test
// solves 30 px), far below what a wrong minimum leaves (hundreds of px).
constexpr double kMaxPlausibleRmsFraction = 0.05;

// "views[2].points[17] (view "plane-02")" for a flat observation index.
std::string Locate(const Correspondences& c, size_t flat) {
  for (size_t v = 0; v < c.views.size(); ++v) {
    const size_t n = c.views[v].observations.size();
    if (flat < n) {
      return "views[" + std::to_string(v) + "].points[" + std::to_string(flat) + "] (view \"" + c.views[v].name + "\")";
    }
    flat -= n;
  }
  return "a point";
}

// The refinement's outcome into the result; a failed or unconverged refinement is an error (no
// camera is written from it).
void ApplyRefinement(CalibrationResult* r, Refinement refinement) {
  const Correspondences& c = r->used;
  if (refinement.status != RefineStatus::kConverged) {
    r->exit_code = refinement.status == RefineStatus::kTooFewPoints ? ExitCode::kBadInput : ExitCode::kDegenerate;
    r->message = refinement.message;
    r->refinement = std::move(refinement);
    return;
  }
  // Converged is not the same as right: from a start far from the truth the refinement can settle in
  // a wrong minimum whose residuals are hundreds of pixels (a narrow lens solved as a fisheye from a
  // 180° guess did). No pixel noise comes near a twentieth of the image diagonal, so such a camera
  // is refused rather than written with a covariance that would look like an answer.
  const double diagonal = std::hypot(c.image_size.width, c.image_size.height);
  if (!(refinement.fit.overall.rms_px <= kMaxPlausibleRmsFraction * diagonal)) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "the refinement ended at a reprojection RMS of %.4g px, more than %g %% of the image diagonal "
                  "(%.4g px), which no corner noise reaches: a wrong minimum or wrong data, not a calibration; "
                  "check that the lens model suits the lens and that the points and pixels correspond",
                  refinement.fit.overall.rms_px, 100 * kMaxPlausibleRmsFraction, kMaxPlausibleRmsFraction * diagonal);
    r->exit_code = ExitCode::kDegenerate;
    r->message = buf;
    r->refinement = std::move(refinement);
    return;
  }
  if (!refinement.message.empty()) r->warnings.push_back(refinement.message);
  for (const Outlier& o : refinement.outliers) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "outlier: views[%zu].points[%zu] (view \"%s\") residual %.3g px = %.1f sigma",
                  o.view, o.point, c.views[o.view].name.c_str(), o.residual_px.norm(), o.normalized);
    r->warnings.emplace_back(buf);
  }
  CalibratedCamera& cam = r->camera;
  cam.camera = refinement.camera;
  cam.method += "+refine";
  cam.fit = refinement.fit;
  cam.P.reset();  // K[R|t] of the refined camera is written instead
  if (c.rig == Rig::kVolume) {
    cam.camera_from_world = refinement.poses[0];
  } else {
    cam.views.clear();
    for (size_t v = 0; v < c.views.size(); ++v) {
      cam.views.push_back({c.views[v].name, refinement.poses[v], refinement.fit.views[v].stats.rms_px});
    }
  }
  // The start's covariance (DLT) does not describe the refined camera: replaced or dropped.
  cam.covariance.reset();
  if (!refinement.covariance.empty()) cam.covariance = refinement.covariance;
  r->refinement = std::move(refinement);
}

// The bound ApplyRefinement puts on a refined camera, for a closed-form camera written unrefined
// (DLT, Tsai, Zhang): an algebraic solve always returns some K, and on data no camera explains (60 px
// corner noise, points and pixels that do not correspond) that K is absurd while the run would look
// like a success. Refused (exit 3, nothing written) when its K is physically impossible — a focal
// length not positive and finite; a pinhole field of view of kMaxPinholeFovDeg or more across the
// image's width or height (no rectilinear lens comes near; a 180° fisheye's K spans ~115°); the
// principal point more than one image diagonal from the image centre (the image's corners are half
// a diagonal from it) — or when its reprojection RMS exceeds kMaxPlausibleRmsFraction of the
// diagonal. With few points the DLT fits noise closely, so the RMS alone does not catch an absurd
// K. docs/math/dlt.md#plausibility.
void RefuseImplausibleClosedForm(CalibrationResult* r) {
  constexpr double kMaxPinholeFovDeg = 170;
  const CalibratedCamera& cam = r->camera;
  const ImageSize& size = r->used.image_size;
  const double diagonal = std::hypot(size.width, size.height);
  const std::vector<double>& p = cam.camera.params;
  const double fx = p[intrinsic::kFx], fy = p[intrinsic::kFy];
  const Eigen::Vector2d principal(p[intrinsic::kCx], p[intrinsic::kCy]);
  const Eigen::Vector2d centre(0.5 * (size.width - 1), 0.5 * (size.height - 1));
  const double rms = cam.fit ? cam.fit->overall.rms_px : 0;
  const double half_fov = 0.5 * kMaxPinholeFovDeg * kPi / 180;
  const double fov_x = 2 * std::atan(0.5 * size.width / fx) * 180 / kPi;
  const double fov_y = 2 * std::atan(0.5 * size.height / fy) * 180 / kPi;
  char buf[520];
  if (!(fx > 0 && fy > 0 && std::isfinite(fx) && std::isfinite(fy))) {
    std::snprintf(buf, sizeof buf,
                  "the %s camera has a focal length that is not positive (fx %.4g px, fy %.4g px): no physical camera; "
                  "the data do not determine one: check that the points and pixels correspond",
                  cam.method.c_str(), fx, fy);
  } else if (!(fx > 0.5 * size.width / std::tan(half_fov) && fy > 0.5 * size.height / std::tan(half_fov))) {
    std::snprintf(buf, sizeof buf,
                  "the %s camera's focal lengths (fx %.4g px, fy %.4g px) give a pinhole field of view of %.4g x %.4g "
                  "degrees, %g or more across the image, which no lens its model describes: the data do not determine "
                  "the camera (reprojection RMS %.4g px over %zu points); check that the points and pixels correspond, "
                  "or add points",
                  cam.method.c_str(), fx, fy, fov_x, fov_y, kMaxPinholeFovDeg, rms, NumObservations(r->used));
  } else if (!((principal - centre).norm() <= diagonal)) {
    std::snprintf(buf, sizeof buf,
                  "the %s camera's principal point (%.4g, %.4g) px lies %.4g px from the image centre, more than the "
                  "image diagonal (%.4g px): no physical lens; the data do not determine the camera (reprojection RMS "
                  "%.4g px over %zu points): check that the points and pixels correspond, or add points",
                  cam.method.c_str(), principal.x(), principal.y(), (principal - centre).norm(), diagonal, rms,
                  NumObservations(r->used));
  } else if (!(rms <= kMaxPlausibleRmsFraction * diagonal)) {
    std::snprintf(buf, sizeof buf,
                  "the %s camera reprojects at an RMS of %.4g px, more than %g %% of the image diagonal (%.4g px), "
                  "beyond any corner detector's noise: wrong data or a lens its model cannot describe, not a "
                  "calibration; check that the points and pixels correspond (the columns are X, Y, Z, u, v)",
                  cam.method.c_str(), rms, 100 * kMaxPlausibleRmsFraction, kMaxPlausibleRmsFraction * diagonal);
  } else {
    return;
  }
  r->exit_code = ExitCode::kDegenerate;
  r->message = buf;
}

void StartVolume(CalibrationResult* r, const CalibrationOptions& options) {
  const Correspondences& c = r->used;
  CalibratedCamera& cam = r->camera;
  const std::vector<Observation> obs = AllObservations(c);
  if (options.start == CalibrationOptions::Start::kDlt) {
    DltResult dlt = SolveDlt(obs, options.dlt);
    r->warnings.insert(r->warnings.end(), dlt.warnings.begin(), dlt.warnings.end());
    if (dlt.status == DltStatus::kPointsBehind) {
      const Observation& o = obs[dlt.deepest_behind];
      char buf[240];
      std::snprintf(buf, sizeof buf, " (e.g. %s at (%.6g, %.6g, %.6g), depth %.4g %s)", Locate(c, dlt.deepest_behind).c_str(),
                    o.point.x(), o.point.y(), o.point.z(), dlt.P.row(2).dot(o.point.homogeneous()),
                    std::string(LengthUnitName(c.length_unit)).c_str());
      dlt.message += buf;
    }
    if (dlt.status != DltStatus::kOk) {
      r->exit_code = DltStatusExitCode(dlt.status);
      r->message = dlt.message;
      r->dlt = std::move(dlt);
      return;
    }
    const auto d = DecomposeProjection(dlt.P);
    VSTCAL_CHECK(d.has_value(), "a normalized, non-mirrored P always decomposes");
    cam.method = "dlt";
    cam.camera = Camera::FromK(d->K, c.image_size);
    cam.camera_from_world = d->camera_from_world;
    cam.P = dlt.P;
    r->dlt_uncertainty = EstimateDltUncertainty(obs, dlt.P);
    r->dlt_covariance = DecompositionCovariance(*d, r->dlt_uncertainty->P_covariance);
    cam.covariance = r->dlt_covariance;
    r->eq13 = DecomposeProjectionEq13(dlt.P);
    r->dlt = std::move(dlt);
  } else {
    TsaiResult tsai = SolveTsai(obs, c.image_size, options.tsai);
    if (tsai.status == TsaiStatus::kPointsBehind) {
      const Observation& o = obs[tsai.deepest_behind];
      char buf[240];
      std::snprintf(buf, sizeof buf, " (e.g. %s at (%.6g, %.6g, %.6g))", Locate(c, tsai.deepest_behind).c_str(),
                    o.point.x(), o.point.y(), o.point.z());
      tsai.message += buf;
    }
    if (tsai.status != TsaiStatus::kOk) {
      r->exit_code = TsaiStatusExitCode(tsai.status);
      r->message = tsai.message;
      r->tsai = std::move(tsai);
      return;
    }
    cam.method = "tsai";
    cam.camera = tsai.camera;
    cam.camera_from_world = tsai.camera_from_world;
    r->tsai = std::move(tsai);
  }
  cam.fit = ComputeVolumeFit(cam.camera, *cam.camera_from_world, c);
}

void StartPlanar(CalibrationResult* r, const CalibrationOptions& options) {
  Correspondences& c = r->used;
  const auto dropped = DropSparseViews(&c, kMinPointsPerPlanarView);
  r->warnings.insert(r->warnings.end(), dropped.begin(), dropped.end());
  if (c.views.size() < 2) {
    // A failing tool prints one line, so the skipped views are named here, not as warnings.
    std::string skipped;
    for (const std::string& d : dropped) skipped += (skipped.empty() ? " (" : "; ") + d;
    r->exit_code = ExitCode::kBadInput;
    r->message = "planar views need at least 2 views of " + std::to_string(kMinPointsPerPlanarView) +
                 " or more points, got " + std::to_string(c.views.size()) + (skipped.empty() ? "" : skipped + ")") +
                 "; add views of the board at different orientations";
    return;
  }
  ZhangResult zhang = ZhangInitialization(c);
  // A fisheye's refinement starts from the best of the pinhole's and the equidistant starts, with
  // k1…k4 fitted to it (fisheye_start.h): neither alone suits both wide and narrow lenses.
  const auto solved = LensModelFromName(options.refinement.lens_model);
  if (solved && std::visit([](const auto& m) { return std::decay_t<decltype(m)>::kOnRay; }, *solved)) {
    FisheyeStart start = ChooseFisheyeStart(c, zhang);
    zhang = std::move(start.start);
    r->fisheye_start = std::move(start.decision);
  }
  if (!zhang.ok) {
    r->exit_code = ExitCode::kDegenerate;
    r->message = zhang.message;
    return;
  }
  CalibratedCamera& cam = r->camera;
  cam.method = "zhang";
  cam.camera = zhang.camera;
  for (size_t v = 0; v < c.views.size(); ++v) cam.views.push_back({c.views[v].name, zhang.camera_from_board[v], 0});
  cam.fit = ComputeViewsFit(cam.camera, zhang.camera_from_board, c);
  for (size_t v = 0; v < c.views.size(); ++v) cam.views[v].rms_px = cam.fit->views[v].stats.rms_px;
}


// One plane (Tsai's coplanar variant): its homography fixes 8 numbers, the pose takes 6, and a
// pinhole's f, cx, cy would need 3 more (Zhang 2000, §3.1), so the refinement keeps Tsai's aspect
// fx/fy = sx, and places the principal point under a prior centred where Tsai assumed it (or holds
// it there, or frees it): docs/math/uncertainty.md#one-plane. Returns the decision to record.
PlanePrincipalPointDecision OnePlaneRefinement(const TsaiResult& tsai, const ImageSize& size,
                                               const CalibrationOptions& options, RefineOptions* refinement) {
  if (refinement->free_focal) {  // a caller's hold of fx and fy holds the aspect already
    refinement->focal_aspect = tsai.sx;
    refinement->focal_aspect_held_because =
        "one plane: Tsai's coplanar sx, as one plane cannot tell the aspect from f and the principal point";
  }
  PlanePrincipalPointDecision d;
  d.mode = options.plane_principal_point;
  d.prior_px = tsai.principal_point;
  // The caller's own prior or hold on the principal point (calib-tsai --prior, --hold) replaces the rule.
  if (PlacesPrincipalPoint(*refinement)) {
    if (!refinement->free_principal_point) {
      d.mode = CalibrationOptions::PlanePrincipalPoint::kHold;
      d.because = "held by the caller: the sigmas are conditional on it";
      return d;
    }
    d.mode = CalibrationOptions::PlanePrincipalPoint::kPrior;
    for (const IntrinsicPrior& p : refinement->priors) {
      if (p.parameter != "cx" && p.parameter != "cy") continue;
      (p.parameter == "cx" ? d.prior_px.x() : d.prior_px.y()) = p.value;
      d.prior_sigma_px = std::max(d.prior_sigma_px, p.sigma);
    }
    d.because = "estimated under the caller's prior";
    return d;
  }
  switch (d.mode) {
    case CalibrationOptions::PlanePrincipalPoint::kHold:
      refinement->free_principal_point = false;
      refinement->principal_point_held_because =
          "one plane: held where Tsai's stages assumed it (the image centre or the principal point given), as asked; "
          "the sigmas are conditional on it";
      d.because = "held, as asked: the sigmas are conditional on it";
      break;
    case CalibrationOptions::PlanePrincipalPoint::kFree:
      d.because = "estimated without a prior, as asked";
      break;
    case CalibrationOptions::PlanePrincipalPoint::kPrior: {
      d.prior_sigma_px = PrincipalPointPriorSigmaPx(size, options.plane_principal_point_prior_sigma);
      char because[200];
      std::snprintf(because, sizeof because,
                    "one plane: a prior at Tsai's principal point, sigma %.4g of the image diagonal (%.4g px)",
                    options.plane_principal_point_prior_sigma, d.prior_sigma_px);
      AddPrincipalPointPrior(d.prior_px, d.prior_sigma_px, because, refinement);
      d.because = "estimated under the one-plane prior";
      break;
    }
  }
  return d;
}

CalibrationResult CalibrateOnce(Correspondences correspondences, const CalibrationOptions& options);

// Parameters the solve estimated, of which `per_view` belong to one view alone.
std::pair<size_t, size_t> EstimatedParameters(const CalibrationResult& r) {
  const bool volume = r.used.rig == Rig::kVolume;
  const size_t per_view = volume ? 0 : 6;
  if (r.refinement) {
    const size_t lens = r.refinement->free.MovedParams(r.refinement->camera.model).size();
    return {lens + 6 * r.refinement->poses.size(), per_view};
  }
  if (volume) return {11, 0};  // DLT's P, or Tsai's pinhole with κ₁ (12): the share differs by < 1/N
  return {4 + 6 * r.used.views.size(), per_view};  // Zhang: fx, fy, cx, cy and each board's pose
}

// Solve → test → reject until the test passes (docs/math/uncertainty.md#view-rejection).
CalibrationResult CalibrateRejecting(Correspondences c, const CalibrationOptions& options) {
  const ViewRejectionOptions& o = options.reject_views;
  std::vector<std::string> warnings;
  if (c.rig == Rig::kPlanarViews) warnings = DropSparseViews(&c, kMinPointsPerPlanarView);
  // Where each kept view and point came from in the input.
  std::vector<size_t> view_index(c.views.size());
  std::vector<std::vector<size_t>> point_index(c.views.size());
  for (size_t v = 0; v < c.views.size(); ++v) {
    view_index[v] = v;
    for (size_t i = 0; i < c.views[v].observations.size(); ++i) point_index[v].push_back(i);
  }
  const size_t min_views = c.rig == Rig::kVolume ? kMinVolumeViewsKept : kMinPlanarViewsKept;
  std::vector<Rejection> rejections;
  const auto erase_view = [&](size_t v) {
    c.views.erase(c.views.begin() + static_cast<std::ptrdiff_t>(v));
    view_index.erase(view_index.begin() + static_cast<std::ptrdiff_t>(v));
    point_index.erase(point_index.begin() + static_cast<std::ptrdiff_t>(v));
  };
  // Rejects test.worst_view, or returns the refusal when too few views would remain.
  const auto reject_view = [&](const RejectionTest& t, int round, const char* of) -> std::optional<CalibrationResult> {
    const size_t v = *t.worst_view;
    Rejection x;
    x.kind = Rejection::Kind::kView;
    x.round = round;
    x.view = view_index[v];
    x.view_name = c.views[v].name;
    x.rms_px = t.view_rms_px[v];
    x.threshold_px = t.view_threshold_px[v];
    char buf[360];
    std::snprintf(buf, sizeof buf,
                  "view RMS %.4g px > %.4g px%s: chi-square threshold for its dof at false alarm %g over %zu views, "
                  "robust sigma %.4g px from the median view",
                  x.rms_px, x.threshold_px, of, o.view_false_alarm, c.views.size(), t.sigma_px);
    x.because = buf;
    if (c.views.size() - 1 < min_views) {
      CalibrationResult refused;
      refused.exit_code = ExitCode::kBadInput;
      refused.rejections = rejections;
      refused.message = VSTCAL_OPT("reject_views") ": view \"" + x.view_name + "\" is inconsistent with the others (" + x.because +
                        "), but rejecting it would leave " + std::to_string(c.views.size() - 1) + " views, fewer than the " +
                        std::to_string(min_views) + (c.rig == Rig::kVolume ? " a volume" : " planar views") +
                        " need; recapture that view or add views, or drop " VSTCAL_OPT("reject_views");
      return refused;
    }
    rejections.push_back(x);
    erase_view(v);
    return std::nullopt;
  };
  for (int round = 1;; ++round) {
    CalibrationResult r = CalibrateOnce(c, options);
    r.warnings.insert(r.warnings.begin(), warnings.begin(), warnings.end());
    r.rejections = rejections;
    r.rejection_rounds = round;
    if (r.exit_code != ExitCode::kOk && options.refine && round < o.max_rounds) {
      // A refinement that fails with a bad view in (a mislabelled one can pull it into an
      // unobservable corner) is no verdict on the views: the closed-form start of the same set is
      // tested instead, for its worst view only (its residuals also hold the unmodelled
      // distortion, so its corners are not judged).
      CalibrationOptions start = options;
      start.refine = false;
      const CalibrationResult s = CalibrateOnce(c, start);
      if (s.exit_code == ExitCode::kOk) {
        const auto [num_params, per_view] = EstimatedParameters(s);
        const RejectionTest t = TestResiduals(c, *s.camera.fit, num_params, per_view, o);
        if (t.worst_view) {
          if (auto refused = reject_view(t, round, " (of the closed-form start: the refinement failed with it)")) {
            return *refused;
          }
          continue;
        }
      }
    }
    if (r.exit_code != ExitCode::kOk) {
      if (!rejections.empty()) {
        r.exit_code = ExitCode::kBadInput;
        r.message = VSTCAL_OPT("reject_views") ": after rejecting " + std::to_string(rejections.size()) +
                    " views or corners (last: view \"" + rejections.back().view_name +
                    "\"), the rest cannot be solved: " + r.message +
                    "; fix or recapture the rejected views, or drop " VSTCAL_OPT("reject_views");
      }
      return r;
    }
    const auto [num_params, per_view] = EstimatedParameters(r);
    const RejectionTest t = TestResiduals(c, *r.camera.fit, num_params, per_view, o);
    r.rejection_sigma_px = t.sigma_px;
    if (!t.worst_view && t.corners.empty()) return r;
    if (round >= o.max_rounds) {
      r.warnings.push_back(VSTCAL_OPT("reject_views") ": still rejecting after " + std::to_string(o.max_rounds) +
                           " rounds; the last solve is kept with what it would have rejected");
      return r;
    }
    if (t.worst_view) {
      if (auto refused = reject_view(t, round, "")) return *refused;
      continue;
    }
    // Corners, from the last of each view backwards so that indices stay valid; reported in order.
    const size_t first = rejections.size();
    for (auto it = t.corners.rbegin(); it != t.corners.rend(); ++it) {
      Rejection x;
      x.kind = Rejection::Kind::kCorner;
      x.round = round;
      x.view = view_index[it->view];
      x.view_name = c.views[it->view].name;
      x.point = point_index[it->view][it->point];
      x.rms_px = it->residual_px;
      x.threshold_px = it->threshold_px;
      char buf[300];
      std::snprintf(buf, sizeof buf,
                    "corner residual %.4g px > %.4g px: chi-square(2) threshold at false alarm %g over %zu corners, "
                    "robust sigma %.4g px",
                    x.rms_px, x.threshold_px, o.corner_false_alarm, NumObservations(c), t.sigma_px);
      x.because = buf;
      rejections.push_back(x);
      auto& obs = c.views[it->view].observations;
      obs.erase(obs.begin() + static_cast<std::ptrdiff_t>(it->point));
      point_index[it->view].erase(point_index[it->view].begin() + static_cast<std::ptrdiff_t>(it->point));
    }
    std::reverse(rejections.begin() + static_cast<std::ptrdiff_t>(first), rejections.end());
    if (c.rig == Rig::kPlanarViews) {
      for (size_t v = c.views.size(); v-- > 0;) {
        if (c.views[v].observations.size() >= kMinPointsPerPlanarView) continue;
        warnings.push_back(VSTCAL_OPT("reject_views") ": view \"" + c.views[v].name + "\" has fewer than " +
                           std::to_string(kMinPointsPerPlanarView) + " corners left after rejecting corners; dropped");
        erase_view(v);
      }
    }
  }
}

}  // namespace

CalibrationResult Calibrate(Correspondences correspondences, const CalibrationOptions& options) {
  CalibrationResult r = options.reject_views.enabled ? CalibrateRejecting(std::move(correspondences), options)
                                                     : CalibrateOnce(std::move(correspondences), options);
  // Here, not in CalibrateOnce: view rejection tests an unrefined start that may be far off on purpose.
  if (r.exit_code == ExitCode::kOk && !options.refine) RefuseImplausibleClosedForm(&r);
  return r;
}

namespace {

CalibrationResult CalibrateOnce(Correspondences correspondences, const CalibrationOptions& options) {
  CalibrationResult r;
  r.used = std::move(correspondences);
  r.camera.name = r.used.camera;
  r.camera.length_unit = r.used.length_unit;
  if (r.used.rig == Rig::kVolume) {
    StartVolume(&r, options);
  } else {
    StartPlanar(&r, options);
  }
  if (r.exit_code != ExitCode::kOk || !options.refine) return r;
  RefineOptions refinement = options.refinement;
  const bool one_plane = r.tsai && r.tsai->variant == TsaiOptions::Variant::kCoplanar;
  if (!one_plane && options.plane_principal_point != CalibrationOptions::PlanePrincipalPoint::kPrior) {
    throw InputError(VSTCAL_OPT("free_principal_point") ": applies to one plane (Tsai's coplanar variant) only; a volume's or planar "
                     "views' principal point is always estimated; remove it");
  }
  if (one_plane) r.plane_principal_point = OnePlaneRefinement(*r.tsai, r.used.image_size, options, &refinement);

  // A parameter not estimated is zero, not frozen at its start: a DLT start's small skew and a
  // Tsai start's k1, k2, k3 (converted from κ₁) would otherwise stay in the refined model
  // unestimated, outside the covariance, and bias the parameters that are estimated.
  Camera start = r.camera.camera;
  if (!refinement.free_skew) start.params[intrinsic::kSkew] = 0;
  const auto names = LensModelParamNames(start.model);
  const std::vector<std::string>& free = refinement.free_distortion;
  for (size_t i = kNumIntrinsicParams; i < names.size(); ++i) {
    if (std::find(free.begin(), free.end(), names[i]) == free.end()) start.params[i] = 0;
  }
  if (free.empty()) start = Camera::FromK(start.K(), start.image_size);  // "none": a pinhole
  // A lens model of another family (a fisheye after Tsai's radial start) starts from the pinhole.
  if (const auto named = LensModelFromName(refinement.lens_model); named && !LensModelExtends(*named, start.model)) {
    start = Camera::FromK(start.K(), start.image_size);
  }
  std::vector<Rigid3d> poses;
  if (r.used.rig == Rig::kVolume) {
    poses.push_back(*r.camera.camera_from_world);
  } else {
    for (const ViewPose& v : r.camera.views) poses.push_back(v.camera_from_board);
  }
  Refinement refined = Refine(r.used, start, poses, refinement);
  if (one_plane && !refined.covariance.empty() && refined.covariance.Find("cx") && refined.covariance.Find("cy")) {
    const ParameterCovariance& cov = refined.covariance;
    r.plane_principal_point->posterior_sigma_px =
        Eigen::Vector2d(std::sqrt(cov.matrix(*cov.Find("cx"), *cov.Find("cx"))), std::sqrt(cov.matrix(*cov.Find("cy"), *cov.Find("cy"))));
  }
  ApplyRefinement(&r, std::move(refined));
  return r;
}

}  // namespace

}  // namespace vstcal
