#include "vstcal/stereo/display_plan.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/core/option_name.h"

namespace vstcal {

std::string_view ViewerName(Viewer viewer) {
  return NameOf(kViewerNames, viewer);
}

double CrossedDisparityPx(double focal_px, double baseline, double depth) { return focal_px * baseline / depth; }

std::optional<double> PerceivedDepthHmd(double ipd, double focal_px, double disparity_px, double translation_px) {
  const double converging = disparity_px - translation_px;
  if (!(converging > 0)) return std::nullopt;
  return ipd * focal_px / converging;
}

std::optional<double> PerceivedDepthScreen(double ipd, double viewing_distance, double screen_parallax) {
  if (!(screen_parallax < ipd)) return std::nullopt;
  return ipd * viewing_distance / (ipd - screen_parallax);
}

namespace {

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

void RequirePositive(double v, const char* flag) {
  if (!(v > 0) || !std::isfinite(v)) {
    throw InputError(std::string(flag) + ": must be a positive finite number, got " + Number(v) +
                     "; give a length > 0");
  }
}

}  // namespace

DisplayPlan PlanDisplay(const DisplayPlanInput& in) {
  RequirePositive(in.baseline, VSTCAL_OPT("baseline"));
  if (in.z0) RequirePositive(*in.z0, VSTCAL_OPT("z0"));
  if (in.display_width <= 0) throw InputError(VSTCAL_OPT("display_width") ": must be a positive number of pixels; give the display's width A > 0");
  if (in.focal_px.has_value() == in.hfov_rad.has_value()) {
    throw InputError(VSTCAL_OPT("focal_px") ", " VSTCAL_OPT("hfov_deg") ": give exactly one: the capture's focal length in px or its horizontal field of view");
  }
  for (const double z : in.depths) RequirePositive(z, VSTCAL_OPT("depths"));
  if (in.viewer != Viewer::kNone) RequirePositive(in.ipd, VSTCAL_OPT("ipd"));
  if (in.viewer == Viewer::kScreen) {
    RequirePositive(in.screen_width, VSTCAL_OPT("screen_width"));
    RequirePositive(in.viewing_distance, VSTCAL_OPT("viewing_distance"));
  }
  DisplayPlan plan;
  const double A = in.display_width;
  if (in.focal_px) {
    RequirePositive(*in.focal_px, VSTCAL_OPT("focal_px"));
    plan.focal_px = *in.focal_px;
    plan.translation_px = in.z0 ? CrossedDisparityPx(plan.focal_px, in.baseline, *in.z0) : 0.0;
    plan.capture_width_needed = A + plan.translation_px;
  } else {
    const double theta = *in.hfov_rad;
    if (!(theta > 0 && theta < kPi)) {
      throw InputError(VSTCAL_OPT("hfov_deg") ": must lie in (0°, 180°), got " + Number(RadToDeg(theta)) +
                       "°; give the capture's horizontal field of view");
    }
    // Eq. 6 with f = A′/(2 tan(θ/2)): A′ = A + A′·b/(2 tan(θ/2) z0).
    const double overlap_depth = in.baseline / (2 * std::tan(theta / 2));
    const double fraction = in.z0 ? overlap_depth / *in.z0 : 0.0;
    if (!(fraction < 1)) {
      throw InputError(VSTCAL_OPT("z0") ": " + Number(*in.z0) + " is not beyond " + Number(overlap_depth) +
                       ", the depth b/(2·tan(θ/2)) where the two fields of view begin to overlap: no capture width "
                       "holds the translation (seed 000 Eq. 6); choose a farther zero-parallax depth");
    }
    // f from Eq. 6's A′, then t and A + t as with a given f, so that p(z0) = t − d(z0) is exactly 0.
    plan.focal_px = A / (1 - fraction) / (2 * std::tan(theta / 2));
    plan.translation_px = in.z0 ? CrossedDisparityPx(plan.focal_px, in.baseline, *in.z0) : 0.0;
    plan.capture_width_needed = A + plan.translation_px;
  }
  if (in.capture_width) plan.capture_margin_px = *in.capture_width - static_cast<int>(std::ceil(plan.capture_width_needed - 1e-9));
  const double t = plan.translation_px;
  if (in.viewer == Viewer::kHmd && in.z0) plan.diverges_beyond = *in.z0;
  if (in.viewer == Viewer::kScreen) {
    // p·S/A = I with p = t − f b/z: f b/z = t − I A/S.
    const double limit = t - in.ipd * A / in.screen_width;
    if (limit > 0) plan.diverges_beyond = plan.focal_px * in.baseline / limit;
  }
  for (const double z : in.depths) {
    DepthRow row;
    row.depth = z;
    row.disparity_px = CrossedDisparityPx(plan.focal_px, in.baseline, z);
    row.parallax_px = t - row.disparity_px;
    row.side = !in.z0 ? -1 : z < *in.z0 ? -1 : z > *in.z0 ? 1 : 0;
    if (in.viewer == Viewer::kHmd) row.perceived_depth = PerceivedDepthHmd(in.ipd, plan.focal_px, row.disparity_px, t);
    if (in.viewer == Viewer::kScreen) {
      row.perceived_depth = PerceivedDepthScreen(in.ipd, in.viewing_distance, row.parallax_px * in.screen_width / A);
    }
    plan.rows.push_back(row);
  }
  return plan;
}

}  // namespace vstcal
