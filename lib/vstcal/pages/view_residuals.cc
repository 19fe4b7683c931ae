#include "vstcal/pages/view_residuals.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "vstcal/pages/html_page.h"
#include "vstcal/pages/overlay.h"

namespace vstcal {
namespace {

constexpr int kPlotWidth = 240;  // CSS px a plot is shown at

std::string Fixed(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

}  // namespace

std::vector<size_t> WorstViewsFirst(const CameraReport& cam) {
  std::vector<size_t> order(cam.views.size());
  std::iota(order.begin(), order.end(), size_t{0});
  auto rms = [&](size_t v) { return cam.views[v].error_px ? cam.views[v].error_px->rms : -1.0; };
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return rms(a) > rms(b); });
  return order;
}

std::string ViewResidualPlots(const ReprojReport& report, size_t camera) {
  const CameraReport& cam = report.cameras[camera];
  const ImageSize& size = report.correspondences.image_size;
  const double scale = ResidualVectorScale(size, cam.overall.error_px);
  const double p95 = cam.overall.error_px ? std::max(cam.overall.error_px->p95, 1e-12) : 1.0;
  const std::string w = std::to_string(size.width), h = std::to_string(size.height);
  const int height = static_cast<int>(std::lround(kPlotWidth * static_cast<double>(size.height) / size.width));
  const std::vector<size_t> order = WorstViewsFirst(cam);
  const size_t shown = std::min(order.size(), kMaxViewPlots);
  std::string plots;
  size_t decimated = 0;
  for (size_t i = 0; i < shown; ++i) {
    const ViewReport& view = cam.views[order[i]];
    const size_t stride = (view.points.size() + kMaxPointsPerView - 1) / kMaxPointsPerView;
    decimated += stride > 1;
    // Three colour bands of |r| / p95, as the overlay's green-to-red ramp.
    std::array<std::string, 3> vectors;
    std::string points;
    size_t drawn = 0;
    for (size_t p = 0; p < view.points.size(); p += std::max<size_t>(stride, 1)) {
      const PointError& e = view.points[p];
      if (e.excluded != Exclusion::kNone || !e.predicted) continue;
      // Pixel centres at integers: +0.5 puts the image's edges on the viewBox's.
      const std::string at = "M" + Fixed(e.measured.x() + 0.5) + " " + Fixed(e.measured.y() + 0.5);
      const Eigen::Vector2d d = scale * (*e.predicted - e.measured);
      const size_t band = std::min<size_t>(2, static_cast<size_t>(3 * e.error_px / p95));
      vectors[band] += at + "l" + Fixed(d.x()) + " " + Fixed(d.y());
      points += at + "h0";
      ++drawn;
    }
    static constexpr std::array<const char*, 3> kColours = {"#00b400", "#e08000", "#e00000"};
    std::string paths;
    for (size_t b = 0; b < 3; ++b) {
      if (vectors[b].empty()) continue;
      paths += "<path class=\"vectors\" stroke=\"" + std::string(kColours[b]) + "\" stroke-width=\"1.5\" vector-effect=\"non-scaling-stroke\" d=\"" + vectors[b] + "\"/>";
    }
    char rms[48] = "no measured point";
    if (view.error_px) std::snprintf(rms, sizeof rms, "RMS %.3g px", view.error_px->rms);
    plots += "<figure class=\"view-residuals\" data-view=\"" + Escape(view.name) + "\" data-drawn=\"" + std::to_string(drawn) +
             "\"><svg viewBox=\"0 0 " + w + " " + h + "\" width=\"" + std::to_string(kPlotWidth) + "\" height=\"" +
             std::to_string(height) + "\" role=\"img\" aria-label=\"residual vectors, view " + Escape(view.name) +
             "\"><g fill=\"none\"><rect x=\"0\" y=\"0\" width=\"" + w + "\" height=\"" + h +
             "\" fill=\"#fff\" stroke=\"#bbb\" stroke-width=\"1\" vector-effect=\"non-scaling-stroke\"/>" + paths +
             "<path class=\"points\" stroke=\"#143c5a\" stroke-width=\"3\" stroke-linecap=\"round\" vector-effect=\"non-scaling-stroke\" d=\"" + points +
             "\"/></g></svg><figcaption>" + Escape(view.name) + ": " + rms + ", " + std::to_string(drawn) + " vectors" +
             (stride > 1 ? " (one point in " + std::to_string(stride) + ")" : "") + "</figcaption></figure>\n";
  }
  char scale_text[64];
  std::snprintf(scale_text, sizeof scale_text, "x%g", scale);
  std::string note = "Camera " + std::to_string(camera) + ": residual vectors on every view, the largest RMS first (as the views table), " +
                     scale_text + " as the overlay above; green below p95 / 3, orange below 2 p95 / 3, red above.";
  if (shown < order.size()) {
    note += " The " + std::to_string(shown) + " largest-RMS views of " + std::to_string(order.size()) +
            " are drawn (a page stays a few MB); every view's numbers are in the JSON report.";
  }
  if (decimated > 0) {
    note += " A view of more than " + std::to_string(kMaxPointsPerView) + " points shows one point in k (k the smallest that leaves at most " + std::to_string(kMaxPointsPerView) + ").";
  }
  return "<div class=\"small-multiples\" data-camera=\"" + std::to_string(camera) + "\" data-views=\"" + std::to_string(order.size()) +
         "\"><p>" + note + "</p>\n" + plots + "</div>\n";
}

}  // namespace vstcal
