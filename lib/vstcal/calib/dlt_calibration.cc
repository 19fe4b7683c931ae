#include "vstcal/calib/dlt_calibration.h"

#include <cstdio>

namespace vstcal {
namespace {

// "views[2].points[17] (plane-02)" for a flat observation index.
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

}  // namespace

DltCalibration CalibrateDlt(const Correspondences& c, const DltOptions& options) {
  VSTCAL_CHECK(c.rig == Rig::kVolume, "DLT needs a volume rig");
  DltCalibration out;
  const std::vector<Observation> obs = AllObservations(c);
  out.dlt = SolveDlt(obs, options);
  if (out.dlt.status == DltStatus::kPointsBehind) {
    const Observation& o = obs[out.dlt.deepest_behind];
    char buf[200];
    std::snprintf(buf, sizeof buf, " (e.g. %s at (%.6g, %.6g, %.6g), depth %.4g %s)",
                  Locate(c, out.dlt.deepest_behind).c_str(), o.point.x(), o.point.y(), o.point.z(),
                  out.dlt.P.row(2).dot(o.point.homogeneous()), std::string(LengthUnitName(c.length_unit)).c_str());
    out.dlt.message += buf;
  }
  if (out.dlt.status != DltStatus::kOk) return out;

  const auto decomposition = DecomposeProjection(out.dlt.P);
  VSTCAL_CHECK(decomposition.has_value(), "a normalized, non-mirrored P always decomposes");
  CalibratedCamera cam;
  cam.name = c.camera;
  cam.camera = Camera::FromK(decomposition->K, c.image_size);
  cam.length_unit = c.length_unit;
  cam.method = "dlt";
  cam.camera_from_world = decomposition->camera_from_world;
  cam.P = out.dlt.P;
  cam.fit = ComputeVolumeFit(cam.camera, *cam.camera_from_world, c);
  out.camera = std::move(cam);
  out.eq13 = DecomposeProjectionEq13(out.dlt.P);
  return out;
}

}  // namespace vstcal
