// The "sources" object of a vstcal/vst-chain@1 file (docs/formats.md#vst-chain): each error
// source's terms, per eye or shared, as distributions, measured terms or covariances, and the
// correlations between the eyes' draws. The rest of the chain (frames, cameras, display, test
// points) is chain_reader.cc's.
#include "vstcal/formats/errsim/chain_sources_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <set>

#include "vstcal/core/suggest.h"
#include "vstcal/formats/errsim/chain_reader.h"
#include "vstcal/geometry/point_registration.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/handeye/handeye_io.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/format_check.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/core/option_name.h"

namespace vstcal::chain_reading {
namespace {

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
  //    offset δ̂; "handeye-uncorrected", N(δ̂, σ_δ²) for one that does not (σ_δ the file's bootstrap
  //    σ when it has one, else its covariance's).
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
      // The bootstrap's σ_δ when the file has one: with few views the first-order σ is up to 15 %
      // low (docs/math/handeye.md#delta-bootstrap).
      const double sigma = spec_->handeye->measured_bootstrap_time_offset_sigma.value_or(std::sqrt(c.matrix(12, 12)));
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

}  // namespace

void ReadSources(const JsonNode& sources, ChainSpec* spec) { SourcesReader(spec).Read(sources); }

}  // namespace vstcal::chain_reading
