#include "vstcal/capture/synthetic_camera.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "vstcal/camera/intrinsics.h"
#include "vstcal/camera/opencv_distortion.h"
#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

std::string CameraNum(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// A pixel quantity (focal length, principal point) within ±limits::kMaxSyntheticScale.
double InScale(std::optional<double> v, double fallback, const std::string& flag) {
  const double x = v.value_or(fallback);
  if (!(std::abs(x) <= limits::kMaxSyntheticScale)) {
    throw InputError(flag + ": " + CameraNum(x) + " px is beyond ±" + CameraNum(limits::kMaxSyntheticScale) +
                     " (docs/reliability.md#limits); give a realistic value");
  }
  return x;
}

}  // namespace

Camera MakeSyntheticCamera(const SyntheticCameraSpec& spec) {
  const auto [w, h] = spec.image_size;
  if (!(w >= 1 && h >= 1 && w <= limits::kMaxImageSide && h <= limits::kMaxImageSide)) {
    throw InputError(VSTCAL_OPT("image_size") ": each side must be 1 to " + std::to_string(limits::kMaxImageSide) + " px");
  }
  if (spec.fx.has_value() == spec.hfov_deg.has_value()) throw InputError(VSTCAL_OPT("fx") "/" VSTCAL_OPT("hfov_deg") ": give exactly one of them");
  if (spec.hfov_deg && !(*spec.hfov_deg > 0 && *spec.hfov_deg < 180)) {
    throw InputError(VSTCAL_OPT("hfov_deg") ": must lie in (0, 180) degrees for a pinhole camera, got " + CameraNum(*spec.hfov_deg));
  }
  if (!(spec.skew_deg > 0 && spec.skew_deg < 180)) throw InputError(VSTCAL_OPT("skew_deg") ": must lie in (0, 180); 90 means no skew");
  const double fx = InScale(spec.fx, spec.fx ? 0.0 : FocalFromHorizontalFov(w, DegToRad(*spec.hfov_deg)),
                            spec.fx ? VSTCAL_OPT("fx") : VSTCAL_OPT("hfov_deg"));
  const double fy = InScale(spec.fy, fx, VSTCAL_OPT("fy"));
  if (!(fx > 0) || !(fy > 0)) throw InputError(VSTCAL_OPT("fx") "/" VSTCAL_OPT("fy") "/" VSTCAL_OPT("hfov_deg") ": focal lengths must be positive");
  Eigen::Matrix3d K;
  K << fx, spec.skew_deg == 90 ? 0.0 : -fx / std::tan(DegToRad(spec.skew_deg)), InScale(spec.cx, 0.5 * (w - 1), VSTCAL_OPT("cx")),
      0, fy, InScale(spec.cy, 0.5 * (h - 1), VSTCAL_OPT("cy")),  //
      0, 0, 1;
  for (const double k : spec.distortion) {
    if (!std::isfinite(k)) throw InputError(VSTCAL_OPT("distortion") ": must be finite numbers, got " + CameraNum(k));
  }
  const int n = static_cast<int>(spec.distortion.size());
  if (n != 0 && n != 5 && n != 8) {
    throw InputError(VSTCAL_OPT("distortion") ": expected 5 numbers k1,k2,p1,p2,k3 (radial-tangential) or 8 "
                     "k1,k2,p1,p2,k3,k4,k5,k6 (rational), got " + std::to_string(n));
  }
  return CameraFromOpenCv(K, ImageSize{w, h}, spec.distortion);
}

CalibratedCamera SyntheticTruth(const Camera& camera, const std::string& name, LengthUnit unit) {
  CalibratedCamera truth;
  truth.name = name;
  truth.camera = camera;
  truth.length_unit = unit;
  truth.method = "synthetic";
  return truth;
}

}  // namespace vstcal
