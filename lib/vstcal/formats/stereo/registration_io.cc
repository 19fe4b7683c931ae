#include "vstcal/formats/stereo/registration_io.h"

#include <set>

#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/camera/residual_stats_json.h"
#include "vstcal/json/format_check.h"

namespace vstcal {
namespace {

constexpr std::string_view kTracksFormat = "vstcal/tracks@1";
constexpr std::string_view kRegistrationFormat = "vstcal/registration@1";

std::vector<NamedPoint> ReadPoints(const JsonNode& node, std::string_view what) {
  std::vector<NamedPoint> points;
  std::set<std::string> names;
  for (size_t i = 0; i < node.ArraySize(); ++i) {
    const JsonNode p = node.at(i);
    const JsonNode name = p.at("name");
    NamedPoint point{name.String(), p.at("world").Vector<3>()};
    if (point.name.empty()) name.Fail("empty name", "give every " + std::string(what) + " a unique name");
    if (!names.insert(point.name).second) {
      name.Fail("duplicate name \"" + point.name + "\"", "give every " + std::string(what) + " a unique name");
    }
    points.push_back(std::move(point));
  }
  return points;
}

std::vector<std::optional<Eigen::Vector2d>> ReadPixels(const JsonNode& node, size_t count, const ImageSize& size) {
  if (node.ArraySize() != count) {
    node.Fail("has " + std::to_string(node.ArraySize()) + " entries for " + std::to_string(count) + " embedded points",
              "give one [u, v] (or null when not tracked) per embedded point, in their order");
  }
  std::vector<std::optional<Eigen::Vector2d>> pixels;
  for (size_t i = 0; i < count; ++i) {
    const JsonNode p = node.at(i);
    if (p.json().is_null()) {
      pixels.emplace_back();
      continue;
    }
    const Eigen::Vector2d px = p.Vector<2>();
    if (px.x() < -0.5 || px.y() < -0.5 || px.x() > size.width - 0.5 || px.y() > size.height - 0.5) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "pixel (%.6g, %.6g) lies outside the %d×%d image", px.x(), px.y(), size.width, size.height);
      p.Fail(buf, "check image_size, or write null for a point the tracker lost");
    }
    pixels.emplace_back(px);
  }
  return pixels;
}

OrderedJson PointsToJson(const std::vector<NamedPoint>& points) {
  OrderedJson a = OrderedJson::array();
  for (const NamedPoint& p : points) a.push_back({{"name", p.name}, {"world", MatrixToJson(p.point_in_world)}});
  return a;
}

OrderedJson PixelsToJson(const std::vector<std::optional<Eigen::Vector2d>>& pixels) {
  OrderedJson a = OrderedJson::array();
  for (const auto& p : pixels) a.push_back(p ? MatrixToJson(*p) : OrderedJson(nullptr));
  return a;
}

OrderedJson OptionalStats(const std::optional<ResidualStats>& s) {
  return s ? ResidualStatsToJson(*s, "_px", "n") : OrderedJson(nullptr);
}

OrderedJson AccuracyToJson(const std::optional<FrameAccuracy>& a) {
  if (!a) return nullptr;
  OrderedJson j;
  const char* eyes[2] = {"left", "right"};
  for (int e = 0; e < 2; ++e) {
    j[eyes[e]] = {{"rotation_deg", a->rotation_deg[e]},
                  {"centre_error", a->centre_error[e]},
                  {"virtual_rms_px", a->virtual_px[e].rms_px},
                  {"virtual_max_px", a->virtual_px[e].max_px}};
  }
  return j;
}

OrderedJson SequenceAccuracyToJson(const std::optional<SequenceAccuracy>& s) {
  if (!s) return nullptr;
  OrderedJson j;
  j["frames"] = s->frames;
  const char* eyes[2] = {"left", "right"};
  for (int e = 0; e < 2; ++e) {
    j[eyes[e]] = {{"rotation_deg", ResidualStatsToJson(s->rotation_deg[e], "", "n")},
                  {"centre_error", ResidualStatsToJson(s->centre_error[e], "", "n")},
                  {"virtual_px", ResidualStatsToJson(s->virtual_px[e], "", "n")}};
  }
  return j;
}

}  // namespace

Tracks TracksFromJson(const JsonDocument& doc) {
  const JsonNode root = doc.root();
  root.ExpectObject();
  CheckFormat(root, kTracksFormat);
  Tracks t;
  t.length_unit = ReadLengthUnit(root.at("length_unit"));
  const JsonNode sizes = root.at("image_size");
  sizes.ExpectObject();
  t.left_image_size = ReadImageSize(sizes.at("left"));
  if (const auto right = sizes.find("right")) t.right_image_size = ReadImageSize(*right);
  const JsonNode embedded = root.at("embedded_points");
  t.embedded = ReadPoints(embedded, "embedded point");
  if (t.embedded.size() < kMinPnpPoints) {
    embedded.Fail(std::to_string(t.embedded.size()) + " points; a camera's pose needs at least 4",
                  "embed at least 4 points, not all on one line");
  }
  if (const auto v = root.find("virtual_points")) t.virtual_points = ReadPoints(*v, "virtual point");
  const JsonNode frames = root.at("frames");
  if (frames.ArraySize() == 0) frames.Fail("no frames", "add at least one frame of tracked pixels");
  std::set<std::string> names;
  for (size_t i = 0; i < frames.ArraySize(); ++i) {
    const JsonNode f = frames.at(i);
    TrackedFrame frame;
    const JsonNode name = f.at("name");
    frame.name = name.String();
    if (frame.name.empty()) name.Fail("empty frame name", "give every frame a unique name");
    if (!names.insert(frame.name).second) {
      name.Fail("duplicate frame name \"" + frame.name + "\"", "give every frame a unique name");
    }
    frame.left = ReadPixels(f.at("left"), t.embedded.size(), t.left_image_size);
    if (const auto right = f.find("right")) {
      if (!t.right_image_size) {
        right->Fail("right pixels, but image_size has no \"right\"", "add image_size.right: [width, height]");
      }
      frame.right = ReadPixels(*right, t.embedded.size(), *t.right_image_size);
    }
    if (const auto truth = f.find("truth")) frame.truth_left_from_world = ReadRigid(truth->at("left_from_world"));
    t.frames.push_back(std::move(frame));
  }
  return t;
}

Tracks ReadTracks(const std::filesystem::path& path) { return TracksFromJson(JsonDocument::Load(path)); }

OrderedJson TracksToJson(const Tracks& t, const Provenance& provenance) {
  OrderedJson j;
  j["format"] = kTracksFormat;
  j["length_unit"] = LengthUnitName(t.length_unit);
  j["image_size"]["left"] = {t.left_image_size.width, t.left_image_size.height};
  if (t.right_image_size) j["image_size"]["right"] = {t.right_image_size->width, t.right_image_size->height};
  j["embedded_points"] = PointsToJson(t.embedded);
  j["virtual_points"] = PointsToJson(t.virtual_points);
  OrderedJson frames = OrderedJson::array();
  for (const TrackedFrame& f : t.frames) {
    OrderedJson jf;
    jf["name"] = f.name;
    jf["left"] = PixelsToJson(f.left);
    if (!f.right.empty()) jf["right"] = PixelsToJson(f.right);
    if (f.truth_left_from_world) jf["truth"] = {{"left_from_world", RigidToJson(*f.truth_left_from_world)}};
    frames.push_back(std::move(jf));
  }
  j["frames"] = std::move(frames);
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

OrderedJson RegistrationToJson(const RegistrationRun& run, const StereoRig& rig, const Tracks& tracks,
                               const std::vector<FrameRegistration>& frames, const Provenance& provenance) {
  OrderedJson j;
  j["format"] = kRegistrationFormat;
  j["rig"] = run.rig;
  j["tracks"] = run.tracks;
  j["mode"] = RegistrationModeName(run.options.mode);
  j["start"] = run.options.warm_start ? "previous-frame" : "closed-form";
  j["length_unit"] = LengthUnitName(rig.length_unit);
  j["virtual_points"] = PointsToJson(tracks.virtual_points);
  OrderedJson out = OrderedJson::array();
  OrderedJson excluded = OrderedJson::array();
  std::vector<std::optional<FrameAccuracy>> accuracy;
  std::vector<Eigen::Vector2d> left_residual_rms, right_residual_rms;
  for (size_t i = 0; i < frames.size(); ++i) {
    const FrameRegistration& f = frames[i];
    OrderedJson jf;
    jf["name"] = tracks.frames[i].name;
    if (f.status != PoseStatus::kOk) {
      jf["status"] = "excluded";
      jf["reason"] = f.failed_eye + " eye: " + std::string(PoseStatusText(f.status));
      excluded.push_back(tracks.frames[i].name);
      out.push_back(std::move(jf));
      continue;
    }
    jf["status"] = "registered";
    jf["left_from_world"] = RigidToJson(f.left_from_world);
    jf["right_from_world"] = RigidToJson(f.right_from_world);
    jf["iterations"] = f.iterations;
    jf["fit"] = {{"left", OptionalStats(f.left_fit)}, {"right", OptionalStats(f.right_fit)}};
    jf["virtual"] = {{"left", PixelsToJson(f.virtual_left)}, {"right", PixelsToJson(f.virtual_right)}};
    accuracy.push_back(AccuracyOf(rig, tracks.frames[i], f, tracks.virtual_points));
    jf["accuracy"] = AccuracyToJson(accuracy.back());
    out.push_back(std::move(jf));
  }
  j["frames"] = std::move(out);
  j["summary"] = {{"frames", frames.size()},
                  {"registered", frames.size() - excluded.size()},
                  {"excluded", std::move(excluded)},
                  {"accuracy", SequenceAccuracyToJson(SummarizeAccuracy(accuracy))}};
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

}  // namespace vstcal
