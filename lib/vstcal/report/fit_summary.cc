#include "vstcal/report/fit_summary.h"

#include <cstdio>

#include "vstcal/core/string_printf.h"
#include "vstcal/scene/measured_volume.h"
#include "vstcal/camera/intrinsics.h"

namespace vstcal {
namespace {

void Append(std::string* out, const char* fmt, auto... args) { *out += StringPrintf(fmt, args...); }

}  // namespace

std::string FitSummaryText(const CalibratedCamera& c) {
  std::string out;
  const Eigen::Matrix3d K = c.camera.K();
  const SkewForm f = SkewFormFromK(K);
  Append(&out, "  K: fx %.3f  fy %.3f  cx %.3f  cy %.3f  skew %.4g (θ = %.5f°)\n", K(0, 0), K(1, 1), K(0, 2), K(1, 2),
         K(0, 1), RadToDeg(f.theta_rad));
  const std::string unit(LengthUnitName(c.length_unit));
  if (c.camera_from_world) {
    const Eigen::Vector3d centre = c.camera_from_world->inverse().t;
    Append(&out, "  camera centre in world: (%.2f, %.2f, %.2f) %s\n", centre.x(), centre.y(), centre.z(), unit.c_str());
  }
  if (!c.fit) return out;
  const Fit& fit = *c.fit;
  Append(&out, "  reprojection: RMS %.4f px, max %.4f px over %zu points in %zu views\n", fit.overall.rms_px,
         fit.overall.max_px, fit.overall.n_points, fit.views.size());
  if (fit.n_behind_camera > 0) Append(&out, "  %zu points project behind the camera\n", fit.n_behind_camera);
  if (!fit.test_points.empty()) {
    Append(&out, "  %-14s %-8s %s\n", "test point", "volume", "error px");
    for (const TestPointFit& t : fit.test_points) {
      const auto e = t.error_px();
      if (e) {
        Append(&out, "  %-14s %-8s %.4f\n", t.name.c_str(), VolumeSideName(t.inside_volume), *e);
      } else {
        Append(&out, "  %-14s %-8s %s\n", t.name.c_str(), VolumeSideName(t.inside_volume),
               t.predicted ? "(not measured)" : "(behind camera)");
      }
    }
  }
  return out;
}

}  // namespace vstcal
