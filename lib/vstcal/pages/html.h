// The reproj-report HTML page (html_page.h: self-contained, opens offline). Numbers are the JSON
// report's (ReprojReportToJson), each cell carrying its JSON pointer, e.g.
// data-key="/cameras/0/overall/error_px/rms" data-value="0.4184294160772006".
#pragma once

#include <filesystem>
#include <string>

#include "vstcal/report/reprojection_report.h"

namespace vstcal {

// Draws the charts with gnuplot (gnuplot.h) and the residual overlays with OpenCV (overlay.h);
// `correspondences_dir` resolves the views' image paths. Throws what those throw.
std::string ReprojReportHtml(const ReprojReport& report, const std::filesystem::path& correspondences_dir);

}  // namespace vstcal
