// The residual-vector overlay (issue 13 item 4): every measured corner of one or more views drawn
// on the view's image (when the correspondences name one) or on a blank canvas of the image's
// size, with its residual r = predicted − measured as a line scaled to be seen. Drawn with OpenCV.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vstcal/report/reprojection_report.h"

namespace vstcal {

struct OverlayPicture {
  std::vector<unsigned char> png;  // at most 1280 px wide
  std::string caption;             // what is drawn, on what, and the vectors' scale
};

// One view to draw: its points' residuals (PointError's measured, predicted, error_px and
// excluded), its name and image as its correspondences give them, and that field for messages
// ("l.json: views[3].image: ").
struct OverlayView {
  std::string name, image, image_field;
  std::span<const PointError> points;
};

// On the image of the first of `views` that names one (its points only, the image in grey),
// resolved as given or else relative to `correspondences_dir`; without images, all views on a blank
// canvas of `size`. Vectors are drawn ×scale with scale = 2 % of the image diagonal over the p95 of
// `overall` (rounded to 1, 2 or 5 × 10ᵏ), coloured green (|r| = 0) to red (|r| ≥ p95). Throws
// InputError naming the image field when a named image cannot be read or has another size.
OverlayPicture DrawResidualOverlay(std::span<const OverlayView> views, const ImageSize& size,
                                   const std::optional<ErrorStats>& overall, const std::filesystem::path& correspondences_dir);

// The vectors' magnification above: 2 % of the image diagonal over the p95 of `overall`, rounded down
// to 1, 2 or 5 × 10ᵏ (the per-view plots of the page use the same, so that they compare).
double ResidualVectorScale(const ImageSize& size, const std::optional<ErrorStats>& overall);

// Camera `camera` of `report`, every view of its correspondences as above.
OverlayPicture DrawResidualOverlay(const ReprojReport& report, size_t camera, const std::filesystem::path& correspondences_dir);

}  // namespace vstcal
