// The vstcal/reproj-report@1 file (docs/formats.md#reproj-report), its terminal table, and the
// camera files reproj-report reads: the one home of the report's formats.
#pragma once

#include <filesystem>
#include <string>

#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"
#include "vstcal/report/reprojection_report.h"
#include "vstcal/report/stereo_report.h"

namespace vstcal {

// A vstcal/camera@1 file with σ̂ (refinement.sigma_px, else dlt.uncertainty.sigma_px, when present
// and positive) beside it.
ReportCamera ReadReportCamera(const std::filesystem::path& path);
// The same from a camera@1 document already in memory (a camera just solved), named `name`.
ReportCamera ReportCameraFrom(const JsonDocument& doc, const std::string& name);

OrderedJson ReprojReportToJson(const ReprojReport& report, const Provenance& provenance);

// The report as a table for a terminal: one block per camera (overall, per view, test points
// inside and outside the volume, normalized residuals) and the differences between cameras.
std::string ReprojReportText(const ReprojReport& report);

// A stereo rig's report: the same format, with a "stereo" block in place of "cameras"
// (docs/formats.md#reproj-report-stereo), and its table.
OrderedJson StereoReportToJson(const StereoReport& report, const Provenance& provenance);
std::string StereoReportText(const StereoReport& report);

}  // namespace vstcal
