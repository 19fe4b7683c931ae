#include "vstcal/report/fit_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

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

std::string ParametersText(const CalibratedCamera& c, std::span<const HeldIntrinsic> held, size_t worst) {
  std::string out;
  if (!c.fit && !c.covariance) return out;
  const auto names = LensModelParamNames(c.camera.model);
  Append(&out, "  %-6s %16s %14s   %s\n", "param", "estimate", "1-sigma", "3-sigma interval (or why held)");
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string name(names[i]);
    const double value = c.camera.params[i];
    const auto is_held = std::find_if(held.begin(), held.end(), [&](const HeldIntrinsic& h) { return h.parameter == name; });
    const std::optional<size_t> k = c.covariance ? c.covariance->Find(name) : std::nullopt;
    if (is_held != held.end()) {
      Append(&out, "  %-6s %16.8g %14s   held: %s\n", name.c_str(), value, "", is_held->because.c_str());
    } else if (k) {
      const double sigma = std::sqrt(std::max(0.0, c.covariance->matrix(*k, *k)));
      Append(&out, "  %-6s %16.8g %14.4g   [%.8g, %.8g]\n", name.c_str(), value, sigma, value - 3 * sigma, value + 3 * sigma);
    } else {
      Append(&out, "  %-6s %16.8g %14s\n", name.c_str(), value, c.covariance ? "(not estimated)" : "(no covariance)");
    }
  }
  if (!c.fit) return out;
  const std::vector<ViewFit>& views = c.fit->views;
  if (views.size() > 1 && worst > 0) {
    std::vector<size_t> order(views.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return views[a].stats.rms_px > views[b].stats.rms_px; });
    out += "  worst views by RMS:";
    for (size_t i = 0; i < std::min(worst, order.size()); ++i) {
      Append(&out, "%s %s %.4f px", i == 0 ? "" : ",", views[order[i]].name.c_str(), views[order[i]].stats.rms_px);
    }
    out += "\n";
  }
  return out;
}

}  // namespace vstcal
