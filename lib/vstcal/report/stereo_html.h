// The page of a stereo rig's report (reproj-report RIG LEFT RIGHT --html; html_page.h:
// self-contained, opens offline): the per-axis error and Holloway's terms overall and per view,
// and the per-axis error against depth (seed 000 Figs. 9–10) drawn by gnuplot. Numbers are the
// JSON report's (io::StereoReportToJson), each cell carrying its JSON pointer, e.g.
// data-key="/stereo/overall/z/rms".
#pragma once

#include <string>

#include "vstcal/report/stereo_report.h"

namespace vstcal {

// Throws what RunGnuplot throws.
std::string StereoReportHtml(const StereoReport& report);

// The chart: |Δx|, |Δy|, |Δz| (length unit) against the known point's depth z in the left frame,
// every measured point (at most kMaxScatterPoints, an even stride). Empty when no point is measured.
std::string StereoDepthScript(const StereoReport& report);

}  // namespace vstcal
