#include "vstcal/pages/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "vstcal/image/codecs.h"
#include "vstcal/image/image_io.h"
#include "vstcal/core/error.h"

namespace vstcal {
namespace {

constexpr int kMaxWidth = 1280;

// 1, 2 or 5 × 10ᵏ at or below x > 0: a scale a reader can multiply by.
double RoundScale(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (const double m : {5.0, 2.0, 1.0}) {
    if (m * decade <= x) return m * decade;
  }
  return decade;
}

// The view's image, in grey (LoadImageFile: its header is checked before anything is
// decoded, so no file can make the report allocate more than a 100-megapixel image).
cv::Mat LoadBackground(const OverlayView& view, const ImageSize& size, const std::filesystem::path& dir) {
  const std::string& named = view.image;
  std::filesystem::path path = named;
  if (!std::filesystem::exists(path) && path.is_relative()) path = dir / named;
  const std::string& field = view.image_field;
  if (!std::filesystem::is_regular_file(path)) {
    throw InputError(field + "\"" + named + "\" not found (as given or beside the correspondences); run from the folder " +
                     "the path is relative to, or remove the field to draw on a blank canvas");
  }
  const LoadedImage loaded = LoadImageFile(path);
  if (!loaded.problem.empty()) throw InputError(field + path.string() + ": " + loaded.problem + "; give a PNG or JPEG");
  if (loaded.image.width != size.width || loaded.image.height != size.height) {
    throw InputError(field + path.string() + " is " + std::to_string(loaded.image.width) + "x" +
                     std::to_string(loaded.image.height) + " px but image_size is " + std::to_string(size.width) + "x" +
                     std::to_string(size.height) + "; give the image the corners were detected in");
  }
  const cv::Mat gray(loaded.image.height, loaded.image.width, CV_8UC1, const_cast<uint8_t*>(loaded.image.pixels.data()));
  cv::Mat colour;
  cv::cvtColor(gray, colour, cv::COLOR_GRAY2BGR);
  return colour;
}

}  // namespace

OverlayPicture DrawResidualOverlay(std::span<const OverlayView> all_views, const ImageSize& size,
                                   const std::optional<ErrorStats>& overall, const std::filesystem::path& dir) {
  std::vector<size_t> views;
  cv::Mat canvas;
  std::string on;
  for (size_t v = 0; v < all_views.size() && views.empty(); ++v) {
    if (!all_views[v].image.empty()) {
      canvas = LoadBackground(all_views[v], size, dir);
      views.push_back(v);
      on = "view " + all_views[v].name + " on its image " + all_views[v].image;
    }
  }
  if (views.empty()) {
    canvas = cv::Mat(size.height, size.width, CV_8UC3, cv::Scalar(255, 255, 255));
    for (size_t v = 0; v < all_views.size(); ++v) views.push_back(v);
    on = "all views on a blank canvas (the correspondences name no image)";
  }
  // Draw at a resolution the page shows: at most kMaxWidth wide.
  const double shrink = std::min(1.0, static_cast<double>(kMaxWidth) / size.width);
  if (shrink < 1.0) cv::resize(canvas, canvas, cv::Size(), shrink, shrink, cv::INTER_AREA);
  const double p95 = overall ? std::max(overall->p95, 1e-12) : 1.0;
  const double scale = ResidualVectorScale(size, overall);
  const int thickness = std::max(2, static_cast<int>(std::lround(std::max(canvas.cols, canvas.rows) / 600.0)));
  // Pixel centres are at integers with (0, 0) the top-left pixel's centre: OpenCV's drawing
  // convention too, so coordinates go in as they are (times the shrink, in 1/16 px).
  constexpr int kShift = 4;
  const auto at = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::lround((p.x() + 0.5) * shrink * 16 - 8)),
                     static_cast<int>(std::lround((p.y() + 0.5) * shrink * 16 - 8)));
  };
  size_t drawn = 0;
  for (const size_t v : views) {
    for (const PointError& e : all_views[v].points) {
      if (e.excluded != Exclusion::kNone) {
        cv::drawMarker(canvas, at(e.measured) / 16, cv::Scalar(128, 128, 128), cv::MARKER_TILTED_CROSS, 6 * thickness,
                       thickness);
        continue;
      }
      const double t = std::min(1.0, e.error_px / p95);
      const cv::Scalar colour(0, 200 * (1 - t), 255 * t);  // BGR: green to red
      const Eigen::Vector2d tip = e.measured + scale * (*e.predicted - e.measured);
      cv::line(canvas, at(e.measured), at(tip), colour, thickness, cv::LINE_AA, kShift);
      cv::circle(canvas, at(e.measured), thickness * 16, cv::Scalar(90, 60, 20), cv::FILLED, cv::LINE_AA, kShift);
      ++drawn;
    }
  }
  OverlayPicture picture;
  picture.png = PngBytes(canvas, "the residual overlay");
  char text[160];
  std::snprintf(text, sizeof text, "; %zu residuals drawn x%g (a %g px residual is %g px long), green 0 to red >= p95 %.3g px",
                drawn, scale, p95, p95 * scale, p95);
  picture.caption = on + text;
  return picture;
}

double ResidualVectorScale(const ImageSize& size, const std::optional<ErrorStats>& overall) {
  const double p95 = overall ? std::max(overall->p95, 1e-12) : 1.0;
  return RoundScale(0.02 * std::hypot(size.width, size.height) / p95);
}

OverlayPicture DrawResidualOverlay(const ReprojReport& report, size_t camera, const std::filesystem::path& dir) {
  VSTCAL_CHECK(camera < report.cameras.size(), "a camera of the report");
  const CameraReport& cam = report.cameras[camera];
  std::vector<OverlayView> views;
  for (size_t v = 0; v < report.correspondences.views.size(); ++v) {
    const View& view = report.correspondences.views[v];
    views.push_back({view.name, view.image, report.correspondences_file + ": views[" + std::to_string(v) + "].image: ",
                     cam.views[v].points});
  }
  return DrawResidualOverlay(views, report.correspondences.image_size, cam.overall.error_px, dir);
}

}  // namespace vstcal
