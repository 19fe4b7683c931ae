// The report's charts as gnuplot scripts (drawn by RunGnuplot, gnuplot.h, into SVG): every number
// is computed here in C++ and handed to gnuplot as an inline data block, so gnuplot only draws.
#pragma once

#include <string>

#include "vstcal/report/reprojection_report.h"

namespace vstcal {

// |r| histograms of every camera, as steps over one set of bins (0 to the largest p99-ish max).
std::string HistogramScript(const ReprojReport& report);
// RMS |r| per view, clustered bars, one colour per camera.
std::string PerViewScript(const ReprojReport& report);
// |r| (px) and lateral error (length unit) against the point's distance from the camera, every
// camera; at most kMaxScatterPoints points per camera (an even stride through the points).
std::string DepthScript(const ReprojReport& report);
// A value per grid cell (row-major; nullopt drawn blank) as a heat map over the image, the colour
// bar labelled `label`: a camera's mean |r| per cell, its projection uncertainty.
std::string HeatMapScript(const ImageGrid& grid, const std::vector<std::optional<double>>& cells, const std::string& label);
// Each test point's |r| and lateral error, inside vs outside the measured volume, every camera.
// Empty when there are no measured test points.
std::string TestPointsScript(const ReprojReport& report);

inline constexpr size_t kMaxScatterPoints = 20000;

}  // namespace vstcal
