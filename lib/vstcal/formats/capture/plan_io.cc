#include "vstcal/formats/capture/plan_io.h"

#include <cmath>
#include <cstdio>

#include "vstcal/formats/camera/camera_io.h"

namespace vstcal {
namespace {

OrderedJson PositionToJson(const PositionPlan& p) {
  OrderedJson j;
  j["name"] = p.name;
  if (p.plane_offset) j["plane_offset"] = *p.plane_offset;
  j["camera_from_board"] = RigidToJson(p.camera_from_board);
  j["coverage"] = p.coverage;
  j["region_coverage"] = MatrixToJson(p.region_coverage);
  j["smallest_square_px"] = p.smallest_square_px;
  j["corners"] = p.corners;
  j["corners_outside"] = p.corners_outside;
  // Behind the camera has no pixel distance: null.
  j["outside_px"] = NumberOrNull(p.outside_px);
  j["obliquity_deg"] = p.obliquity_deg;
  j["depth_range"] = {p.depth_min, p.depth_max};
  j["used"] = p.used;
  j["warnings"] = p.warnings;
  return j;
}

}  // namespace

OrderedJson CapturePlanToJson(const CapturePlan& plan, const Provenance& provenance) {
  const PlanRequest& r = plan.request;
  OrderedJson j;
  j["format"] = "vstcal/capture-plan@1";
  j["provenance"] = ProvenanceToJson(provenance);
  j["rig"] = r.rig == Rig::kVolume ? "volume" : "planar-views";
  j["length_unit"] = LengthUnitName(r.target.length_unit);
  j["target"] = DescribeTarget(r.target);
  j["image_size"] = {r.camera.image_size.width, r.camera.image_size.height};
  j["K"] = MatrixToJson(r.camera.K());
  j["distortion"] = DistortionToJson(r.camera);
  if (r.rig == Rig::kVolume) j["camera_from_world"] = RigidToJson(plan.camera_from_world);
  OrderedJson positions = OrderedJson::array();
  for (const PositionPlan& p : plan.positions) positions.push_back(PositionToJson(p));
  j["positions"] = std::move(positions);
  OrderedJson prediction;
  prediction["method"] = r.method;
  prediction["pixel_sigma"] = r.pixel_sigma;
  prediction["used_corners"] = plan.used_corners;
  prediction["observable"] = plan.prediction.observable;
  if (!plan.prediction.observable) prediction["message"] = plan.prediction.message;
  prediction["smallest_scaled_eigenvalue"] = plan.prediction.smallest_scaled_eigenvalue;
  OrderedJson sigmas = OrderedJson::array();
  for (const ParameterSigma& s : plan.sigmas) sigmas.push_back({{"name", s.name}, {"value", s.value}, {"sigma", s.sigma}});
  prediction["parameters"] = std::move(sigmas);
  OrderedJson points = OrderedJson::array();
  for (const PointUncertainty& u : plan.points) {
    OrderedJson q;
    q["name"] = u.name;
    if (u.point_in_world) q["point_in_world"] = MatrixToJson(*u.point_in_world);
    if (u.pixel_depth) q["pixel_depth"] = MatrixToJson(*u.pixel_depth);
    q["with_poses_px"] = u.with_poses_px;
    q["intrinsics_only_px"] = u.intrinsics_only_px;
    points.push_back(std::move(q));
  }
  prediction["test_points"] = std::move(points);
  j["prediction"] = std::move(prediction);
  j["warnings"] = plan.warnings;
  return j;
}

std::string CapturePlanText(const CapturePlan& plan) {
  std::string text;
  char buf[400];
  std::snprintf(buf, sizeof buf, "%zu positions of a %s; prediction at σ = %.3g px (%s, %d corners)\n", plan.positions.size(),
                DescribeTarget(plan.request.target).c_str(), plan.request.pixel_sigma, plan.request.method.c_str(), plan.used_corners);
  text += buf;
  text += "  position        coverage  smallest square  outside  obliquity\n";
  for (const PositionPlan& p : plan.positions) {
    std::snprintf(buf, sizeof buf, "  %-14s  %7.1f%%  %12.1f px  %3d/%-3d  %7.1f°\n", p.name.c_str(), 100 * p.coverage,
                  p.smallest_square_px, p.corners_outside, p.corners, p.obliquity_deg);
    text += buf;
    for (const std::string& w : p.warnings) text += "    warning: " + w + "\n";
  }
  if (!plan.sigmas.empty()) text += "  parameter  value  1-σ\n";
  for (const ParameterSigma& s : plan.sigmas) {
    std::snprintf(buf, sizeof buf, "  %-6s %12.6g %10.4g\n", s.name.c_str(), s.value, s.sigma);
    text += buf;
  }
  if (!plan.points.empty()) text += "  projection 1-σ (major axis): with poses / intrinsics only\n";
  for (const PointUncertainty& u : plan.points) {
    std::snprintf(buf, sizeof buf, "  %-24s %8.4f px %8.4f px\n", u.name.c_str(), u.with_poses_px, u.intrinsics_only_px);
    text += buf;
  }
  for (const std::string& w : plan.warnings) text += "  warning: " + w + "\n";
  return text;
}

}  // namespace vstcal
