#include "vstcal/formats/errsim/chain_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <set>
#include <system_error>

#include "vstcal/core/suggest.h"
#include "vstcal/geometry/point_registration.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/handeye/handeye_io.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/format_check.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {


// Built by appending: GCC 12's -Wrestrict misfires on "literal" + std::string.
std::string Quoted(std::string_view s) { return std::string("\"").append(s).append("\""); }
std::string Number(double v) { return ShortestDecimal(v); }

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
  return {std::move(file), std::move(m.solution)};
}

// {"file": "<tracker-noise@1 path>"}.
TrackerNoiseReference ReadTrackerNoiseReference(const JsonNode& node, const std::filesystem::path& directory, LengthUnit chain_unit) {
  node.ExpectObject();
  auto [file, document] = ReadReference(node, directory, "tracker-noise@1");
  TrackerNoiseMeasurement m = TrackerNoiseFromJson(document);
  CheckUnit(node, m.length_unit, chain_unit, "a tracker noise");
  return {std::move(file), std::move(m.noise)};
}

// A number, or one number per component.
double Component(const JsonNode& node, int i, int n) {
  if (node.json().is_array()) {
    node.ArraySize(n);
    return node.at(i).Number();
  }
  return node.Number();
}

// A distribution object for n components (docs/formats.md#vst-chain-distributions), file units.
DistributionSpec ReadDistribution(const JsonNode& node, int n) {
  node.ExpectObject();
  const JsonNode kind_node = node.at("distribution");
  const std::string kind = kind_node.String();
  static const std::vector<std::string_view> kKinds = {"normal", "uniform", "fixed"};
  DistributionSpec out;
  out.first.resize(n);
  out.second.resize(n);
  if (kind == "normal") {
    ExpectKeys(node, {"distribution", "sigma", "mean"}, "field of a normal distribution");
    out.kind = DistributionSpec::Kind::kNormal;
    const JsonNode sigma = node.at("sigma");
    const auto mean = node.find("mean");
    for (int i = 0; i < n; ++i) {
      out.first[i] = mean ? Component(*mean, i, n) : 0.0;
      out.second[i] = Component(sigma, i, n);
      if (out.second[i] < 0) {
        (sigma.json().is_array() ? sigma.at(i) : sigma)
            .Fail("must not be negative, got " + Number(out.second[i]), "give a standard deviation ≥ 0");
      }
    }
  } else if (kind == "uniform") {
    out.kind = DistributionSpec::Kind::kUniform;
    if (node.find("half_width")) {
      ExpectKeys(node, {"distribution", "half_width"}, "field of a uniform distribution");
      const JsonNode hw = node.at("half_width");
      for (int i = 0; i < n; ++i) {
        const double h = Component(hw, i, n);
        if (h < 0) hw.Fail("must not be negative, got " + Number(h), "give a half width ≥ 0");
        out.first[i] = -h;
        out.second[i] = h;
      }
    } else {
      ExpectKeys(node, {"distribution", "min", "max"}, "field of a uniform distribution");
      const JsonNode lo = node.at("min"), hi = node.at("max");
      for (int i = 0; i < n; ++i) {
        out.first[i] = Component(lo, i, n);
        out.second[i] = Component(hi, i, n);
        if (out.first[i] > out.second[i]) {
          hi.Fail("is below min (" + Number(out.first[i]) + " > " + Number(out.second[i]) + ")", "give min ≤ max");
        }
      }
    }
  } else if (kind == "fixed") {
    ExpectKeys(node, {"distribution", "value"}, "field of a fixed distribution");
    out.kind = DistributionSpec::Kind::kFixed;
    const JsonNode value = node.at("value");
    for (int i = 0; i < n; ++i) out.first[i] = Component(value, i, n);
  } else {
    kind_node.Fail("unknown distribution " + Quoted(kind), SuggestKey(kind, kKinds));
  }
  return out;
}

// Every lens parameter name any model of the variant has, in layout order (the largest model's).
std::vector<std::string_view> AllLensParameterNames() {
  std::vector<std::string_view> names;
  ForEachLensModel([&](auto model) {
    const auto& n = decltype(model)::kParamNames;
    if (n.size() > names.size()) names.assign(n.begin(), n.end());
  });
  return names;
}

constexpr std::array<std::string_view, 5> kEyeKeys = {"", "both", "left", "right", "shared"};
int EyeKeyRank(const std::string& key) {
  return static_cast<int>(std::find(kEyeKeys.begin(), kEyeKeys.end(), key) - kEyeKeys.begin());
}

class SourcesReader {
 public:
  explicit SourcesReader(ChainSpec* spec) : spec_(spec) {}

  void Read(const JsonNode& sources) {
    const std::vector<std::string_view> keys(kSourceKeys.begin(), kSourceKeys.end());
    ExpectKeys(sources, keys, "error source");
    for (int s = 0; s < kNumSources; ++s) {
      const Source source = static_cast<Source>(s);
      const auto node = sources.find(SourceKey(source));
      if (!node) continue;
      node->ExpectObject();
      if (source == Source::kCameraIntrinsic) {
        ReadIntrinsics(*node);
      } else if (source == Source::kVirtualObjectAlignment && node->find("fiducials")) {
        ReadFiducials(*node);
      } else {
        ReadSource(*node, source);
      }
    }
    std::stable_sort(spec_->terms.begin(), spec_->terms.end(), [](const TermSpec& a, const TermSpec& b) {
      if (a.term != b.term) return a.term < b.term;
      return EyeKeyRank(a.eye_key) < EyeKeyRank(b.eye_key);
    });
    std::stable_sort(spec_->correlations.begin(), spec_->correlations.end(),
                     [](const CorrelationSpec& a, const CorrelationSpec& b) { return a.term < b.term; });
  }

 private:
  // Terms a file object may hold: those of `source` with this scope and group (kFiducial's form
  // and kLens are read on their own).
  static std::vector<const TermDecl*> TermsOf(Source source, TermScope scope, std::string_view group) {
    std::vector<const TermDecl*> out;
    for (const TermDecl& d : kTerms) {
      if (d.source == source && d.scope == scope && d.group == group && d.extent != TermExtent::kPerFiducial &&
          d.extent != TermExtent::kLens) {
        out.push_back(&d);
      }
    }
    return out;
  }

  void ReadTerms(const JsonNode& node, const std::vector<const TermDecl*>& terms, const std::string& eye_key) {
    for (const TermDecl* d : terms) {
      if (const auto term = node.find(d->file_key)) {
        if (term->json().is_string()) {
          spec_->terms.push_back(MeasuredTerm(*term, *d, eye_key));
          continue;
        }
        spec_->terms.push_back({d->term, eye_key, std::string(d->file_key), ReadDistribution(*term, d->components), ""});
      }
    }
  }

  // A term given by the word of the measurement it comes from (docs/math/vst-chain.md#measured-chain):
  //  - tracking.rotation_deg, .translation: "tracker_noise", N(0, σ²) per axis with the
  //    tracker-noise file's σ (the same in every frame: its three axes' RMS); "handeye", with the σ
  //    the handeye file's joint solve estimated (its tracker_noise);
  //  - tracking.latency_s: "handeye", the residual N(0, σ_δ²) of a system that applies the measured
  //    offset δ̂; "handeye-uncorrected", N(δ̂, σ_δ²) for one that does not.
  TermSpec MeasuredTerm(const JsonNode& node, const TermDecl& d, const std::string& eye_key) {
    const std::string word = node.String();
    TermSpec t{d.term, eye_key, std::string(d.file_key), {}, word};
    t.distribution.kind = DistributionSpec::Kind::kNormal;
    t.distribution.first.assign(static_cast<size_t>(d.components), 0.0);
    if (d.term == Term::kTrackingRotation || d.term == Term::kTrackingTranslation) {
      if (word != "tracker_noise" && word != "handeye") {
        node.Fail("unknown value " + Quoted(word),
                  "write \"tracker_noise\" (the tracker_noise file's σ), \"handeye\" (the σ calib-handeye solve estimated jointly) or a "
                  "distribution object");
      }
      double rotation_rad = 0, translation = 0;
      if (word == "tracker_noise") {
        if (!spec_->tracker_noise) node.Fail("the chain references no tracker noise", "add \"tracker_noise\": {\"file\": \"<tracker-noise@1 file>\"}, or give a distribution");
        rotation_rad = spec_->tracker_noise->measured.rotation.sigma;
        translation = spec_->tracker_noise->measured.translation.sigma;
      } else {
        if (!spec_->handeye) node.Fail("the chain references no hand-eye calibration", "add \"handeye\": {\"file\": \"<handeye@1 file>\"}, or give a distribution");
        const std::optional<JointTrackerNoise>& n = spec_->handeye->measured.tracker_noise;
        if (!n) {
          node.Fail("the handeye file " + spec_->handeye->file + " has no tracker noise (its tracker was taken as exact)",
                    "solve without " VSTCAL_OPT("tracker_exact") ", reference a tracker-noise@1 file (\"tracker_noise\"), or give a distribution");
        }
        rotation_rad = n->rotation.sigma;
        translation = n->translation.sigma;
      }
      const double sigma = d.term == Term::kTrackingRotation ? RadToDeg(rotation_rad) : translation;
      t.distribution.second.assign(static_cast<size_t>(d.components), sigma);
      return t;
    }
    if (d.term == Term::kTrackingLatency) {
      if (word != "handeye" && word != "handeye-uncorrected") {
        node.Fail("unknown value " + Quoted(word),
                  "write \"handeye\" (the residual after applying the measured time offset), \"handeye-uncorrected\" or a distribution object");
      }
      const ParameterCovariance& c = HandEyeCovariance(node);
      const double sigma = std::sqrt(c.matrix(12, 12));
      t.distribution.first.assign(1, word == "handeye" ? 0.0 : spec_->handeye->measured.time_offset);
      t.distribution.second.assign(1, sigma);
      return t;
    }
    node.Fail("is a word, not a distribution", "give a distribution object {\"distribution\": \"normal\", …}");
  }

  // The referenced handeye file's covariance, which a field needs.
  const ParameterCovariance& HandEyeCovariance(const JsonNode& node) {
    if (!spec_->handeye) node.Fail("the chain references no hand-eye calibration", "add \"handeye\": {\"file\": \"<handeye@1 file>\"}, or give the distribution inline");
    if (spec_->handeye->measured.covariance.size() == 0) {
      node.Fail("the handeye file " + spec_->handeye->file + " has no covariance",
                "reference a file written by calib-handeye solve (a calib-synth truth has none), or give the distribution inline");
    }
    if (handeye_covariance_.parameters.empty()) {
      handeye_covariance_.parameters = spec_->handeye->measured.names;
      handeye_covariance_.matrix = spec_->handeye->measured.covariance;
    }
    return handeye_covariance_;
  }

  // "covariance" of a measured pose (docs/formats.md#vst-chain-measured): "handeye" (the file's
  // block of `pose`) or inline over <pose>.rx … .tz, stored in that order.
  PoseCovarianceSpec ReadPoseCovariance(const JsonNode& cov, const std::string& pose) {
    static const std::array<std::string_view, 6> kAxes = {"rx", "ry", "rz", "tx", "ty", "tz"};
    std::vector<std::string> names;
    for (const std::string_view a : kAxes) names.push_back(pose + "." + std::string(a));
    PoseCovarianceSpec out;
    out.covariance.parameters = names;
    out.covariance.matrix.resize(6, 6);
    if (cov.json().is_string()) {
      if (cov.String() != "handeye") {
        cov.Fail("unknown value " + Quoted(cov.String()), "write \"handeye\" (the handeye file's " + pose + " block) or an object {\"parameters\", \"matrix\"} over " + pose + ".rx … .tz");
      }
      const ParameterCovariance& c = HandEyeCovariance(cov);
      out.from_handeye = true;
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) out.covariance.matrix(a, b) = c.matrix(*c.Find(names[a]), *c.Find(names[b]));
      return out;
    }
    cov.ExpectObject();
    ExpectKeys(cov, {"parameters", "matrix"}, "field of a covariance");
    const JsonNode list = cov.at("parameters");
    list.ArraySize(6);
    std::vector<std::string> read;
    for (size_t i = 0; i < 6; ++i) {
      std::string name = list.at(i).String();
      if (std::find(names.begin(), names.end(), name) == names.end()) {
        list.at(i).Fail("unknown parameter " + Quoted(name), "this covariance is over " + pose + ".rx, .ry, .rz, .tx, .ty, .tz");
      }
      if (std::find(read.begin(), read.end(), name) != read.end()) list.at(i).Fail("duplicate parameter " + Quoted(name), "list each parameter once");
      read.push_back(std::move(name));
    }
    const ParameterCovariance c = ReadCovarianceMatrix(cov, read);
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) out.covariance.matrix(a, b) = c.matrix(*c.Find(names[a]), *c.Find(names[b]));
    return out;
  }

  // "left" / "right" / "both" / "shared" sub-objects: read(node, key) for each one given.
  template <typename Read>
  void PerEye(const JsonNode& node, Read read) {
    const auto both = node.find("both");
    for (const std::string_view eye : kEyeNames) {
      if (both && node.find(eye)) {
        node.at(eye).Fail("both \"both\" and " + Quoted(eye) + " are given", "give either \"both\" or \"left\"/\"right\"");
      }
    }
    for (const std::string_view key : {"both", "left", "right", "shared"}) {
      if (const auto n = node.find(key)) read(*n, std::string(key));
    }
  }

  // The eye keys under which a per-eye term (term, key) was given.
  std::vector<const TermSpec*> Given(Term term, const std::string& key) const {
    std::vector<const TermSpec*> out;
    for (const TermSpec& t : spec_->terms) {
      if (t.term == term && t.key == key) out.push_back(&t);
    }
    return out;
  }

  // A shared term is one draw for both eyes: it cannot also be drawn per eye.
  void CheckShared(const JsonNode& node, Source source) {
    const auto shared = node.find("shared");
    if (!shared) return;
    for (const TermSpec& t : spec_->terms) {
      if (t.eye_key != "shared" || Declaration(t.term).source != source) continue;
      for (const TermSpec* other : Given(t.term, t.key)) {
        if (other->eye_key == "shared") continue;
        shared->at(t.key).Fail("given in both \"shared\" and " + Quoted(other->eye_key),
                               "give the term once: in \"shared\" (one draw for both eyes) or in \"left\"/\"right\"/\"both\" "
                               "(a draw per eye, optionally with a \"correlation\")");
      }
    }
  }

  // sources.<source>.correlation.<key>: ρ between the eyes' draws of a per-eye term given for
  // both eyes as normal distributions; a number, or one per component.
  void ReadCorrelations(const JsonNode& node, Source source, const std::vector<std::string_view>& keys,
                        const std::function<const TermDecl*(std::string_view)>& term_of) {
    const auto correlation = node.find("correlation");
    if (!correlation) return;
    ExpectKeys(*correlation, keys, "per-eye term of " + std::string(SourceKey(source)) + " to correlate");
    for (const std::string_view key : keys) {
      const auto value = correlation->find(key);
      if (!value) continue;
      const TermDecl* d = term_of(key);
      const int n = d->extent == TermExtent::kLens ? 1 : d->components;
      CorrelationSpec c{d->term, std::string(key), std::vector<double>(n)};
      for (int i = 0; i < n; ++i) {
        c.rho[i] = Component(*value, i, n);
        if (!(c.rho[i] >= -1 && c.rho[i] <= 1)) {
          (value->json().is_array() ? value->at(i) : *value)
              .Fail("must lie within [-1, 1], got " + Number(c.rho[i]),
                    "give the correlation ρ between the eyes' draws, -1 ≤ ρ ≤ 1 (ρ = 1 with equal σ's is \"shared\")");
        }
      }
      bool left = false, right = false;
      for (const TermSpec* t : Given(d->term, c.key)) {
        if (t->eye_key == "shared") {
          value->Fail("the term is \"shared\" (one draw for both eyes, ρ = 1)",
                      "delete the correlation, or give the term in \"both\" or \"left\"/\"right\"");
        }
        if (t->distribution.kind != DistributionSpec::Kind::kNormal) {
          value->Fail("needs normal distributions, but the " + (t->eye_key == "both" ? std::string("term") : t->eye_key + " eye's") +
                          " is not normal",
                      "give normal σ's for both eyes, or put the term in \"shared\" for one draw of any distribution");
        }
        left = left || t->eye_key == "both" || t->eye_key == "left";
        right = right || t->eye_key == "both" || t->eye_key == "right";
      }
      if (!left || !right) {
        value->Fail("the term is not given for both eyes", "give it in \"both\", or in \"left\" and \"right\", as normal σ's");
      }
      spec_->correlations.push_back(std::move(c));
    }
  }

  void ReadSource(const JsonNode& node, Source source) {
    const std::string what = "term of " + std::string(SourceKey(source));
    const auto once = TermsOf(source, TermScope::kOnce, "");
    const auto per_eye = TermsOf(source, TermScope::kPerEye, "");
    std::vector<std::string_view> allowed, groups;
    for (const TermDecl* d : once) allowed.push_back(d->file_key);
    for (const TermDecl& d : kTerms) {
      if (d.source == source && !d.group.empty() && std::find(groups.begin(), groups.end(), d.group) == groups.end()) {
        groups.push_back(d.group);
      }
    }
    allowed.insert(allowed.end(), groups.begin(), groups.end());
    if (!per_eye.empty()) allowed.insert(allowed.end(), {"left", "right", "both", "shared", "correlation"});
    if (source == Source::kTrackerAlignment) allowed.push_back("covariance");
    ExpectKeys(node, allowed, what);
    if (source == Source::kTrackerAlignment && node.find("covariance")) {
      ExpectKeys(node, {"covariance"}, "term of tracker_alignment with a covariance (rotation_deg and translation do not mix with it)");
      spec_->alignment_covariance = ReadPoseCovariance(node.at("covariance"), "tracker_from_board");
    }
    ReadTerms(node, once, "");
    for (const std::string_view group : groups) {
      if (const auto g = node.find(group)) {
        const auto terms = TermsOf(source, TermScope::kOnce, group);
        std::vector<std::string_view> keys;
        for (const TermDecl* d : terms) keys.push_back(d->file_key);
        // The camera head's mount may take a hand-eye X's covariance: the error of the whole head.
        if (source == Source::kCameraExtrinsic && g->find("covariance")) {
          ExpectKeys(*g, {"covariance"}, "term of camera_extrinsic." + std::string(group) +
                                             " with a covariance (rotation_deg and translation do not mix with it)");
          spec_->mount_covariance = ReadPoseCovariance(g->at("covariance"), "hmd_from_camera");
          continue;
        }
        ExpectKeys(*g, keys, what + "." + std::string(group));
        ReadTerms(*g, terms, "");
      }
    }
    if (per_eye.empty()) return;
    std::vector<std::string_view> keys;
    for (const TermDecl* d : per_eye) keys.push_back(d->file_key);
    PerEye(node, [&](const JsonNode& eye, const std::string& key) {
      if (source == Source::kCameraExtrinsic && eye.find("covariance")) return ReadExtrinsicCovariance(eye, key);
      ExpectKeys(eye, keys, what + (key == "shared" ? " (shared by both eyes)" : " (per eye)"));
      if (key == "shared" && spec_->extrinsic_covariance) {
        eye.Fail("given with camera_extrinsic.right.covariance, which is the right camera's whole pose error",
                 "give the left camera's error in \"left\", or drop the covariance to share a draw");
      }
      ReadTerms(eye, per_eye, key);
    });
    CheckShared(node, source);
    ReadCorrelations(node, source, keys, [&](std::string_view key) {
      return *std::find_if(per_eye.begin(), per_eye.end(), [&](const TermDecl* d) { return d->file_key == key; });
    });
  }

  // camera_extrinsic.right.covariance: "rig" or inline over right_from_left's six tangents.
  void ReadExtrinsicCovariance(const JsonNode& eye, const std::string& key) {
    const JsonNode cov = eye.at("covariance");
    if (key != "right") {
      cov.Fail("a camera_extrinsic covariance is that of a rig's right_from_left, an error of the right camera",
               "move it to sources.camera_extrinsic.right (the left camera is the rig's reference)");
    }
    ExpectKeys(eye, {"covariance"}, "term of camera_extrinsic.right with a covariance (rotation_deg and translation do not mix with it)");
    ExtrinsicCovarianceSpec c;
    if (cov.json().is_string()) {
      if (cov.String() != "rig") {
        cov.Fail("unknown value " + Quoted(cov.String()),
                 "write \"rig\" (the rig file's covariance) or an object {\"parameters\", \"matrix\"} over right_from_left.rx … .tz");
      }
      if (!spec_->rig) cov.Fail("the chain references no rig", "add \"rig\": {\"file\": \"<stereo@1 file>\"}, or give the covariance inline");
      if (!spec_->rig->covariance) {
        cov.Fail("the rig " + spec_->rig->file + " has no covariance",
                 "reference a rig solved by calib-stereo solve (it writes one), or give σ's per component");
      }
      c.from_rig = true;
      c.covariance = *spec_->rig->covariance;
    } else {
      c.covariance = ReadRelativePoseCovariance(cov);
    }
    spec_->extrinsic_covariance = std::move(c);
  }

  // σ's per lens parameter, or a calibration covariance (the camera file's or inline).
  void ReadIntrinsics(const JsonNode& node) {
    ExpectKeys(node, {"left", "right", "both", "shared", "correlation"}, "term of camera_intrinsic");
    const std::vector<std::string_view> names = AllLensParameterNames();
    PerEye(node, [&](const JsonNode& eye, const std::string& key) {
      const auto cov = eye.find("covariance");
      if (cov && key == "shared") {
        cov->Fail("a covariance is one camera's", "give σ's per lens parameter in \"shared\", or the covariance per eye");
      }
      if (key == "shared" && !spec_->intrinsic_covariances.empty()) {
        eye.Fail("given with a camera_intrinsic covariance, whose draw is the eye's whole lens error",
                 "give σ's per lens parameter for both eyes to share a draw, or drop \"shared\"");
      }
      if (!cov) {
        ExpectKeys(eye, names, "lens parameter of camera_intrinsic");
        for (const std::string_view name : names) {
          if (const auto term = eye.find(name)) spec_->terms.push_back({Term::kLens, key, std::string(name), ReadDistribution(*term, 1), ""});
        }
        return;
      }
      ExpectKeys(eye, {"covariance"}, "term of camera_intrinsic with a covariance");
      IntrinsicCovarianceSpec c;
      c.eye_key = key;
      for (int e = 0; e < kNumEyes; ++e) {
        if (key != "both" && key != kEyeNames[e]) continue;
        if (cov->json().is_string()) {
          if (cov->String() != "camera") {
            cov->Fail("unknown value " + Quoted(cov->String()),
                      "write \"camera\" (the camera file's covariance) or an object {\"parameters\", \"matrix\"}");
          }
          if (!spec_->cameras[e].covariance) {
            if (spec_->rig) {
              cov->Fail("the rig " + spec_->rig->file + "'s " + std::string(kEyeNames[e]) + " camera has no covariance",
                        "reference a rig assembled from camera@1 files that have \"covariance\" (calib-stereo assemble keeps their lens part), or give σ's per parameter");
            }
            cov->Fail("the " + std::string(kEyeNames[e]) + " camera has no covariance",
                      "reference a camera@1 file that has \"covariance\", or give σ's per parameter");
          }
          c.from_camera = true;
        } else {
          c.covariance = ReadCovariance(*cov, spec_->cameras[e].camera, std::nullopt);  // inline: no poses to name
        }
        const ParameterCovariance& used = c.from_camera ? *spec_->cameras[e].covariance : c.covariance;
        const auto lens = LensModelParamNames(spec_->cameras[e].camera.model);
        if (std::none_of(used.parameters.begin(), used.parameters.end(),
                         [&](const std::string& p) { return std::find(lens.begin(), lens.end(), p) != lens.end(); })) {
          cov->Fail("names none of the lens parameters", "name them as fx, fy, cx, cy, s and the lens model's coefficients");
        }
      }
      spec_->intrinsic_covariances.push_back(std::move(c));
    });
    CheckShared(node, Source::kCameraIntrinsic);
    static const TermDecl& lens = Declaration(Term::kLens);
    ReadCorrelations(node, Source::kCameraIntrinsic, names, [](std::string_view) { return &lens; });
  }

  void ReadFiducials(const JsonNode& node) {
    ExpectKeys(node, {"fiducials", "fle_rms"}, "term of virtual_object_alignment with fiducials (the pose terms "
                                               "rotation_deg/translation do not mix with them)");
    const JsonNode layout = node.at("fiducials");
    const size_t n = layout.ArraySize();
    if (n < 3) layout.Fail("has " + std::to_string(n) + " fiducials", "give at least 3, not all on one line");
    if (n > kMaxFiducials) {
      layout.Fail("has " + std::to_string(n) + " fiducials, more than the " + std::to_string(kMaxFiducials) + " err-sim takes",
                  "give at most " + std::to_string(kMaxFiducials));
    }
    for (size_t i = 0; i < n; ++i) spec_->fiducials.push_back(layout.at(i).Vector<3>());
    if (!RegistrationFrame::For(spec_->fiducials)) {
      layout.Fail("the fiducials lie on one line (the rotation about it is free)", "give at least 3 fiducials not on one line");
    }
    spec_->fle_rms = node.at("fle_rms").NonNegativeNumber();
  }

  ChainSpec* spec_;
  ParameterCovariance handeye_covariance_;  // the handeye file's, named
};

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

  SourcesReader(&spec).Read(root.at("sources"));
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
