// Residual vectors on every view (issue 24 item 3): small multiples, one inline SVG per view, the
// views in the order of the page's views table (the largest RMS first), each plot the image's frame
// with every measured corner as a dot and its residual r = predicted − measured as a line, magnified
// as the camera's overlay (ResidualVectorScale) so that the plots compare. Vector art, no pixels:
// a plot costs some 40 bytes a point. The page stays bounded: at most kMaxViewPlots views a camera
// and kMaxPointsPerView points a view (every k-th point beyond that), each cut said in the caption.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "vstcal/report/reprojection_report.h"

namespace vstcal {

inline constexpr size_t kMaxViewPlots = 48;
inline constexpr size_t kMaxPointsPerView = 250;

// The indices of cam.views, the largest RMS |residual| first (views without a measured point
// last), ties in file order.
std::vector<size_t> WorstViewsFirst(const CameraReport& cam);

// The <section> of camera `camera`'s per-view plots: a figure class="view-residuals" per view with
// data-view (its name) and data-drawn (the vectors drawn), its SVG's paths class "vectors" (one
// per colour band) and "points".
std::string ViewResidualPlots(const ReprojReport& report, size_t camera);

}  // namespace vstcal
