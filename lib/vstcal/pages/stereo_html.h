// The page of a stereo rig's report (reproj-report RIG LEFT RIGHT --html; html_page.h:
// self-contained, opens offline): the per-axis error and Holloway's terms overall, the per-axis
// error against depth (seed 000 Figs. 9–10) drawn by gnuplot, each camera's heat map and residual
// vectors through the rig, and per view both cameras' reprojection RMS and the triangulated
// error. Numbers are the JSON report's (StereoReportToJson), each cell carrying its JSON pointer, e.g.
// data-key="/stereo/overall/z/rms".
#pragma once

#include <filesystem>
#include <string>

#include "vstcal/report/stereo_report.h"

namespace vstcal {

// Draws the charts with gnuplot and each camera's residual overlay with OpenCV (overlay.h);
// `left_dir` and `right_dir` resolve the two correspondences files' image paths. Throws what those throw.
std::string StereoReportHtml(const StereoReport& report, const std::filesystem::path& left_dir,
                             const std::filesystem::path& right_dir);

// The chart: |Δx|, |Δy|, |Δz| (length unit) against the known point's depth z in the left frame,
// every measured point (at most kMaxScatterPoints, an even stride). Empty when no point is measured.
std::string StereoDepthScript(const StereoReport& report);

}  // namespace vstcal
