#include "vstcal/calib/pipeline.h"

#include <cstdio>

#include <Eigen/Geometry>

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
    r->exit_code = ExitCode::kDegenerate;
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
  if (!refinement.covariance.parameters.empty()) cam.covariance = refinement.covariance;
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
  const ZhangResult zhang = ZhangInitialization(c);
  if (!zhang.ok) {
    r->exit_code = c.views.size() < 2 ? ExitCode::kBadInput : ExitCode::kDegenerate;
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

  // Skew not estimated means skew zero: a DLT start's small skew is dropped, not frozen.
  Camera start = r.camera.camera;
  if (!options.refinement.free_skew) start.params[4] = 0;
  std::vector<Rigid3d> poses;
  if (r.used.rig == Rig::kVolume) {
    poses.push_back(*r.camera.camera_from_world);
  } else {
    for (const ViewPose& v : r.camera.views) poses.push_back(v.camera_from_board);
  }
  ApplyRefinement(&r, Refine(r.used, start, poses, options.refinement));
  return r;
}

}  // namespace vstcal
