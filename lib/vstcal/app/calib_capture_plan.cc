// calib-capture plan as a library call (commands.h).
#include <cmath>

#include "vstcal/app/calib_capture.h"
#include "vstcal/formats/capture/plan_compare.h"
#include "vstcal/formats/capture/plan_io.h"
#include "vstcal/formats/capture/target_io.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/core/option_name.h"

namespace vstcal::app {
namespace {

Camera PlanCamera(PlanCommand& command) {
  if (!command.camera_file.empty()) return ReadCamera(command.camera_file).camera;
  SyntheticCameraSpec& spec = command.nominal;
  if (command.focal_mm || command.pixel_pitch_um) {
    if (!(command.focal_mm && command.pixel_pitch_um)) {
      throw InputError(VSTCAL_OPT("focal_mm") ": give it with " VSTCAL_OPT("pixel_pitch_um") " (the sensor's pixel size), or give " VSTCAL_OPT("fx") " in px");
    }
    if (spec.fx || spec.hfov_deg) throw InputError(VSTCAL_OPT("focal_mm") ": give one of " VSTCAL_OPT("fx") ", " VSTCAL_OPT("hfov_deg") " and " VSTCAL_OPT("focal_mm"));
    if (!(*command.focal_mm > 0 && *command.pixel_pitch_um > 0)) {
      throw InputError(VSTCAL_OPT("focal_mm") ", " VSTCAL_OPT("pixel_pitch_um") ": must be positive (mm, µm)");
    }
    spec.fx = *command.focal_mm * 1000 / *command.pixel_pitch_um;
  }
  if (!spec.fx && !spec.hfov_deg) {
    throw InputError(VSTCAL_OPT("camera") ": give a camera@1 file, or the nominal focal length (" VSTCAL_OPT("fx") ", " VSTCAL_OPT("hfov_deg") " or " VSTCAL_OPT("focal_mm") " with "
                     VSTCAL_OPT("pixel_pitch_um") ") and " VSTCAL_OPT("image_size"));
  }
  return MakeSyntheticCamera(spec);
}

}  // namespace

Outcome RunPlan(PlanCommand command, const Provenance& provenance) {
  Outcome out;
  if (!command.compare.empty()) {
    const PlanPrediction a = ReadPlanPrediction(command.compare.at(0)), b = ReadPlanPrediction(command.compare.at(1));
    const std::string text = ComparePlansText(a, b);
    out.files.emplace_back(command.output, command.text ? text : DumpJson(ComparePlansToJson(a, b, provenance)));
    out.summary = "calib-capture plan " VSTCAL_OPT("compare") ": " + text + "wrote " + command.output;
    return out;
  }
  PlanRequest& r = command.request;
  r.target = ReadTarget(command.target_file);
  r.camera = PlanCamera(command);
  if (command.default_test_points && r.rig == Rig::kVolume) {
    // Seed000TestPoints measures from the corners' extent (half widths of a grid of spacings):
    // a 2 × 2 grid of the extent's width, its Y coordinates rescaled to the extent's height.
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (const TargetCorner& c : TargetCorners(r.target)) {
      lo = lo.cwiseMin(c.xy);
      hi = hi.cwiseMax(c.xy);
    }
    VolumeSpec spec = r.volume;
    spec.grid_cols = 2;
    spec.grid_rows = 2;
    spec.spacing = hi.x() - lo.x();
    spec.length_unit = r.target.length_unit;
    std::vector<TestPoint> points = Seed000TestPoints(spec);
    for (TestPoint& t : points) t.point_in_world.y() *= (hi.y() - lo.y()) / spec.spacing;
    r.test_points = std::move(points);
  }
  CapturePlan plan = PlanCapture(r);
  const std::string text = CapturePlanText(plan);
  out.files.emplace_back(command.output, command.text ? text : DumpJson(CapturePlanToJson(plan, provenance)));
  out.summary = "calib-capture plan: " + text + "wrote " + command.output;
  return out;
}

}  // namespace vstcal::app
