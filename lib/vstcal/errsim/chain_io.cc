#include "vstcal/errsim/chain_io.h"

#include <cmath>
#include <set>

#include "vstcal/io/camera_io.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/format_check.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/errsim/source_io.h"

namespace vstcal::errsim {
namespace {

using io::JsonNode;
using io::ExpectKeys;

// {"R", "t"} or {"rotvec_deg", "t"} (docs/conventions.md#rotations).
Rigid3d ReadTransform(const JsonNode& node) {
  ExpectKeys(node, {"R", "t", "rotvec_deg"}, "field of a transform");
  const bool has_r = node.find("R").has_value(), has_rotvec = node.find("rotvec_deg").has_value();
  if (has_r == has_rotvec) node.Fail("needs exactly one of \"R\" and \"rotvec_deg\"", "give the rotation once, as R (3×3) or rotvec_deg");
  if (has_r) return io::ReadRigid(node);
  return Rigid3d::FromRotvec(DegToRad(1.0) * node.at("rotvec_deg").Vector<3>(), node.at("t").Vector<3>());
}

// A whole number in [lo, 2^53] (JSON integers beyond 2^31 are legitimate for samples and seeds).
uint64_t ReadCount(const JsonNode& node, double lo) {
  const double v = node.Number();
  if (v != std::floor(v) || v < lo || v > 9007199254740992.0) {
    node.Fail("expected a whole number ≥ " + io::OrderedJson(lo).dump() + ", got " + node.json().dump(),
              "write a whole number between " + io::OrderedJson(lo).dump() + " and 2^53");
  }
  return static_cast<uint64_t>(v);
}

struct EyeCamera {
  Camera camera;
  std::optional<ParameterCovariance> covariance;
};

// {"file": "<camera@1 path>"} or an inline {image_size, K, distortion[, covariance]}.
EyeCamera ReadEyeCamera(const JsonNode& node, const std::filesystem::path& directory) {
  node.ExpectObject();
  EyeCamera out;
  if (const auto file = node.find("file")) {
    ExpectKeys(node, {"file"}, "field of a camera reference");
    const std::filesystem::path path = directory / file->String();
    const io::JsonDocument doc = io::JsonDocument::Load(path);
    CalibratedCamera calibrated = io::CameraFromJson(doc);
    out.camera = std::move(calibrated.camera);
    out.covariance = std::move(calibrated.covariance);
    return out;
  }
  out.camera = io::ReadCameraIntrinsics(node);
  if (const auto cov = node.find("covariance")) out.covariance = io::ReadCovariance(*cov, out.camera, std::nullopt);  // inline: no poses
  return out;
}

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Every test point must be seen by both cameras: in front and inside the image.
void CheckTestPointsVisible(const JsonNode& points, const ChainGeometry& g) {
  const Rigid3d hmd_from_world = g.hmd_from_tracker * g.tracker_from_world;
  for (size_t k = 0; k < g.test_points.size(); ++k) {
    for (int e = 0; e < kNumEyes; ++e) {
      const Eigen::Vector3d x = g.camera_from_hmd[e] * (hmd_from_world * g.test_points[k].point_in_world);
      const JsonNode where = points.at(k).at("world");
      const std::string eye(kEyeNames[e]);
      const auto q = g.cameras[e].Project(x);
      if (!q) {
        where.Fail("lies behind the " + eye + " camera (depth " + Number(x.z()) + " " + std::string(LengthUnitName(g.length_unit)) + ")",
                   "move the point in front of both cameras, or check frames (x_a = a_from_b · x_b)");
      }
      if (!g.cameras[e].InImage(*q)) {
        where.Fail("projects outside the " + eye + " image, at (" + Number(q->x()) + ", " + Number(q->y()) + ") px in " +
                       std::to_string(g.cameras[e].image_size.width) + "×" + std::to_string(g.cameras[e].image_size.height),
                   "move the point into both cameras' field of view");
      }
    }
  }
}

}  // namespace

ChainModel ChainFromJson(const io::JsonDocument& doc, const std::filesystem::path& directory) {
  const JsonNode root = doc.root();
  root.ExpectObject();
  io::CheckFormat(root, kChainFormat);
  ChainGeometry g;
  g.length_unit = io::ReadLengthUnit(root.at("length_unit"));

  const JsonNode frames = root.at("frames");
  ExpectKeys(frames, {"tracker_from_world", "hmd_from_tracker", "camera_from_hmd", "world_from_virtual", "world_from_object"},
             "frame");
  g.tracker_from_world = ReadTransform(frames.at("tracker_from_world"));
  g.hmd_from_tracker = ReadTransform(frames.at("hmd_from_tracker"));
  const JsonNode camera_from_hmd = frames.at("camera_from_hmd");
  ExpectKeys(camera_from_hmd, {"left", "right"}, "eye");
  for (int e = 0; e < kNumEyes; ++e) g.camera_from_hmd[e] = ReadTransform(camera_from_hmd.at(kEyeNames[e]));
  if (const auto v = frames.find("world_from_virtual")) g.world_from_virtual = ReadTransform(*v);
  g.world_from_object = ReadTransform(frames.at("world_from_object"));
  const double baseline = g.CameraBaseline();
  if (!(baseline > 0)) camera_from_hmd.Fail("the two cameras are at the same place", "give each eye's camera its own position");

  const JsonNode cameras = root.at("cameras");
  ExpectKeys(cameras, {"left", "right"}, "eye");
  std::array<std::optional<ParameterCovariance>, kNumEyes> covariance;
  for (int e = 0; e < kNumEyes; ++e) {
    EyeCamera c = ReadEyeCamera(cameras.at(kEyeNames[e]), directory);
    g.cameras[e] = std::move(c.camera);
    covariance[e] = std::move(c.covariance);
  }

  const JsonNode display = root.at("display");
  ExpectKeys(display, {"ipd", "eye_centre", "camera_baseline"}, "field of display");
  g.ipd = display.at("ipd").PositiveNumber();
  g.eye_centre_in_hmd = 0.5 * (g.camera_from_hmd[0].inverse().t + g.camera_from_hmd[1].inverse().t);
  if (const auto c = display.find("eye_centre")) g.eye_centre_in_hmd = c->Vector<3>();
  if (const auto b = display.find("camera_baseline")) {
    if (std::abs(b->PositiveNumber() - baseline) > 1e-6 * baseline) {
      b->Fail("disagrees with the distance between the cameras in frames.camera_from_hmd (" + Number(baseline) + ")",
              "fix one of them, or delete camera_baseline");
    }
  }

  if (const auto motion = root.find("head_motion")) {
    ExpectKeys(*motion, {"angular_velocity_deg_s", "linear_velocity"}, "field of head_motion");
    if (const auto w = motion->find("angular_velocity_deg_s")) g.head_angular_velocity = DegToRad(1.0) * w->Vector<3>();
    if (const auto v = motion->find("linear_velocity")) g.head_linear_velocity = v->Vector<3>();
  }

  const JsonNode points = root.at("test_points");
  const size_t n = points.ArraySize();
  if (n == 0) points.Fail("no test points", "add at least one test point {\"name\", \"world\"}");
  std::set<std::string> names;
  for (size_t k = 0; k < n; ++k) {
    const JsonNode p = points.at(k);
    ExpectKeys(p, {"name", "world", "surface_behind"}, "field of a test point");
    TestPoint tp;
    tp.name = p.at("name").String();
    if (tp.name.empty()) p.at("name").Fail("empty test point name", "give every test point a unique name");
    if (!names.insert(tp.name).second) p.at("name").Fail("duplicate test point name \"" + tp.name + "\"", "give every test point a unique name");
    tp.point_in_world = p.at("world").Vector<3>();
    if (const auto s = p.find("surface_behind")) {
      tp.surface_behind = s->Number();
      if (*tp.surface_behind == 0) s->Fail("must not be 0 (the overlay would be exactly on the surface)", "give the signed depth gap: > 0 in front, < 0 hidden");
    }
    g.test_points.push_back(std::move(tp));
  }
  CheckTestPointsVisible(points, g);

  const JsonNode sources = root.at("sources");
  sources.ExpectObject();
  ChainModel model = ChainModel::WithZeroErrors(std::move(g), ReadFiducialLayout(sources));
  model.samples = ReadCount(root.at("samples"), 1);
  model.seed = ReadCount(root.at("seed"), 0);
  ReadSources(sources, covariance, &model);
  return model;
}

ChainModel ReadChain(const std::filesystem::path& path) {
  return ChainFromJson(io::JsonDocument::Load(path), path.parent_path());
}

}  // namespace vstcal::errsim
