#include "vstcal/formats/camera/correspondences_io.h"

#include <set>

#include "vstcal/core/limits.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/format_check.h"

namespace vstcal {
namespace {

constexpr std::string_view kCorrespondencesFormat = "vstcal/correspondences@1";

std::string_view RigName(Rig rig) { return rig == Rig::kVolume ? "volume" : "planar-views"; }

// A detected pixel lies on the sensor: u ∈ [−0.5, W − 0.5], v ∈ [−0.5, H − 0.5].
void CheckInImage(const JsonNode& node, const Eigen::Vector2d& px, const ImageSize& s, std::string_view fix) {
  if (px.x() < -0.5 || px.y() < -0.5 || px.x() > s.width - 0.5 || px.y() > s.height - 0.5) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "pixel (%.6g, %.6g) lies outside the %d×%d image", px.x(), px.y(), s.width, s.height);
    node.Fail(buf, fix);
  }
}

Observation ReadPoint(const JsonNode& node, const Correspondences& c) {
  constexpr std::string_view kForm = "write each point as [X, Y, Z, u, v], or [X, Y, Z, u, v, weight]";
  if (!node.json().is_array()) node.Fail("expected [X, Y, Z, u, v], got a non-array", kForm);
  if (node.json().size() != 5 && node.json().size() != 6) {
    node.Fail("expected 5 numbers [X, Y, Z, u, v] or 6 with a weight, got " + std::to_string(node.json().size()), kForm);
  }
  Observation o;
  for (int i = 0; i < 3; ++i) o.point(i) = node.at(i).Number();
  for (int i = 0; i < 2; ++i) o.pixel(i) = node.at(3 + i).Number();
  if (node.json().size() == 6) {
    const JsonNode w = node.at(5);
    o.weight = w.Number();
    if (!(o.weight > 0)) {
      w.Fail("the weight must be positive, got " + w.json().dump(),
             "give a weight > 0 (the point's noise is sigma/sqrt(weight)), or remove the point");
    }
  }
  CheckInImage(node, o.pixel, c.image_size, "check image_size and that the columns are X, Y, Z, u, v");
  if (c.rig == Rig::kPlanarViews && o.point.z() != 0.0) {
    node.at(2).Fail("planar-views points lie on their board (Z = 0), got Z = " + node.at(2).json().dump(),
                    "use \"rig\": \"volume\" for 3-D points in one world frame");
  }
  return o;
}

}  // namespace

Correspondences CorrespondencesFromJson(const JsonDocument& doc) {
  const JsonNode root = doc.root();
  root.ExpectObject();
  CheckFormat(root, kCorrespondencesFormat);
  Correspondences c;
  if (auto camera = root.find("camera")) c.camera = camera->String();
  c.image_size = ReadImageSize(root.at("image_size"));
  c.length_unit = ReadLengthUnit(root.at("length_unit"));
  c.rig = root.at("rig").OneOf({"volume", "planar-views"}) == "volume" ? Rig::kVolume : Rig::kPlanarViews;

  const JsonNode views = root.at("views");
  const size_t n_views = views.ArraySize();
  if (n_views == 0) views.Fail("no views", "add at least one view with points");
  if (n_views > limits::kMaxViews) {
    views.Fail(std::to_string(n_views) + " views, more than the " + std::to_string(limits::kMaxViews) +
                   " vstcal calibrates from (docs/reliability.md#limits)",
               "keep a subset of the views");
  }
  size_t n_points = 0;
  std::set<std::string> names;
  for (size_t i = 0; i < n_views; ++i) {
    const JsonNode v = views.at(i);
    View view;
    view.name = v.at("name").String();
    if (view.name.empty()) v.at("name").Fail("empty view name", "give every view a unique name");
    if (!names.insert(view.name).second) v.at("name").Fail("duplicate view name \"" + view.name + "\"", "give every view a unique name");
    if (auto image = v.find("image")) view.image = image->String();
    if (auto offset = v.find("plane_offset")) view.plane_offset = offset->Number();
    if (auto time = v.find("time")) view.time = time->Number();
    const JsonNode points = v.at("points");
    const size_t n = points.ArraySize();
    if (n == 0) points.Fail("the view has no points", "remove the view or add its points");
    n_points += n;
    if (n_points > limits::kMaxPoints) {
      points.Fail("the views hold more than the " + std::to_string(limits::kMaxPoints) +
                      " points vstcal calibrates from (docs/reliability.md#limits)",
                  "decimate the points or keep a subset of the views");
    }
    view.observations.reserve(n);
    for (size_t k = 0; k < n; ++k) view.observations.push_back(ReadPoint(points.at(k), c));
    c.views.push_back(std::move(view));
  }

  if (auto tests = root.find("test_points")) {
    const size_t n = tests->ArraySize();
    std::set<std::string> test_names;
    for (size_t i = 0; i < n; ++i) {
      const JsonNode t = tests->at(i);
      TestPoint tp;
      tp.name = t.at("name").String();
      if (!test_names.insert(tp.name).second) t.at("name").Fail("duplicate test point name \"" + tp.name + "\"", "give every test point a unique name");
      tp.point_in_world = t.at("world").Vector<3>();
      if (auto px = t.find("pixel")) {
        tp.pixel = px->Vector<2>();
        CheckInImage(*px, *tp.pixel, c.image_size, "check image_size, or omit \"pixel\" if the point was not seen");
      }
      c.test_points.push_back(std::move(tp));
    }
  }
  return c;
}

Correspondences ReadCorrespondences(const std::filesystem::path& path) {
  return CorrespondencesFromJson(JsonDocument::Load(path));
}

OrderedJson CorrespondencesToJson(const Correspondences& c, const Provenance& provenance) {
  OrderedJson j;
  j["format"] = kCorrespondencesFormat;
  if (!c.camera.empty()) j["camera"] = c.camera;
  j["image_size"] = {c.image_size.width, c.image_size.height};
  j["length_unit"] = LengthUnitName(c.length_unit);
  j["rig"] = RigName(c.rig);
  OrderedJson views = OrderedJson::array();
  for (const View& v : c.views) {
    OrderedJson jv;
    jv["name"] = v.name;
    if (!v.image.empty()) jv["image"] = v.image;
    if (v.plane_offset) jv["plane_offset"] = *v.plane_offset;
    if (v.time) jv["time"] = *v.time;
    OrderedJson points = OrderedJson::array();
    for (const Observation& o : v.observations) {
      OrderedJson p = {o.point.x(), o.point.y(), o.point.z(), o.pixel.x(), o.pixel.y()};
      if (o.weight != 1.0) p.push_back(o.weight);  // a weight of 1 is the default: not written
      points.push_back(std::move(p));
    }
    jv["points"] = std::move(points);
    views.push_back(std::move(jv));
  }
  j["views"] = std::move(views);
  if (!c.test_points.empty()) {
    OrderedJson tests = OrderedJson::array();
    for (const TestPoint& t : c.test_points) {
      OrderedJson jt;
      jt["name"] = t.name;
      jt["world"] = MatrixToJson(t.point_in_world);
      if (t.pixel) jt["pixel"] = MatrixToJson(*t.pixel);
      tests.push_back(std::move(jt));
    }
    j["test_points"] = std::move(tests);
  }
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

}  // namespace vstcal
