// The residual-vector overlay (issue 13 item 4): every measured corner of one or more views drawn
// on the view's image (when the correspondences name one) or on a blank canvas of the image's
// size, with its residual r = predicted − measured as a line scaled to be seen. Drawn with OpenCV.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "vstcal/report/reprojection_report.h"

namespace vstcal {

struct OverlayPicture {
  std::vector<unsigned char> png;  // at most 1280 px wide
  std::string caption;             // what is drawn, on what, and the vectors' scale
};

// Camera `camera` of `report`: on the image of the first view that names one (its points only, the
// image in grey),
// resolved as given or else relative to `correspondences_dir`; without images, all views on a
// blank canvas. Vectors are drawn ×scale with scale = 2 % of the image diagonal over the p95 |r|
// (rounded to 1, 2 or 5 × 10ᵏ), coloured green (|r| = 0) to red (|r| ≥ p95). Throws InputError
// naming the correspondences' field when a named image cannot be read or has another size.
OverlayPicture DrawResidualOverlay(const ReprojReport& report, size_t camera, const std::filesystem::path& correspondences_dir);

}  // namespace vstcal
