#include "vstcal/errsim/source_io.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Eigenvalues>

#include "vstcal/core/error.h"
#include "vstcal/core/suggest.h"
#include "vstcal/errsim/point_registration.h"
#include "vstcal/io/camera_io.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/json_writer.h"

namespace vstcal::errsim {
namespace {

using io::JsonNode;
using io::ExpectKeys;

constexpr double kRadPerDeg = kPi / 180.0;

std::string Quoted(std::string_view s) { return "\"" + std::string(s) + "\""; }

// A number, or one number per component.
double Component(const JsonNode& node, int i, int n) {
  if (node.json().is_array()) {
    node.ArraySize(n);
    return node.at(i).Number();
  }
  return node.Number();
}

// A distribution object for n components, converted to internal units by `scale`
// (docs/formats.md#vst-chain-distributions).
std::vector<Distribution> ReadDistribution(const JsonNode& node, int n, double scale) {
  node.ExpectObject();
  const JsonNode kind_node = node.at("distribution");
  const std::string kind = kind_node.String();
  static const std::vector<std::string_view> kKinds = {"normal", "uniform", "fixed"};
  std::vector<Distribution> out(n, Distribution::MakeFixed(0));
  if (kind == "normal") {
    ExpectKeys(node, {"distribution", "sigma", "mean"}, "field of a normal distribution");
    const JsonNode sigma = node.at("sigma");
    const auto mean = node.find("mean");
    for (int i = 0; i < n; ++i) {
      const double s = Component(sigma, i, n);
      if (s < 0) {
        (sigma.json().is_array() ? sigma.at(i) : sigma)
            .Fail("must not be negative, got " + io::OrderedJson(s).dump(), "give a standard deviation ≥ 0");
      }
      out[i] = Distribution::MakeNormal(scale * (mean ? Component(*mean, i, n) : 0.0), scale * s);
    }
  } else if (kind == "uniform") {
    if (node.find("half_width")) {
      ExpectKeys(node, {"distribution", "half_width"}, "field of a uniform distribution");
      const JsonNode hw = node.at("half_width");
      for (int i = 0; i < n; ++i) {
        const double h = Component(hw, i, n);
        if (h < 0) hw.Fail("must not be negative, got " + io::OrderedJson(h).dump(), "give a half width ≥ 0");
        out[i] = Distribution::MakeUniform(-scale * h, scale * h);
      }
    } else {
      ExpectKeys(node, {"distribution", "min", "max"}, "field of a uniform distribution");
      const JsonNode lo = node.at("min"), hi = node.at("max");
      for (int i = 0; i < n; ++i) {
        const double a = Component(lo, i, n), b = Component(hi, i, n);
        if (a > b) hi.Fail("is below min (" + io::OrderedJson(a).dump() + " > " + io::OrderedJson(b).dump() + ")", "give min ≤ max");
        out[i] = Distribution::MakeUniform(scale * a, scale * b);
      }
    }
  } else if (kind == "fixed") {
    ExpectKeys(node, {"distribution", "value"}, "field of a fixed distribution");
    const JsonNode value = node.at("value");
    for (int i = 0; i < n; ++i) out[i] = Distribution::MakeFixed(scale * Component(value, i, n));
  } else {
    kind_node.Fail("unknown distribution " + Quoted(kind), SuggestKey(kind, kKinds));
  }
  return out;
}

// One key of a source: which parameters it sets, how many components, and the unit scale.
struct Term {
  std::string_view key;   // in the file: "rotation_deg"
  std::string_view name;  // parameter name part: "rotation"
  int components;
  double scale;  // file unit → internal unit
};

const std::vector<Term> kPoseTerms = {{"rotation_deg", "rotation", 3, kRadPerDeg}, {"translation", "translation", 3, 1.0}};

class SourceReader {
 public:
  explicit SourceReader(ChainModel* model) : model_(model) {
    for (size_t i = 0; i < model->parameters.size(); ++i) index_[model->parameters[i].name] = i;
  }

  // Applies the terms of `node` (every key must be one of `terms` or `extra_keys`) to the parameters
  // "<source>.<prefix><term name>[.x|.y|.z|.u|.v]".
  void Terms(const JsonNode& node, Source source, const std::string& prefix, const std::vector<Term>& terms,
             std::vector<std::string_view> extra_keys = {}) {
    std::vector<std::string_view> allowed = extra_keys;
    for (const Term& t : terms) allowed.push_back(t.key);
    ExpectKeys(node, allowed, "term of " + std::string(SourceKey(source)));
    for (const Term& t : terms) {
      const auto term = node.find(t.key);
      if (!term) continue;
      const auto d = ReadDistribution(*term, t.components, t.scale);
      static const char* kXyz[] = {".x", ".y", ".z"};
      static const char* kUv[] = {".u", ".v"};
      for (int i = 0; i < t.components; ++i) {
        const std::string suffix = t.components == 3 ? kXyz[i] : t.components == 2 ? kUv[i] : "";
        Set(std::string(SourceKey(source)) + "." + prefix + std::string(t.name) + suffix, d[i]);
      }
    }
  }

  // "left" / "right" / "both" sub-objects of a per-eye source; calls read(node, eye) for each eye.
  template <typename Read>
  void PerEye(const JsonNode& node, Read read) {
    const auto both = node.find("both");
    for (int e = 0; e < kNumEyes; ++e) {
      const auto eye = node.find(kEyeNames[e]);
      if (both && eye) eye->Fail("both \"both\" and " + Quoted(kEyeNames[e]) + " are given", "give either \"both\" or \"left\"/\"right\"");
      if (both) read(*both, e);
      if (eye) read(*eye, e);
    }
  }

  void Set(const std::string& name, const Distribution& d) {
    const auto it = index_.find(name);
    VSTCAL_CHECK(it != index_.end(), "no parameter " + name);
    model_->parameters[it->second].distribution = d;
  }
  ChainParameter& parameter(const std::string& name) { return model_->parameters[index_.at(name)]; }
  ChainModel& model() { return *model_; }

 private:
  ChainModel* model_;
  std::map<std::string, size_t> index_;
};

// σ's per lens parameter, or a calibration covariance turned into a mixing matrix over standard
// normals: δ = V Λ^½ z with Σ = V Λ Vᵀ over the parameters the covariance names.
void ReadIntrinsics(const JsonNode& node, int eye, const std::optional<ParameterCovariance>& from_camera, SourceReader* r) {
  const std::string prefix = std::string(kEyeNames[eye]) + ".";
  std::vector<Term> terms;
  for (const std::string_view p : VirtualLens::kParamNames) terms.push_back({p, p, 1, 1.0});
  const auto cov_node = node.find("covariance");
  if (!cov_node) {
    r->Terms(node, Source::kCameraIntrinsic, prefix, terms);
    return;
  }
  ExpectKeys(node, {"covariance"}, "term of camera_intrinsic with a covariance");
  ParameterCovariance cov;
  if (cov_node->json().is_string()) {
    if (cov_node->String() != "camera") cov_node->Fail("unknown value " + Quoted(cov_node->String()), "write \"camera\" (the camera file's covariance) or an object {\"parameters\", \"matrix\"}");
    if (!from_camera) {
      cov_node->Fail("the " + std::string(kEyeNames[eye]) + " camera has no covariance",
                     "reference a camera@1 file that has \"covariance\", or give σ's per parameter");
    }
    cov = *from_camera;
  } else {
    cov = io::ReadCovariance(*cov_node, r->model().geometry.cameras[eye], std::nullopt);  // inline: no poses to name
  }
  std::vector<int> rows;  // lens index of each covariance row used
  std::vector<int> used;  // covariance index
  for (size_t i = 0; i < cov.parameters.size(); ++i) {
    for (int k = 0; k < kNumLensParams; ++k) {
      if (VirtualLens::kParamNames[k] == cov.parameters[i]) rows.push_back(k), used.push_back(static_cast<int>(i));
    }
  }
  if (rows.empty()) {
    cov_node->Fail("names none of the lens parameters", "name them as fx, fy, cx, cy, s, k1, k2, p1, p2, k3");
  }
  const int m = static_cast<int>(rows.size());
  Eigen::MatrixXd sub(m, m);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) sub(a, b) = cov.matrix(used[a], used[b]);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(sub);
  const double largest = std::max(0.0, eig.eigenvalues().maxCoeff());
  if (eig.eigenvalues().minCoeff() < -1e-9 * largest) {
    cov_node->Fail("is not positive semi-definite (smallest eigenvalue " + io::OrderedJson(eig.eigenvalues().minCoeff()).dump() + ")",
                   "give a valid covariance matrix");
  }
  auto& mixing = r->model().intrinsic_mixing[eye];
  mixing.setZero();
  for (int j = 0; j < m; ++j) {
    const double root = std::sqrt(std::max(0.0, eig.eigenvalues()(j)));
    for (int a = 0; a < m; ++a) mixing(rows[a], j) = eig.eigenvectors()(a, j) * root;
  }
  // θ's slots of this eye now hold the standard normals z_j of the principal directions.
  for (int j = 0; j < kNumLensParams; ++j) {
    ChainParameter& p = r->parameter("camera_intrinsic." + prefix + std::string(VirtualLens::kParamNames[j]));
    p.name = "camera_intrinsic." + prefix + "mode[" + std::to_string(j) + "]";
    p.file_unit = "1";
    p.distribution = j < m ? Distribution::MakeNormal(0, 1) : Distribution::MakeFixed(0);
  }
}

}  // namespace

std::vector<Eigen::Vector3d> ReadFiducialLayout(const JsonNode& sources) {
  const auto voa = sources.find("virtual_object_alignment");
  if (!voa) return {};
  voa->ExpectObject();
  const auto layout = voa->find("fiducials");
  if (!layout) return {};
  std::vector<Eigen::Vector3d> fiducials;
  const size_t n = layout->ArraySize();
  for (size_t i = 0; i < n; ++i) fiducials.push_back(layout->at(i).Vector<3>());
  if (n < 3) layout->Fail("has " + std::to_string(n) + " fiducials", "give at least 3, not all on one line");
  if (!RegistrationFrame::For(fiducials)) layout->Fail("the fiducials lie on one line (the rotation about it is free)", "give at least 3 fiducials not on one line");
  return fiducials;
}

void ReadSources(const JsonNode& sources, const std::array<std::optional<ParameterCovariance>, kNumEyes>& camera_covariance,
                 ChainModel* model) {
  const std::vector<std::string_view> keys(kSourceKeys.begin(), kSourceKeys.end());
  ExpectKeys(sources, keys, "error source");
  SourceReader r(model);
  if (auto n = sources.find("tracker_alignment")) r.Terms(*n, Source::kTrackerAlignment, "", kPoseTerms);
  if (auto n = sources.find("tracking")) {
    std::vector<Term> terms = kPoseTerms;
    terms.push_back({"latency_s", "latency", 1, 1.0});
    r.Terms(*n, Source::kTracking, "", terms);
  }
  if (auto n = sources.find("camera_extrinsic")) {
    r.Terms(*n, Source::kCameraExtrinsic, "", {{"baseline", "baseline", 1, 1.0}}, {"left", "right", "both", "rig"});
    if (auto rig = n->find("rig")) r.Terms(*rig, Source::kCameraExtrinsic, "rig.", kPoseTerms);
    r.PerEye(*n, [&](const JsonNode& eye, int e) {
      r.Terms(eye, Source::kCameraExtrinsic, std::string(kEyeNames[e]) + ".", kPoseTerms);
    });
  }
  if (auto n = sources.find("camera_intrinsic")) {
    ExpectKeys(*n, {"left", "right", "both"}, "term of camera_intrinsic");
    r.PerEye(*n, [&](const JsonNode& eye, int e) { ReadIntrinsics(eye, e, camera_covariance[e], &r); });
  }
  if (auto n = sources.find("rendering")) {
    r.Terms(*n, Source::kRendering, "", {{"latency_s", "latency", 1, 1.0}}, {"disparity_px"});
    if (auto d = n->find("disparity_px")) {
      const Distribution disparity = ReadDistribution(*d, 1, 1.0)[0];
      for (const TestPoint& tp : model->geometry.test_points) r.Set("rendering.disparity[" + tp.name + "]", disparity);
    }
  }
  if (auto n = sources.find("display")) {
    r.Terms(*n, Source::kDisplay, "", {{"ipd", "ipd", 1, 1.0}, {"latency_s", "latency", 1, 1.0}}, {"left", "right", "both"});
    r.PerEye(*n, [&](const JsonNode& eye, int e) {
      r.Terms(eye, Source::kDisplay, std::string(kEyeNames[e]) + ".",
              {{"eyepoint", "eyepoint", 3, 1.0}, {"screen_shift_px", "screen_shift", 2, 1.0},
               {"magnification", "magnification", 1, 1.0}, {"lens_k1", "lens_k1", 1, 1.0}});
    });
  }
  if (auto n = sources.find("virtual_object_alignment")) {
    if (model->fiducials_in_object.empty()) {
      r.Terms(*n, Source::kVirtualObjectAlignment, "", kPoseTerms);
    } else {
      ExpectKeys(*n, {"fiducials", "fle_rms"}, "term of virtual_object_alignment with fiducials (the pose terms "
                                               "rotation_deg/translation do not mix with them)");
      // FLE is the RMS of the 3-D localization error: σ = FLE/√3 on each axis (Fitzpatrick 1998).
      const double fle = n->at("fle_rms").NonNegativeNumber();
      for (size_t k = 0; k < model->fiducials_in_object.size(); ++k) {
        for (const char* axis : {".x", ".y", ".z"}) {
          r.Set("virtual_object_alignment.fiducial[" + std::to_string(k) + "]" + axis,
                Distribution::MakeNormal(0, fle / std::sqrt(3.0)));
        }
      }
    }
  }
}

}  // namespace vstcal::errsim
