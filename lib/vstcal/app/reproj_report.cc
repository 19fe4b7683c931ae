#include "vstcal/app/reproj_report.h"

#include <filesystem>

#include "vstcal/core/error.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/report/report_format.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/pages/html.h"
#include "vstcal/pages/stereo_html.h"

namespace vstcal::app {
namespace {

std::filesystem::path FolderOf(const std::string& file) { return std::filesystem::path(file).parent_path(); }

Outcome RigReport(const ReprojReportRequest& r, const JsonDocument& rig, const Provenance& provenance) {
  if (r.inputs.size() != 3) {
    throw InputError(r.inputs.front() + ": a stereo rig takes two correspondences files after it, LEFT then RIGHT; got " +
                     std::to_string(r.inputs.size() - 1));
  }
  const StereoReport report =
      BuildStereoReport(StereoRigFromJson(rig), ReadCorrespondences(r.inputs[1]), ReadCorrespondences(r.inputs[2]),
                        r.inputs[0], r.inputs[1], r.inputs[2], {r.match_views, r.grid_cols, r.grid_rows});
  Outcome outcome;
  outcome.files = {{r.output, DumpJson(StereoReportToJson(report, provenance))}};
  if (!r.html.empty()) {
    outcome.files.emplace_back(r.html, StereoReportHtml(report, FolderOf(r.inputs[1]), FolderOf(r.inputs[2])));
  }
  if (r.text) outcome.stdout_text = StereoReportText(report);
  for (const std::string& note : ExclusionNotes(report)) outcome.summary += "reproj-report: note: " + note + "\n";
  return outcome;
}

}  // namespace

bool IsRigRequest(const ReprojReportRequest& request) {
  return IsStereoRigDocument(JsonDocument::Load(request.inputs.front()));
}

Outcome RunReprojReport(const ReprojReportRequest& r, const Provenance& provenance) {
  const JsonDocument first = JsonDocument::Load(r.inputs.front());
  if (IsStereoRigDocument(first)) return RigReport(r, first, provenance);
  const std::string& corr_file = r.inputs.back();
  std::vector<ReportCamera> cameras;
  for (size_t i = 0; i + 1 < r.inputs.size(); ++i) cameras.push_back(ReadReportCamera(r.inputs[i]));
  ReprojReportOptions options;
  options.grid_cols = r.grid_cols;
  options.grid_rows = r.grid_rows;
  const ReprojReport report = BuildReprojReport(cameras, ReadCorrespondences(corr_file), corr_file, options);
  Outcome outcome;
  outcome.files = {{r.output, DumpJson(ReprojReportToJson(report, provenance))}};
  if (!r.html.empty()) outcome.files.emplace_back(r.html, ReprojReportHtml(report, FolderOf(corr_file)));
  if (r.text) outcome.stdout_text = ReprojReportText(report);
  for (const std::string& note : ExclusionNotes(report)) outcome.summary += "reproj-report: note: " + note + "\n";
  return outcome;
}

std::string ReprojReportPageOf(const std::string& camera_file, const std::string& camera_json, const Correspondences& corners,
                               const std::string& corners_name, const std::string& images_folder) {
  const std::vector<ReportCamera> cameras = {ReportCameraFrom(JsonDocument::Parse(camera_json, camera_file), camera_file)};
  const ReprojReport report = BuildReprojReport(cameras, corners, corners_name, ReprojReportOptions{});
  return ReprojReportHtml(report, images_folder);
}

}  // namespace vstcal::app
