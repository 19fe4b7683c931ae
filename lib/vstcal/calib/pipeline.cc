#include "vstcal/calib/pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "vstcal/estimators/information.h"

namespace vstcal {
namespace {

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
  if (!refinement.covariance.empty()) cam.covariance = refinement.covariance;
  r->refinement = std::move(refinement);
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

void StartPlanar(CalibrationResult* r) {
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
  const ZhangResult zhang = ZhangInitialization(c);
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
// pinhole's f, cx, cy would need 3 more (Zhang 2000, §3.1), so the refinement keeps Tsai's own
// assumptions: fx/fy = sx, and the principal point where Tsai assumed it, unless freed
// (docs/math/uncertainty.md#one-plane).
void HoldWhatOnePlaneCannotDetermine(const TsaiResult& tsai, const CalibrationOptions& options, RefineOptions* refinement) {
  refinement->focal_aspect = tsai.sx;
  refinement->focal_aspect_held_because =
      "one plane: Tsai's coplanar sx (--sx), as one plane cannot tell the aspect from f and the principal point";
  if (options.plane_principal_point != CalibrationOptions::PlanePrincipalPoint::kFree) {
    refinement->free_principal_point = false;
    refinement->principal_point_held_because =
        options.plane_principal_point == CalibrationOptions::PlanePrincipalPoint::kHold
            ? "one plane: held where Tsai's stages assumed it (the image centre or --principal-point); "
              "--free-principal-point yes or auto frees it"
            : "one plane: held where Tsai's stages assumed it; --free-principal-point auto left it held (see "
              "refinement.one_plane)";
  }
}

// kAuto: at the held optimum, would the principal point be determined, and how well? Frees it
// (refining again from the held optimum) when the scaled information is regular with cx, cy free
// and both σ's are within the limit. Leaves `refined` as it is otherwise.
PlanePrincipalPointDecision DecidePlanePrincipalPoint(const Correspondences& c, const CalibrationOptions& options,
                                                      RefineOptions* refinement, Refinement* refined) {
  PlanePrincipalPointDecision d;
  d.mode = options.plane_principal_point;
  d.freed = d.mode == CalibrationOptions::PlanePrincipalPoint::kFree;
  const ImageSize& size = c.image_size;
  d.limit_px = options.plane_principal_point_max_sigma * std::hypot(size.width, size.height);
  if (d.mode == CalibrationOptions::PlanePrincipalPoint::kHold) {
    d.because = "held (--free-principal-point no)";
    return d;
  }
  if (d.mode == CalibrationOptions::PlanePrincipalPoint::kFree) {
    d.because = "freed (--free-principal-point yes)";
    return d;
  }
  if (refined->status != RefineStatus::kConverged) {
    d.because = "held: the refinement with it held did not converge";
    return d;
  }
  RefineOptions freed = *refinement;
  freed.free_principal_point = true;
  const CalibrationCovariance cov = CovarianceAt(c, refined->camera, refined->poses, freed, refined->sigma_px);
  if (!cov.observable) {
    d.because = "held: with it free, " + cov.weakest;
    return d;
  }
  d.sigma_if_free_px = Eigen::Vector2d(std::sqrt(cov.covariance.matrix(*cov.covariance.Find("cx"), *cov.covariance.Find("cx"))),
                                       std::sqrt(cov.covariance.matrix(*cov.covariance.Find("cy"), *cov.covariance.Find("cy"))));
  char buf[200];
  std::snprintf(buf, sizeof buf, "its sigma with it free would be (%.3g, %.3g) px, limit %.3g px", d.sigma_if_free_px->x(),
                d.sigma_if_free_px->y(), d.limit_px);
  if (d.sigma_if_free_px->maxCoeff() > d.limit_px) {
    d.because = std::string("held: ") + buf;
    return d;
  }
  d.freed = true;
  d.because = std::string("freed: ") + buf;
  *refinement = freed;
  *refined = Refine(c, refined->camera, refined->poses, freed);
  return d;
}

}  // namespace

CalibrationResult Calibrate(Correspondences correspondences, const CalibrationOptions& options) {
  CalibrationResult r;
  r.used = std::move(correspondences);
  r.camera.name = r.used.camera;
  r.camera.length_unit = r.used.length_unit;
  if (r.used.rig == Rig::kVolume) {
    StartVolume(&r, options);
  } else {
    StartPlanar(&r);
  }
  if (r.exit_code != ExitCode::kOk || !options.refine) return r;
  RefineOptions refinement = options.refinement;
  const bool one_plane = r.tsai && r.tsai->variant == TsaiOptions::Variant::kCoplanar;
  if (!one_plane && options.plane_principal_point != CalibrationOptions::PlanePrincipalPoint::kHold) {
    throw InputError("--free-principal-point: applies to one plane (Tsai's coplanar variant) only; a volume's or planar "
                     "views' principal point is always estimated; remove it");
  }
  if (one_plane) HoldWhatOnePlaneCannotDetermine(*r.tsai, options, &refinement);

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
  std::vector<Rigid3d> poses;
  if (r.used.rig == Rig::kVolume) {
    poses.push_back(*r.camera.camera_from_world);
  } else {
    for (const ViewPose& v : r.camera.views) poses.push_back(v.camera_from_board);
  }
  Refinement refined = Refine(r.used, start, poses, refinement);
  if (one_plane) {
    r.plane_principal_point = DecidePlanePrincipalPoint(r.used, options, &refinement, &refined);
  }
  ApplyRefinement(&r, std::move(refined));
  return r;
}

}  // namespace vstcal
