// reproj-report as a library call (docs/tools/reproj-report.md): one or more cameras against a
// correspondences file, or a stereo rig against its two cameras' correspondences.
#pragma once

#include <string>
#include <vector>

#include "vstcal/app/outcome.h"
#include "vstcal/json/provenance.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal::app {

struct ReprojReportRequest {
  // camera@1 files then the correspondences@1 file; or a stereo@1 rig, then LEFT and RIGHT.
  std::vector<std::string> inputs;
  std::string output;       // reproj-report@1
  std::string html;         // empty: no page
  std::string match_views;  // a rig's view-matching expression; empty: by name
  int grid_cols = 8, grid_rows = 6;
  bool text = false;  // the report's text table for stdout
};

// A rig's report when the first input is a stereo@1 file, else the cameras' report; the summary
// has a note for each kind of point the statistics leave out (how many and why).
Outcome RunReprojReport(const ReprojReportRequest& request, const Provenance& provenance);

// True when the request's first input is a stereo rig (then match_views applies).
bool IsRigRequest(const ReprojReportRequest& request);

// reproj-report's page for a camera just solved, before any file is written (calib-tsai and
// calib-dlt --html): the camera as its file will hold it (camera@1 text, named `camera_file`)
// against the correspondences it was solved from (named `corners_name`; the views' relative image
// paths are tried as given, then against `images_folder`). The default grid, as reproj-report's.
std::string ReprojReportPageOf(const std::string& camera_file, const std::string& camera_json, const Correspondences& corners,
                               const std::string& corners_name, const std::string& images_folder);

}  // namespace vstcal::app
