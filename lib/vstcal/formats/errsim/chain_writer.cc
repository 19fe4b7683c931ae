#include "vstcal/formats/errsim/chain_writer.h"

#include <algorithm>

#include "vstcal/formats/camera/camera_io.h"

namespace vstcal {
namespace {


OrderedJson TransformToJson(const TransformSpec& t) {
  OrderedJson j;
  if (t.R) {
    j["R"] = MatrixToJson(*t.R);
  } else {
    j["rotvec_deg"] = MatrixToJson(t.rotvec_deg);
  }
  j["t"] = MatrixToJson(t.t);
  return j;
}

OrderedJson CovarianceToJson(const ParameterCovariance& c) {
  return {{"parameters", c.parameters}, {"matrix", MatrixToJson(c.matrix)}};
}

OrderedJson CameraToJson(const CameraSpec& c) {
  if (!c.file.empty()) return {{"file", c.file}};
  OrderedJson j;
  j["image_size"] = {c.camera.image_size.width, c.camera.image_size.height};
  j["K"] = MatrixToJson(c.camera.K());
  j["distortion"] = DistortionToJson(c.camera);
  if (c.covariance) j["covariance"] = CovarianceToJson(*c.covariance);
  return j;
}

// One number when every component has it, else one per component.
OrderedJson Components(const std::vector<double>& v) {
  if (std::all_of(v.begin(), v.end(), [&](double x) { return x == v[0]; })) return v[0];
  return v;
}

OrderedJson DistributionToJson(const DistributionSpec& d) {
  switch (d.kind) {
    case DistributionSpec::Kind::kNormal:
      return {{"distribution", "normal"}, {"mean", Components(d.first)}, {"sigma", Components(d.second)}};
    case DistributionSpec::Kind::kUniform:
      return {{"distribution", "uniform"}, {"min", Components(d.first)}, {"max", Components(d.second)}};
    case DistributionSpec::Kind::kFixed:
      return {{"distribution", "fixed"}, {"value", Components(d.first)}};
  }
  return nullptr;
}

OrderedJson SourcesToJson(const ChainSpec& spec) {
  OrderedJson sources = OrderedJson::object();
  // spec.terms is in kTerms order (grouped by source), then eye key: walking it builds each
  // source's object in the schema's order.
  for (const TermSpec& t : spec.terms) {
    const TermDecl& d = Declaration(t.term);
    OrderedJson* at = &sources[std::string(SourceKey(d.source))];
    if (!t.eye_key.empty()) at = &(*at)[t.eye_key];
    if (!d.group.empty()) at = &(*at)[std::string(d.group)];
    (*at)[t.key] = t.from.empty() ? DistributionToJson(t.distribution) : OrderedJson(t.from);
  }
  for (const CorrelationSpec& c : spec.correlations) {
    sources[std::string(SourceKey(Declaration(c.term).source))]["correlation"][c.key] = Components(c.rho);
  }
  for (const IntrinsicCovarianceSpec& c : spec.intrinsic_covariances) {
    sources["camera_intrinsic"][c.eye_key]["covariance"] = c.from_camera ? OrderedJson("camera") : CovarianceToJson(c.covariance);
  }
  if (const auto& c = spec.extrinsic_covariance) {
    sources["camera_extrinsic"]["right"]["covariance"] = c->from_rig ? OrderedJson("rig") : CovarianceToJson(c->covariance);
  }
  auto pose_covariance = [](const PoseCovarianceSpec& c) { return c.from_handeye ? OrderedJson("handeye") : CovarianceToJson(c.covariance); };
  if (const auto& c = spec.mount_covariance) sources["camera_extrinsic"]["rig"]["covariance"] = pose_covariance(*c);
  if (const auto& c = spec.alignment_covariance) sources["tracker_alignment"]["covariance"] = pose_covariance(*c);
  if (!spec.fiducials.empty()) {
    OrderedJson layout = OrderedJson::array();
    for (const auto& f : spec.fiducials) layout.push_back(MatrixToJson(f));
    sources["virtual_object_alignment"] = {{"fiducials", layout}, {"fle_rms", spec.fle_rms}};
  }
  // The sources in their DESIGN order, whatever order the loops above met them in.
  OrderedJson ordered = OrderedJson::object();
  for (const std::string_view key : kSourceKeys) {
    if (sources.contains(key)) ordered[std::string(key)] = sources[std::string(key)];
  }
  return ordered;
}

// A kept provenance in ProvenanceToJson's key order (tool, version, args, seed), then any other
// keys as read (alphabetically): the order does not depend on how the file was read.
OrderedJson CanonicalProvenance(const OrderedJson& kept) {
  OrderedJson out = OrderedJson::object();
  for (const char* key : {"tool", "version", "args", "seed"}) {
    if (kept.contains(key)) out[key] = kept[key];
  }
  for (auto it = kept.begin(); it != kept.end(); ++it) {
    if (!out.contains(it.key())) out[it.key()] = it.value();
  }
  return out;
}

}  // namespace

OrderedJson ChainSpecToJson(const ChainSpec& spec, const Provenance& provenance) {
  OrderedJson j;
  j["format"] = kChainFormat;
  if (!spec.name.empty()) j["name"] = spec.name;
  j["length_unit"] = LengthUnitName(spec.length_unit);
  j["samples"] = spec.samples;
  j["seed"] = spec.seed;
  OrderedJson frames;
  if (!spec.handeye) frames["tracker_from_world"] = TransformToJson(spec.tracker_from_world);  // else the hand-eye Z
  frames["hmd_from_tracker"] = TransformToJson(spec.hmd_from_tracker);
  if (!spec.handeye) frames["camera_from_hmd"]["left"] = TransformToJson(spec.camera_from_hmd[0]);  // else X⁻¹
  if (!spec.rig) frames["camera_from_hmd"]["right"] = TransformToJson(spec.camera_from_hmd[1]);  // else the rig's
  frames["world_from_virtual"] = TransformToJson(spec.world_from_virtual);
  frames["world_from_object"] = TransformToJson(spec.world_from_object);
  j["frames"] = std::move(frames);
  if (spec.handeye) j["handeye"] = {{"file", spec.handeye->file}};
  if (spec.tracker_noise) j["tracker_noise"] = {{"file", spec.tracker_noise->file}};
  if (spec.rig) {
    j["rig"] = {{"file", spec.rig->file}};
  } else {
    j["cameras"] = {{"left", CameraToJson(spec.cameras[0])}, {"right", CameraToJson(spec.cameras[1])}};
  }
  OrderedJson display;
  display["ipd"] = spec.ipd;
  display["eye_centre"] = MatrixToJson(spec.eye_centre);
  if (spec.camera_baseline) display["camera_baseline"] = *spec.camera_baseline;
  display["virtual_image_distance"] = spec.virtual_image_distance > 0 ? OrderedJson(spec.virtual_image_distance) : OrderedJson("infinity");
  // Per eye, as the reader keeps it: {"left": φ_h or [φ_h, φ_v], "right": …}.
  for (int e = 0; e < kNumEyes; ++e) {
    if (const auto& fov = spec.display_field_of_view[e]) {
      display["field_of_view_deg"][std::string(kEyeNames[e])] =
          fov->vertical_deg ? OrderedJson::array({fov->horizontal_deg, *fov->vertical_deg}) : OrderedJson(fov->horizontal_deg);
    }
  }
  j["display"] = std::move(display);
  j["head_motion"] = {{"angular_velocity_deg_s", MatrixToJson(spec.angular_velocity_deg_s)},
                      {"linear_velocity", MatrixToJson(spec.linear_velocity)}};
  OrderedJson points = OrderedJson::array();
  for (const ChainTestPoint& tp : spec.test_points) {
    OrderedJson p;
    p["name"] = tp.name;
    p["world"] = MatrixToJson(tp.point_in_world);
    if (tp.surface_behind) p["surface_behind"] = *tp.surface_behind;
    points.push_back(std::move(p));
  }
  j["test_points"] = std::move(points);
  j["sources"] = SourcesToJson(spec);
  if (const auto& c = spec.joint_covariance) j["joint_covariance"] = c->from_rig ? OrderedJson("rig") : CovarianceToJson(c->covariance);
  j["provenance"] = spec.provenance ? CanonicalProvenance(*spec.provenance) : ProvenanceToJson(provenance);
  return j;
}

}  // namespace vstcal
