#include "vstcal/formats/errsim/chain_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <set>
#include <system_error>

#include "vstcal/core/suggest.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/handeye/handeye_io.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/format_check.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/core/option_name.h"
#include "vstcal/formats/errsim/chain_sources_reader.h"

namespace vstcal {
namespace {

using chain_reading::Number;
using chain_reading::Quoted;



// {"R", "t"} or {"rotvec_deg", "t"} (docs/conventions.md#rotations).
TransformSpec ReadTransform(const JsonNode& node) {
  ExpectKeys(node, {"R", "t", "rotvec_deg"}, "field of a transform");
  const bool has_r = node.find("R").has_value(), has_rotvec = node.find("rotvec_deg").has_value();
  if (has_r == has_rotvec) node.Fail("needs exactly one of \"R\" and \"rotvec_deg\"", "give the rotation once, as R (3×3) or rotvec_deg");
  TransformSpec spec;
  if (has_r) {
    spec.value = ReadRigid(node);
    spec.R = node.at("R").Matrix<3, 3>();
  } else {
    spec.rotvec_deg = node.at("rotvec_deg").Vector<3>();
    if (spec.rotvec_deg.norm() > 1e6) node.at("rotvec_deg").Fail("is beyond 10⁶ degrees", "write the rotation vector in degrees, |r| ≤ 360");
    spec.value = Rigid3d::FromRotvec(DegToRad(1.0) * spec.rotvec_deg, node.at("t").Vector<3>());
  }
  spec.t = node.at("t").Vector<3>();
  return spec;
}

// A whole number in [lo, hi] (JSON integers beyond 2^31 are legitimate for samples and seeds).
uint64_t ReadCount(const JsonNode& node, double lo, double hi, const std::string& hi_text) {
  const double v = node.Number();
  if (v != std::floor(v) || v < lo || v > hi) {
    const std::string lo_text = std::to_string(static_cast<uint64_t>(lo));
    node.Fail("expected a whole number from " + lo_text + " to " + hi_text + ", got " + node.json().dump(),
              "write a whole number between " + lo_text + " and " + hi_text);
  }
  return static_cast<uint64_t>(v);
}

// A {"file": "<path>"} reference: the path as written and the document it names, relative to the
// chain's folder. Checked here, where the chain's field can be named; the referenced file's own
// problems name that file.
std::pair<std::string, JsonDocument> ReadReference(const JsonNode& node, const std::filesystem::path& directory,
                                                       std::string_view format) {
  ExpectKeys(node, {"file"}, "field of a " + std::string(format) + " reference");
  const JsonNode file = node.at("file");
  std::string written = file.String();
  const std::string fix = "give the " + std::string(format) + " file's path, relative to the chain's folder";
  if (written.empty()) file.Fail("is empty", fix);
  const std::filesystem::path path = directory / written;
  std::error_code error;
  if (!std::filesystem::exists(path, error)) file.Fail("names " + path.string() + ", which does not exist", fix);
  if (std::filesystem::is_directory(path, error)) file.Fail("names " + path.string() + ", a directory", fix);
  return {std::move(written), JsonDocument::Load(path)};
}

// {"file": "<camera@1 path>"} or an inline {image_size, K, distortion[, covariance]}.
CameraSpec ReadCameraSpec(const JsonNode& node, const std::filesystem::path& directory) {
  node.ExpectObject();
  CameraSpec out;
  if (node.find("file")) {
    auto [file, document] = ReadReference(node, directory, "camera@1");
    out.file = std::move(file);
    CalibratedCamera calibrated = CameraFromJson(document);
    out.camera = std::move(calibrated.camera);
    out.covariance = std::move(calibrated.covariance);
    return out;
  }
  ExpectKeys(node, {"image_size", "K", "intrinsics", "distortion", "covariance"}, "field of an inline camera");
  out.camera = ReadCameraIntrinsics(node);
  if (const auto cov = node.find("covariance")) out.covariance = ReadCovariance(*cov, out.camera, std::nullopt);  // inline: no poses
  return out;
}

// {"file": "<stereo@1 path>"}: the rig's cameras go into `cameras`, right_from_left and its
// covariance into the returned spec. The rig's length unit must be the chain's.
RigSpec ReadRigSpec(const JsonNode& node, const std::filesystem::path& directory, LengthUnit chain_unit,
                    std::array<CameraSpec, kNumEyes>* cameras) {
  node.ExpectObject();
  auto [file, document] = ReadReference(node, directory, "stereo@1");
  StereoRig rig = StereoRigFromJson(document);
  if (rig.length_unit != chain_unit) {
    node.at("file").Fail("names a rig in \"" + std::string(LengthUnitName(rig.length_unit)) + "\", but the chain is in \"" +
                             std::string(LengthUnitName(chain_unit)) + "\"",
                         "write the chain in the rig's length unit");
  }
  (*cameras)[0] = {"", std::move(rig.left.camera), std::move(rig.left.covariance)};
  (*cameras)[1] = {"", std::move(rig.right.camera), std::move(rig.right.covariance)};
  return {std::move(file), rig.right_from_left, std::move(rig.covariance), std::move(rig.joint_covariance)};
}

// The length unit of a referenced measurement must be the chain's: its translations and σ's are
// numbers in it.
void CheckUnit(const JsonNode& node, LengthUnit file_unit, LengthUnit chain_unit, std::string_view what) {
  if (file_unit == chain_unit) return;
  node.at("file").Fail("names " + std::string(what) + " in \"" + std::string(LengthUnitName(file_unit)) + "\", but the chain is in \"" +
                           std::string(LengthUnitName(chain_unit)) + "\"",
                       "write the chain in the measurement's length unit (or measure in the chain's)");
}

// {"file": "<handeye@1 path>"} (docs/formats.md#vst-chain-measured).
HandEyeReference ReadHandEyeReference(const JsonNode& node, const std::filesystem::path& directory, LengthUnit chain_unit) {
  node.ExpectObject();
  auto [file, document] = ReadReference(node, directory, "handeye@1");
  HandEyeMeasurement m = HandEyeFromJson(document);
  CheckUnit(node, m.length_unit, chain_unit, "a hand-eye calibration");
  return {std::move(file), std::move(m.solution), m.bootstrap_time_offset_sigma};
}

// {"file": "<tracker-noise@1 path>"}.
TrackerNoiseReference ReadTrackerNoiseReference(const JsonNode& node, const std::filesystem::path& directory, LengthUnit chain_unit) {
  node.ExpectObject();
  auto [file, document] = ReadReference(node, directory, "tracker-noise@1");
  TrackerNoiseMeasurement m = TrackerNoiseFromJson(document);
  CheckUnit(node, m.length_unit, chain_unit, "a tracker noise");
  return {std::move(file), std::move(m.noise)};
}


// One angle of a display's field of view: the camera's image spans it, so it must be a real
// field, more than 0° and less than 180°.
double ReadFieldAngle(const JsonNode& node) {
  const double deg = node.Number();
  if (!(deg > 0 && deg < 180)) {
    node.Fail("must lie strictly between 0 and 180 degrees, got " + Number(deg),
              "give the angle the camera's image spans on the display, 0 < φ < 180 (e.g. 90), or delete the field to show the camera's own");
  }
  return deg;
}

// φ_h, or [φ_h, φ_v].
DisplayFieldOfView ReadOneFieldOfView(const JsonNode& node) {
  DisplayFieldOfView fov;
  if (node.json().is_array()) {
    node.ArraySize(2);
    fov.horizontal_deg = ReadFieldAngle(node.at(0));
    fov.vertical_deg = ReadFieldAngle(node.at(1));
  } else {
    fov.horizontal_deg = ReadFieldAngle(node);
  }
  return fov;
}

// display.field_of_view_deg (docs/formats.md#vst-chain-display-fov): one field for both eyes, or
// {"left": …, "right": …} (an eye not given shows its camera's own field).
std::array<std::optional<DisplayFieldOfView>, kNumEyes> ReadDisplayFieldOfView(const JsonNode& node) {
  std::array<std::optional<DisplayFieldOfView>, kNumEyes> out;
  if (node.json().is_object()) {
    ExpectKeys(node, {"left", "right"}, "eye");
    for (int e = 0; e < kNumEyes; ++e) {
      if (const auto eye = node.find(kEyeNames[e])) out[e] = ReadOneFieldOfView(*eye);
    }
    return out;
  }
  out[0] = out[1] = ReadOneFieldOfView(node);
  return out;
}

// "joint_covariance" (docs/formats.md#vst-chain-joint): "rig" or inline. Each parameter it
// draws is drawn by it alone: a σ, a correlation or a covariance given for the same error under
// sources would be a second answer.
JointCovarianceSpec ReadJointCovarianceSpec(const JsonNode& node, const ChainSpec& spec) {
  JointCovarianceSpec out;
  if (node.json().is_string()) {
    if (node.String() != "rig") {
      node.Fail("unknown value " + Quoted(node.String()),
                "write \"rig\" (the rig file's joint_covariance) or an object {\"parameters\", \"matrix\"} over left.<lens "
                "parameter>, right.<lens parameter> and right_from_left.rx … .tz");
    }
    if (!spec.rig) node.Fail("the chain references no rig", "add \"rig\": {\"file\": \"<stereo@1 file>\"}, or give the covariance inline");
    if (!spec.rig->joint_covariance) {
      node.Fail("the rig " + spec.rig->file + " has no joint_covariance",
                "reference a rig solved by calib-stereo solve (it writes one), or give the covariance inline");
    }
    out.from_rig = true;
    out.covariance = *spec.rig->joint_covariance;
  } else {
    out.covariance = ReadJointCovariance(node, spec.cameras[0].camera.model, spec.cameras[1].camera.model);
  }
  const ParameterCovariance& c = out.covariance;
  auto twice = [&](const std::string& name, const std::string& field) {
    node.Fail("draws " + name + ", which " + field + " also gives",
              "give each error once: delete it from " + field + ", or from joint_covariance");
  };
  bool pose = false;
  for (const std::string& t : RelativePoseTangentNames()) pose = pose || c.Find(t).has_value();
  for (const TermSpec& t : spec.terms) {
    const bool right = t.eye_key == "right" || t.eye_key == "both" || t.eye_key == "shared";
    const bool left = t.eye_key == "left" || t.eye_key == "both" || t.eye_key == "shared";
    const std::string field = "sources." + std::string(SourceKey(Declaration(t.term).source)) + "." + t.eye_key + "." + t.key;
    if (t.term == Term::kLens) {
      if (left && c.Find(JointCovarianceName(0, t.key))) twice(JointCovarianceName(0, t.key), field);
      if (right && c.Find(JointCovarianceName(1, t.key))) twice(JointCovarianceName(1, t.key), field);
    }
    if ((t.term == Term::kCameraRotation || t.term == Term::kCameraTranslation) && right && pose) {
      twice("right_from_left's error (the right camera's pose)", field);
    }
  }
  for (const CorrelationSpec& r : spec.correlations) {
    if (r.term == Term::kLens && (c.Find(JointCovarianceName(0, r.key)) || c.Find(JointCovarianceName(1, r.key)))) {
      twice("both eyes' " + r.key + " with their correlation", "sources.camera_intrinsic.correlation." + r.key);
    }
  }
  for (const IntrinsicCovarianceSpec& ic : spec.intrinsic_covariances) {
    for (int e = 0; e < kNumEyes; ++e) {
      if (ic.eye_key != "both" && ic.eye_key != kEyeNames[e]) continue;
      for (const std::string_view p : LensModelParamNames(spec.cameras[e].camera.model)) {
        if (c.Find(JointCovarianceName(e, p))) twice(JointCovarianceName(e, p), "sources.camera_intrinsic." + ic.eye_key + ".covariance");
      }
    }
  }
  if (pose && spec.extrinsic_covariance) twice("right_from_left's error", "sources.camera_extrinsic.right.covariance");
  return out;
}

}  // namespace

ChainSpec ChainSpecFromJson(const JsonDocument& doc, const std::filesystem::path& directory) {
  const JsonNode root = doc.root();
  root.ExpectObject();
  CheckFormat(root, kChainFormat);
  ExpectKeys(root, {"format", "name", "length_unit", "samples", "seed", "frames", "rig", "handeye", "tracker_noise", "cameras",
                    "display", "head_motion", "test_points", "sources", "joint_covariance", "provenance"},
             "field of a chain");
  ChainSpec spec;
  spec.file = doc.name();
  if (const auto name = root.find("name")) spec.name = name->String();
  spec.length_unit = ReadLengthUnit(root.at("length_unit"));
  spec.samples = ReadCount(root.at("samples"), 1, 1e12, "10^12");
  spec.seed = ReadCount(root.at("seed"), 0, 9007199254740992.0, "2^53");

  if (const auto handeye = root.find("handeye")) spec.handeye = ReadHandEyeReference(*handeye, directory, spec.length_unit);
  if (const auto noise = root.find("tracker_noise")) spec.tracker_noise = ReadTrackerNoiseReference(*noise, directory, spec.length_unit);

  const JsonNode frames = root.at("frames");
  ExpectKeys(frames, {"tracker_from_world", "hmd_from_tracker", "camera_from_hmd", "world_from_virtual", "world_from_object"},
             "frame");
  if (spec.handeye) {
    // The hand-eye calibration measured both: the chain giving them too would be two answers.
    if (const auto t = frames.find("tracker_from_world")) {
      t->Fail("given with \"handeye\", which sets it to tracker_from_board (the chain's world is the board's frame)",
              "delete frames.tracker_from_world (or \"handeye\")");
    }
    spec.tracker_from_world.R = spec.handeye->measured.tracker_from_board.R;
    spec.tracker_from_world.t = spec.handeye->measured.tracker_from_board.t;
    spec.tracker_from_world.value = spec.handeye->measured.tracker_from_board;
  } else {
    spec.tracker_from_world = ReadTransform(frames.at("tracker_from_world"));
  }
  spec.hmd_from_tracker = ReadTransform(frames.at("hmd_from_tracker"));
  // With a rig and a hand-eye calibration there is nothing left to write under camera_from_hmd.
  const JsonDocument no_eyes = JsonDocument::Parse("{}", doc.name());
  const bool eyes_optional = spec.handeye && root.find("rig");
  const JsonNode camera_from_hmd =
      eyes_optional && !frames.find("camera_from_hmd") ? no_eyes.root() : frames.at("camera_from_hmd");
  ExpectKeys(camera_from_hmd, {"left", "right"}, "eye");
  auto left_camera_from_hmd = [&]() {
    if (!spec.handeye) return ReadTransform(camera_from_hmd.at("left"));
    if (const auto left = camera_from_hmd.find("left")) {
      left->Fail("given with \"handeye\", which sets it to the inverse of hmd_from_camera",
                 "delete frames.camera_from_hmd.left (or \"handeye\")");
    }
    const Rigid3d x = spec.handeye->measured.hmd_from_camera.inverse();
    TransformSpec t;
    t.R = x.R;
    t.t = x.t;
    t.value = x;
    return t;
  };
  if (const auto rig = root.find("rig")) {
    // The rig holds the cameras and their relative pose: the chain giving them too would be two
    // answers to one question.
    if (const auto cameras = root.find("cameras")) {
      cameras->Fail("given with \"rig\", which holds both cameras", "delete \"cameras\" (or \"rig\", to give the cameras here)");
    }
    if (const auto right = camera_from_hmd.find("right")) {
      right->Fail("given with \"rig\", which sets it to right_from_left · camera_from_hmd.left",
                  "delete frames.camera_from_hmd.right (or \"rig\")");
    }
    spec.rig = ReadRigSpec(*rig, directory, spec.length_unit, &spec.cameras);
    spec.camera_from_hmd[0] = left_camera_from_hmd();
    const Rigid3d right = spec.rig->right_from_left * spec.camera_from_hmd[0].value;
    spec.camera_from_hmd[1].R = right.R;
    spec.camera_from_hmd[1].t = right.t;
    spec.camera_from_hmd[1].value = right;
  } else {
    spec.camera_from_hmd[0] = left_camera_from_hmd();
    spec.camera_from_hmd[1] = ReadTransform(camera_from_hmd.at("right"));
  }
  if (const auto v = frames.find("world_from_virtual")) spec.world_from_virtual = ReadTransform(*v);
  spec.world_from_object = ReadTransform(frames.at("world_from_object"));
  const Eigen::Vector3d left = spec.camera_from_hmd[0].value.inverse().t, right = spec.camera_from_hmd[1].value.inverse().t;
  const double baseline = (right - left).norm();
  if (!(baseline > 0)) camera_from_hmd.Fail("the two cameras are at the same place", "give each eye's camera its own position");

  if (!spec.rig) {
    const JsonNode cameras = root.at("cameras");
    ExpectKeys(cameras, {"left", "right"}, "eye");
    for (int e = 0; e < kNumEyes; ++e) spec.cameras[e] = ReadCameraSpec(cameras.at(kEyeNames[e]), directory);
  }

  const JsonNode display = root.at("display");
  ExpectKeys(display, {"ipd", "eye_centre", "camera_baseline", "virtual_image_distance", "field_of_view_deg"}, "field of display");
  if (const auto fov = display.find("field_of_view_deg")) spec.display_field_of_view = ReadDisplayFieldOfView(*fov);
  spec.ipd = display.at("ipd").PositiveNumber();
  spec.eye_centre = (0.5 * (left + right)).array() + 0.0;  // + 0.0: no −0 in a written chain
  if (const auto c = display.find("eye_centre")) spec.eye_centre = c->Vector<3>();
  if (const auto b = display.find("camera_baseline")) {
    spec.camera_baseline = b->PositiveNumber();
    if (std::abs(*spec.camera_baseline - baseline) > 1e-6 * baseline) {
      b->Fail("disagrees with the distance between the cameras in frames.camera_from_hmd (" + Number(baseline) + ")",
              "fix one of them, or delete camera_baseline");
    }
  }
  spec.virtual_image_distance = DefaultVirtualImageDistance(spec.length_unit);
  if (const auto d = display.find("virtual_image_distance")) {
    if (d->json().is_string()) {
      if (d->String() != "infinity") d->Fail("unknown value " + d->json().dump(), "give a distance > 0 or \"infinity\" (a collimated display)");
      spec.virtual_image_distance = 0;
    } else {
      spec.virtual_image_distance = d->PositiveNumber();
    }
  }

  if (const auto motion = root.find("head_motion")) {
    ExpectKeys(*motion, {"angular_velocity_deg_s", "linear_velocity"}, "field of head_motion");
    if (const auto w = motion->find("angular_velocity_deg_s")) spec.angular_velocity_deg_s = w->Vector<3>();
    if (const auto v = motion->find("linear_velocity")) spec.linear_velocity = v->Vector<3>();
  }

  const JsonNode points = root.at("test_points");
  const size_t n = points.ArraySize();
  if (n == 0) points.Fail("no test points", "add at least one test point {\"name\", \"world\"}");
  if (n > kMaxTestPoints) {
    points.Fail("has " + std::to_string(n) + " test points, more than the " + std::to_string(kMaxTestPoints) + " err-sim takes",
                "give at most " + std::to_string(kMaxTestPoints) + " (split the chain)");
  }
  std::set<std::string> names;
  for (size_t k = 0; k < n; ++k) {
    const JsonNode p = points.at(k);
    ExpectKeys(p, {"name", "world", "surface_behind"}, "field of a test point");
    ChainTestPoint tp;
    tp.name = p.at("name").String();
    if (tp.name.empty()) p.at("name").Fail("empty test point name", "give every test point a unique name");
    if (!names.insert(tp.name).second) p.at("name").Fail("duplicate test point name \"" + tp.name + "\"", "give every test point a unique name");
    tp.point_in_world = p.at("world").Vector<3>();
    if (const auto s = p.find("surface_behind")) {
      tp.surface_behind = s->Number();
      if (*tp.surface_behind == 0) s->Fail("must not be 0 (the overlay would be exactly on the surface)", "give the signed depth gap: > 0 in front, < 0 hidden");
    }
    spec.test_points.push_back(std::move(tp));
  }

  chain_reading::ReadSources(root.at("sources"), &spec);
  if (const auto joint = root.find("joint_covariance")) spec.joint_covariance = ReadJointCovarianceSpec(*joint, spec);
  if (const auto provenance = root.find("provenance")) {
    provenance->ExpectObject();
    spec.provenance = OrderedJson::parse(provenance->json().dump());
  }
  return spec;
}

ChainSpec ReadChainSpec(const std::filesystem::path& path) {
  return ChainSpecFromJson(JsonDocument::Load(path), path.parent_path());
}

ChainModel ReadChain(const std::filesystem::path& path) { return BuildChainModel(ReadChainSpec(path)); }

}  // namespace vstcal
