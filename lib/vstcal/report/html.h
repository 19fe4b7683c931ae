// The reproj-report HTML page: one self-contained file (styles inline, every picture a data: URI,
// a Content-Security-Policy that forbids any fetch), opening offline in any browser. Numbers are
// the JSON report's (io::ReprojReportToJson): each table cell carries the JSON pointer it shows
// and the value in the shortest round-trip decimal, data-key="/cameras/0/overall/error_px/rms"
// data-value="0.4184294160772006", so a test can read them back and compare with the JSON.
#pragma once

#include <filesystem>
#include <string>

#include "vstcal/report/reprojection_report.h"

namespace vstcal {

// Draws the charts with gnuplot (gnuplot.h) and the residual overlays with OpenCV (overlay.h);
// `correspondences_dir` resolves the views' image paths. Throws what those throw.
std::string ReprojReportHtml(const ReprojReport& report, const std::filesystem::path& correspondences_dir);

// RFC 4648 base64 (with padding), for data: URIs.
std::string Base64(const unsigned char* data, size_t size);
inline std::string Base64(const std::string& text) {
  return Base64(reinterpret_cast<const unsigned char*>(text.data()), text.size());
}

}  // namespace vstcal
