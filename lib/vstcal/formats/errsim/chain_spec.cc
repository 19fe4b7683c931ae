#include "vstcal/formats/errsim/chain_spec.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "vstcal/core/error.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/geometry/linalg.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/reader_common.h"
#include "vstcal/scene/stereo_rig.h"

namespace vstcal {
namespace {


std::string PointField(size_t k) { return "test_points[" + std::to_string(k) + "].world"; }

// Every test point must be seen by both cameras: in front, within the lens's valid domain and
// inside the image.
void CheckTestPointsVisible(const ChainSpec& spec, const ChainGeometry& g) {
  const Rigid3d hmd_from_world = g.hmd_from_tracker * g.tracker_from_world;
  // Once per camera: each is a search over the image plane (tens of thousands of Jacobians).
  std::array<double, kNumEyes> valid_r2;
  for (int e = 0; e < kNumEyes; ++e) valid_r2[e] = g.cameras[e].ValidRadiusSquared();
  for (size_t k = 0; k < g.test_points.size(); ++k) {
    for (int e = 0; e < kNumEyes; ++e) {
      const Camera& camera = g.cameras[e];
      const Eigen::Vector3d x = g.camera_from_hmd[e] * (hmd_from_world * g.test_points[k].point_in_world);
      const std::string eye(kEyeNames[e]);
      const auto q = camera.Project(x);
      if (!q) {
        FailField(spec.file, PointField(k),
                      "lies behind the " + eye + " camera (depth " + MessageNumber(x.z()) + " " + std::string(LengthUnitName(g.length_unit)) + ")",
                      "move the point in front of both cameras, or check frames (x_a = a_from_b · x_b)");
      }
      const double r2 = (x.x() * x.x() + x.y() * x.y()) / (x.z() * x.z());
      if (!(r2 <= valid_r2[e])) {
        FailField(spec.file, PointField(k),
                      "lies " + MessageNumber(RadToDeg(std::atan(std::sqrt(r2)))) + "° off the " + eye +
                          " camera's axis, outside its lens model's valid domain (the distortion folds over beyond " +
                          MessageNumber(RadToDeg(std::atan(std::sqrt(valid_r2[e])))) + "°)",
                      "move the point into both cameras' field of view");
      }
      if (!camera.InImage(*q)) {
        FailField(spec.file, PointField(k),
                      "projects outside the " + eye + " image, at (" + MessageNumber(q->x()) + ", " + MessageNumber(q->y()) + ") px in " +
                          std::to_string(camera.image_size.width) + "×" + std::to_string(camera.image_size.height),
                      "move the point into both cameras' field of view");
      }
    }
  }
}

Distribution ToInternal(const DistributionSpec& d, size_t i, double scale) {
  switch (d.kind) {
    case DistributionSpec::Kind::kNormal: return Distribution::MakeNormal(scale * d.first[i], scale * d.second[i]);
    case DistributionSpec::Kind::kUniform: return Distribution::MakeUniform(scale * d.first[i], scale * d.second[i]);
    case DistributionSpec::Kind::kFixed: return Distribution::MakeFixed(scale * d.first[i]);
  }
  return Distribution::MakeFixed(0);
}

// The eyes whose slots take a term's distribution: a shared term's is drawn once, in the left
// eye's slots, and the right eye reads them (Couple).
std::vector<int> EyesOf(const std::string& eye_key) {
  if (eye_key == "left") return {0};
  if (eye_key == "right") return {1};
  if (eye_key == "both") return {0, 1};
  return {0};
}

// The left and right slots of component i of a per-eye term (for kLens, of lens parameter `key`).
std::array<int, kNumEyes> EyeSlots(const ChainModel& model, Term term, const std::string& key, int i) {
  std::array<int, kNumEyes> slots{};
  for (int e = 0; e < kNumEyes; ++e) {
    int at = i;
    if (term == Term::kLens) {
      const auto names = LensModelParamNames(model.renderer[e].model);
      at = static_cast<int>(std::find(names.begin(), names.end(), key) - names.begin());
    }
    slots[e] = model.layout.Offset(term, e) + at;
  }
  return slots;
}

int ComponentsOf(const ChainModel& model, Term term) {
  return term == Term::kLens ? 1 : model.layout.Size(term, 0);
}

// A shared term: the right eye reads the left eye's draw (its own slots stay fixed at 0).
void Share(const TermSpec& t, ChainModel* model) {
  for (int i = 0; i < ComponentsOf(*model, t.term); ++i) {
    const auto slots = EyeSlots(*model, t.term, t.key, i);
    model->couplings.push_back({slots[0], slots[1], 1.0});  // from the left eye's slot to the right's
  }
}

// Correlation ρ between the eyes' normal draws (L ~ N(μ_L, σ_L²), R ~ N(μ_R, σ_R²)): R = α·L + R'
// with α = ρ·σ_R/σ_L and R' ~ N(μ_R − α·μ_L, σ_R²·(1 − ρ²)) independent of L, so that
// cov(L, R) = α·σ_L² = ρ·σ_L·σ_R and var R = α²σ_L² + σ_R²(1 − ρ²) = σ_R². A component with a
// σ of 0 has no correlation to give and stays independent.
void Correlate(const CorrelationSpec& c, ChainModel* model) {
  for (int i = 0; i < ComponentsOf(*model, c.term); ++i) {
    const auto slots = EyeSlots(*model, c.term, c.key, i);
    const auto* left = std::get_if<Distribution::Normal>(&model->parameters[slots[0]].distribution.form());
    Distribution& right_distribution = model->parameters[slots[1]].distribution;
    const auto* right = std::get_if<Distribution::Normal>(&right_distribution.form());
    VSTCAL_CHECK(left && right, "a correlation between distributions that are not normal");  // the reader refuses them
    const double rho = c.rho[static_cast<size_t>(i) % c.rho.size()];
    if (!(left->sigma > 0 && right->sigma > 0)) continue;
    const double alpha = rho * right->sigma / left->sigma;
    right_distribution = Distribution::MakeNormal(right->mean - alpha * left->mean, right->sigma * std::sqrt(1 - rho * rho));
    model->couplings.push_back({slots[0], slots[1], alpha});
  }
}

// V Λ^½ of Σ = V Λ Vᵀ: column j the j-th principal direction scaled by its σ, so that V Λ^½ z
// has covariance Σ for standard normals z. InputError at `field` unless Σ is positive semi-definite.
Eigen::MatrixXd PrincipalRoots(const Eigen::MatrixXd& covariance, const ChainSpec& spec, const std::string& field,
                               const std::string& what) {
  const SymmetricEigen eig = DecomposeSymmetric(covariance);
  const double largest = std::max(0.0, eig.values.maxCoeff());
  if (eig.values.minCoeff() < -1e-9 * largest) {
    FailField(spec.file, field, what + " is not positive semi-definite", "give a valid covariance matrix");
  }
  Eigen::MatrixXd roots = eig.vectors;
  for (int j = 0; j < roots.cols(); ++j) roots.col(j) *= std::sqrt(std::max(0.0, eig.values(j)));
  return roots;
}

// The right eye's camera_extrinsic from a rig covariance over right_from_left's tangent (ω, ρ):
// θ's right rotation and translation slots hold six standard normals, mixed by V Λ^½.
void ApplyExtrinsicCovariance(const ChainSpec& spec, const ParameterCovariance& cov, ChainModel* model) {
  const auto& names = RelativePoseTangentNames();
  Eigen::MatrixXd ordered(6, 6);
  std::array<int, 6> index{};
  for (int i = 0; i < 6; ++i) {
    const auto it = std::find(cov.parameters.begin(), cov.parameters.end(), names[i]);
    VSTCAL_CHECK(it != cov.parameters.end(), "a rig covariance without " + names[i]);  // the reader requires all six
    index[i] = static_cast<int>(it - cov.parameters.begin());
  }
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) ordered(a, b) = cov.matrix(index[a], index[b]);
  constexpr int kRight = 1;
  model->extrinsic_mixing[kRight] = PrincipalRoots(ordered, spec, "sources.camera_extrinsic.right.covariance", "the covariance");
  int j = 0;
  for (const Term term : {Term::kCameraRotation, Term::kCameraTranslation}) {
    const int offset = model->layout.Offset(term, kRight);
    for (int i = 0; i < model->layout.Size(term, kRight); ++i, ++j) {
      ChainParameter& p = model->parameters[offset + i];
      p.slot.name = "camera_extrinsic.right.mode[" + std::to_string(j) + "]";
      p.slot.file_unit = FileUnit(TermUnit::kRelative, LengthUnit::kMillimetre, 0);  // "1"
      p.slot.file_per_internal = 1;
      p.distribution = Distribution::MakeNormal(0, 1);
    }
  }
}

// A measured pose covariance (a hand-eye X or Z block) as the mixing of a rotation and a
// translation term that exist once: θ's six slots hold standard normals z, the pose error is
// (ω, ρ) = V Λ^½ z (docs/math/vst-chain.md#measured-chain derives why the handeye tangent needs
// no conversion for either).
void ApplyPoseCovariance(const ChainSpec& spec, const ParameterCovariance& cov, Term rotation, Term translation,
                         const std::string& field, ChainModel::Matrix6d* mixing, ChainModel* model) {
  *mixing = PrincipalRoots(cov.matrix, spec, field, "the covariance");
  const TermDecl& d = Declaration(rotation);
  std::string prefix(SourceKey(d.source));
  if (!d.group.empty()) prefix.append(".").append(d.group);
  int j = 0;
  for (const Term term : {rotation, translation}) {
    const int offset = model->layout.Offset(term);
    for (int i = 0; i < model->layout.Size(term); ++i, ++j) {
      ChainParameter& p = model->parameters[offset + i];
      p.slot.name = prefix + ".mode[" + std::to_string(j) + "]";
      p.slot.file_unit = FileUnit(TermUnit::kRelative, LengthUnit::kMillimetre, 0);  // "1"
      p.slot.file_per_internal = 1;
      p.distribution = Distribution::MakeNormal(0, 1);
    }
  }
}

// Where each measurement's distributions come from, as the report names them.
DistributionOrigin HandEyeOrigin(const ChainSpec& spec) { return {spec.handeye->file, "vstcal/handeye@1"}; }

DistributionOrigin TermOrigin(const ChainSpec& spec, const TermSpec& t) {
  if (t.from.empty()) return {};
  if (t.from == "tracker_noise") return {spec.tracker_noise->file, "vstcal/tracker-noise@1"};
  return HandEyeOrigin(spec);
}

// A camera's covariance: the rig's (stereo@1), the camera file's (camera@1), or typed inline.
DistributionOrigin CameraOrigin(const ChainSpec& spec, int eye) {
  if (spec.rig) return {spec.rig->file, "vstcal/stereo@1"};
  if (!spec.cameras[eye].file.empty()) return {spec.cameras[eye].file, "vstcal/camera@1"};
  return {};
}

void SetOrigin(ChainModel* model, Term term, int eye, const DistributionOrigin& origin) {
  const int offset = model->layout.Offset(term, eye);
  for (int i = 0; i < model->layout.Size(term, eye); ++i) model->parameters[offset + i].origin = origin;
}

// The covariance's lens block as a mixing matrix over standard normals: δ = V Λ^½ z with
// Σ = V Λ Vᵀ over the lens parameters it names, placed in the renderer's rows.
void ApplyCovariance(const ChainSpec& spec, const ParameterCovariance& cov, int eye, ChainModel* model) {
  const auto names = LensModelParamNames(model->renderer[eye].model);
  std::vector<int> rows, used;
  for (size_t i = 0; i < cov.parameters.size(); ++i) {
    const auto it = std::find(names.begin(), names.end(), cov.parameters[i]);
    if (it != names.end()) rows.push_back(static_cast<int>(it - names.begin())), used.push_back(static_cast<int>(i));
  }
  const int m = static_cast<int>(rows.size());
  Eigen::MatrixXd sub(m, m);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) sub(a, b) = cov.matrix(used[a], used[b]);
  const Eigen::MatrixXd roots = PrincipalRoots(sub, spec, "sources.camera_intrinsic",
                                               "the " + std::string(kEyeNames[eye]) + " covariance's lens block");
  Eigen::MatrixXd& mixing = model->intrinsic_mixing[eye];
  mixing.setZero();
  for (int j = 0; j < m; ++j) {
    for (int a = 0; a < m; ++a) mixing(rows[a], j) = roots(a, j);
  }
  // θ's lens slots of this eye now hold the standard normals z_j of the principal directions.
  const int offset = model->layout.Offset(Term::kLens, eye);
  for (int j = 0; j < model->layout.Size(Term::kLens, eye); ++j) {
    ChainParameter& p = model->parameters[offset + j];
    p.slot.name = std::string("camera_intrinsic.").append(kEyeNames[eye]).append(".mode[").append(std::to_string(j)).append("]");
    p.slot.file_unit = FileUnit(TermUnit::kRelative, LengthUnit::kMillimetre, 0);  // "1" (GCC 12 -Wrestrict misfires on = "1")
    p.distribution = j < m ? Distribution::MakeNormal(0, 1) : Distribution::MakeFixed(0);
  }
}

// A rig's joint covariance as one correlated draw (docs/math/vst-chain.md#joint-draw). Its
// parameters in a fixed order — the left lens, the right lens (each in the renderer's layout),
// then right_from_left's (ω, ρ) — and Σ = L D Lᵀ in that order (L unit lower triangular, no
// pivoting): slot k of θ holds N(0, D_k), the variance of parameter k given the ones before it,
// and parameter j reads θ[j] + Σ_k<j L(j, k)·θ[k]. So the part of the right camera's pose error
// that the lens errors explain moves with camera_intrinsic (switched off or scaled with it), and
// camera_extrinsic keeps what remains; a parameter the ones before it determine (D_k = 0, e.g.
// perfectly correlated cx's) draws nothing of its own.
void ApplyJointCovariance(const ChainSpec& spec, ChainModel* model) {
  const ParameterCovariance& cov = spec.joint_covariance->covariance;
  struct Entry {
    int slot;
    size_t index;  // in cov
  };
  std::vector<Entry> order;
  for (int e = 0; e < kNumEyes; ++e) {
    const auto names = LensModelParamNames(model->renderer[e].model);
    for (size_t i = 0; i < names.size(); ++i) {
      if (const auto at = cov.Find(JointCovarianceName(e, names[i]))) order.push_back({model->layout.Offset(Term::kLens, e) + static_cast<int>(i), *at});
    }
  }
  constexpr int kRight = 1;
  const auto& tangents = RelativePoseTangentNames();
  for (int i = 0; i < 6; ++i) {
    const Term term = i < 3 ? Term::kCameraRotation : Term::kCameraTranslation;
    if (const auto at = cov.Find(tangents[i])) order.push_back({model->layout.Offset(term, kRight) + i % 3, *at});
  }
  const int n = static_cast<int>(order.size());
  Eigen::MatrixXd sigma(n, n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) sigma(a, b) = cov.matrix(order[a].index, order[b].index);
  // LDLᵀ by columns. A pivot below the rounding of its own diagonal is 0: the parameter is a
  // combination of the ones before it, and (Σ being PSD) so is its covariance with every later one.
  Eigen::MatrixXd L = Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd d(n);
  for (int k = 0; k < n; ++k) {
    double dk = sigma(k, k);
    for (int m = 0; m < k; ++m) dk -= L(k, m) * L(k, m) * d(m);
    if (dk < -1e-9 * std::max(sigma(k, k), 0.0) - 1e-300) {
      FailField(spec.file, "joint_covariance.matrix", "is not positive semi-definite (pivot " + MessageNumber(dk) + " at " + cov.parameters[order[k].index] + ")",
                "give a valid covariance matrix");
    }
    d(k) = dk > 1e-12 * sigma(k, k) ? dk : 0.0;
    for (int j = k + 1; j < n; ++j) {
      double v = sigma(j, k);
      for (int m = 0; m < k; ++m) v -= L(j, m) * L(k, m) * d(m);
      L(j, k) = d(k) > 0 ? v / d(k) : 0.0;
    }
  }
  const DistributionOrigin origin = spec.joint_covariance->from_rig ? DistributionOrigin{spec.rig->file, "vstcal/stereo@1"} : DistributionOrigin{};
  for (int k = 0; k < n; ++k) {
    ChainParameter& p = model->parameters[order[k].slot];
    p.distribution = d(k) > 0 ? Distribution::MakeNormal(0, std::sqrt(d(k))) : Distribution::MakeFixed(0);
    p.origin = origin;
    for (int j = k + 1; j < n; ++j) {
      if (L(j, k) != 0) model->couplings.push_back({order[k].slot, order[j].slot, L(j, k)});
    }
  }
}

}  // namespace

double DefaultVirtualImageDistance(LengthUnit unit) { return 1.5 / MetresPer(unit); }

std::array<AnyLensModel, kNumEyes> ChainSpec::RendererLenses() const {
  std::array<AnyLensModel, kNumEyes> out;
  for (int e = 0; e < kNumEyes; ++e) {
    int needed = LensModelNumParams(cameras[e].camera.model);
    for (const TermSpec& t : terms) {
      if (t.term != Term::kLens || (t.eye_key != "both" && t.eye_key != "shared" && t.eye_key != kEyeNames[e])) continue;
      ForEachLensModel([&](auto model) {
        const auto& names = decltype(model)::kParamNames;
        const auto it = std::find(names.begin(), names.end(), t.key);
        if (it != names.end()) needed = std::max(needed, static_cast<int>(it - names.begin()) + 1);
      });
    }
    // The smallest model with that many parameters that extends the camera's (the variant lists
    // a family's models by size; a fisheye's renderer stays a fisheye). None: the camera's own,
    // whose names then refuse the term.
    bool found = false;
    out[e] = cameras[e].camera.model;
    ForEachLensModel([&](auto model) {
      if (!found && LensModelExtends(model, cameras[e].camera.model) && decltype(model)::kNumParams >= needed) {
        out[e] = model, found = true;
      }
    });
  }
  return out;
}

ChainModel BuildChainModel(const ChainSpec& spec) {
  ChainGeometry g;
  g.length_unit = spec.length_unit;
  g.tracker_from_world = spec.tracker_from_world.value;
  g.hmd_from_tracker = spec.hmd_from_tracker.value;
  for (int e = 0; e < kNumEyes; ++e) {
    g.camera_from_hmd[e] = spec.camera_from_hmd[e].value;
    g.cameras[e] = spec.cameras[e].camera;
  }
  g.world_from_virtual = spec.world_from_virtual.value;
  g.world_from_object = spec.world_from_object.value;
  g.display.ipd = spec.ipd;
  g.display.eye_centre_in_hmd = spec.eye_centre;
  g.display.inverse_image_distance = spec.virtual_image_distance > 0 ? 1.0 / spec.virtual_image_distance : 0.0;
  for (int e = 0; e < kNumEyes; ++e) {
    // The camera's image, W × H px, spans the display's field of view: f = (W/2)/tan(φ_h/2); the
    // vertical by its own angle, else with the camera's pixel aspect fy/fx.
    const auto& fov = spec.display_field_of_view[e];
    if (!fov) continue;
    const Camera& camera = spec.cameras[e].camera;
    const double fx = 0.5 * camera.image_size.width / std::tan(0.5 * DegToRad(fov->horizontal_deg));
    const double fy = fov->vertical_deg ? 0.5 * camera.image_size.height / std::tan(0.5 * DegToRad(*fov->vertical_deg))
                                        : fx * camera.params[intrinsic::kFy] / camera.params[intrinsic::kFx];
    g.display.focal_px[e] = Eigen::Vector2d(fx, fy);
  }
  g.head_angular_velocity = DegToRad(1.0) * spec.angular_velocity_deg_s;
  g.head_linear_velocity = spec.linear_velocity;
  g.test_points = spec.test_points;
  CheckTestPointsVisible(spec, g);

  ChainModel model = ChainModel::WithZeroErrors(std::move(g), spec.fiducials, spec.RendererLenses());
  model.samples = spec.samples;
  model.seed = spec.seed;
  if (spec.handeye) {
    for (const std::string& w : spec.handeye->measured.warnings) model.measurement_warnings.push_back(spec.handeye->file + ": " + w);
  }
  for (const TermSpec& t : spec.terms) {
    const TermDecl& d = Declaration(t.term);
    const double scale = 1.0 / FilePerInternal(d.unit);
    for (const int e : EyesOf(t.eye_key)) {
      const int offset = model.layout.Offset(t.term, e), size = model.layout.Size(t.term, e);
      if (t.term == Term::kLens) {
        const auto names = LensModelParamNames(model.renderer[e].model);
        const int i = static_cast<int>(std::find(names.begin(), names.end(), t.key) - names.begin());
        model.parameters[offset + i].distribution = ToInternal(t.distribution, 0, scale);
        model.parameters[offset + i].origin = TermOrigin(spec, t);
        continue;
      }
      const int components = d.components;
      for (int j = 0; j < size; ++j) model.parameters[offset + j].distribution = ToInternal(t.distribution, j % components, scale);
      SetOrigin(&model, t.term, e, TermOrigin(spec, t));
    }
  }
  if (!spec.fiducials.empty()) {
    // FLE is the RMS of the 3-D localization error: σ = FLE/√3 on each axis (Fitzpatrick 1998).
    const int offset = model.layout.Offset(Term::kFiducial), size = model.layout.Size(Term::kFiducial);
    for (int j = 0; j < size; ++j) model.parameters[offset + j].distribution = Distribution::MakeNormal(0, spec.fle_rms / std::sqrt(3.0));
  }
  for (const IntrinsicCovarianceSpec& c : spec.intrinsic_covariances) {
    for (const int e : EyesOf(c.eye_key)) {
      ApplyCovariance(spec, c.from_camera ? *spec.cameras[e].covariance : c.covariance, e, &model);
      if (c.from_camera) SetOrigin(&model, Term::kLens, e, CameraOrigin(spec, e));
    }
  }
  if (spec.extrinsic_covariance) {
    ApplyExtrinsicCovariance(spec, spec.extrinsic_covariance->covariance, &model);
    if (spec.extrinsic_covariance->from_rig) {
      for (const Term term : {Term::kCameraRotation, Term::kCameraTranslation}) SetOrigin(&model, term, 1, {spec.rig->file, "vstcal/stereo@1"});
    }
  }
  // A hand-eye X moves the whole camera head (both eyes: with a rig the right camera is
  // right_from_left · camera_from_hmd.left); Z is the tracker's alignment.
  if (const auto& c = spec.mount_covariance) {
    ApplyPoseCovariance(spec, c->covariance, Term::kRigRotation, Term::kRigTranslation, "sources.camera_extrinsic.rig.covariance",
                        &model.mount_mixing, &model);
    if (c->from_handeye) {
      for (const Term term : {Term::kRigRotation, Term::kRigTranslation}) SetOrigin(&model, term, 0, HandEyeOrigin(spec));
    }
  }
  if (const auto& c = spec.alignment_covariance) {
    ApplyPoseCovariance(spec, c->covariance, Term::kTrackerAlignmentRotation, Term::kTrackerAlignmentTranslation,
                        "sources.tracker_alignment.covariance", &model.tracker_alignment_mixing, &model);
    if (c->from_handeye) {
      for (const Term term : {Term::kTrackerAlignmentRotation, Term::kTrackerAlignmentTranslation}) {
        SetOrigin(&model, term, 0, HandEyeOrigin(spec));
      }
    }
  }
  for (const TermSpec& t : spec.terms) {
    if (t.eye_key == "shared") Share(t, &model);
  }
  for (const CorrelationSpec& c : spec.correlations) Correlate(c, &model);
  if (spec.joint_covariance) ApplyJointCovariance(spec, &model);
  std::sort(model.couplings.begin(), model.couplings.end(), [](const ChainModel::SlotCoupling& a, const ChainModel::SlotCoupling& b) {
    return a.to != b.to ? a.to < b.to : a.from < b.from;
  });
  const ChainEvaluator chain(model);
  for (size_t k = 0; k < chain.num_points(); ++k) {
    if (chain.nominal_undefined(k) != Undefined::kNone) {
      FailField(spec.file, PointField(k),
                    std::string("the error-free chain does not see it (") + UndefinedName(chain.nominal_undefined(k)) + ")",
                    "move the point nearer: the eyes' rays to it must meet");
    }
  }
  return model;
}

}  // namespace vstcal
