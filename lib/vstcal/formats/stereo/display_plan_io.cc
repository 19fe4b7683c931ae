#include "vstcal/formats/stereo/display_plan_io.h"

#include <cmath>

#include "vstcal/geometry/rotation.h"

namespace vstcal {
namespace {

OrderedJson Optional(const std::optional<double>& v) { return v ? OrderedJson(*v) : OrderedJson(nullptr); }

std::string_view SideName(int side) { return side < 0 ? "front" : side > 0 ? "behind" : "screen"; }

}  // namespace

OrderedJson DisplayPlanToJson(const DisplayPlanInput& in, const DisplayPlan& plan, LengthUnit unit,
                              const Provenance& provenance) {
  OrderedJson j;
  j["format"] = "vstcal/stereo-plan@1";
  j["length_unit"] = LengthUnitName(unit);
  OrderedJson input;
  input["baseline"] = in.baseline;
  input["z0"] = Optional(in.z0);
  input["display_width_px"] = in.display_width;
  input["focal_px"] = Optional(in.focal_px);
  input["hfov_deg"] = in.hfov_rad ? OrderedJson(RadToDeg(*in.hfov_rad)) : OrderedJson(nullptr);
  input["capture_width_px"] = in.capture_width ? OrderedJson(*in.capture_width) : OrderedJson(nullptr);
  input["viewer"] = ViewerName(in.viewer);
  input["ipd"] = in.viewer != Viewer::kNone ? OrderedJson(in.ipd) : OrderedJson(nullptr);
  input["screen_width"] = in.viewer == Viewer::kScreen ? OrderedJson(in.screen_width) : OrderedJson(nullptr);
  input["viewing_distance"] = in.viewer == Viewer::kScreen ? OrderedJson(in.viewing_distance) : OrderedJson(nullptr);
  j["input"] = std::move(input);
  j["focal_px"] = plan.focal_px;
  j["translation_px"] = plan.translation_px;
  j["capture_width_needed_px"] = plan.capture_width_needed;
  j["capture_margin_px"] = plan.capture_margin_px ? OrderedJson(*plan.capture_margin_px) : OrderedJson(nullptr);
  // Depth ranges: null ends are 0 (in front) and infinity (behind).
  j["in_front_of_screen"] = {{"from", 0.0}, {"to", Optional(in.z0)}};
  j["behind_screen"] = in.z0 ? OrderedJson{{"from", *in.z0}, {"to", Optional(plan.diverges_beyond)}} : OrderedJson(nullptr);
  j["diverges_beyond"] = Optional(plan.diverges_beyond);
  OrderedJson rows = OrderedJson::array();
  for (const DepthRow& r : plan.rows) {
    OrderedJson row;
    row["depth"] = r.depth;
    row["disparity_px"] = r.disparity_px;
    row["parallax_px"] = r.parallax_px;
    row["side"] = SideName(r.side);
    row["perceived_depth"] = Optional(r.perceived_depth);
    row["perceived_ratio"] = r.perceived_depth ? OrderedJson(*r.perceived_depth / r.depth) : OrderedJson(nullptr);
    rows.push_back(std::move(row));
  }
  j["depths"] = std::move(rows);
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

}  // namespace vstcal
