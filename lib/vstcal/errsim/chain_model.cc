#include "vstcal/errsim/chain_model.h"

#include "vstcal/core/error.h"

namespace vstcal {

double ChainGeometry::CameraBaseline() const {
  return (camera_from_hmd[1].inverse().t - camera_from_hmd[0].inverse().t).norm();
}

Eigen::Vector3d ChainGeometry::CameraCentre() const {
  return 0.5 * (camera_from_hmd[0].inverse().t + camera_from_hmd[1].inverse().t);
}

Distribution Scaled(const Distribution& d, double s) {
  VSTCAL_CHECK(s >= 0, "a scale factor must not be negative");
  if (const auto* n = std::get_if<Distribution::Normal>(&d.form())) return Distribution::MakeNormal(s * n->mean, s * n->sigma);
  if (const auto* u = std::get_if<Distribution::Uniform>(&d.form())) return Distribution::MakeUniform(s * u->lo, s * u->hi);
  return Distribution::MakeFixed(s * d.Mean());
}

ChainModel ChainModel::WithZeroErrors(ChainGeometry geometry, std::vector<Eigen::Vector3d> fiducials_in_object,
                                      const std::optional<std::array<AnyLensModel, kNumEyes>>& renderer_lens) {
  ChainModel m;
  ChainShape shape;
  for (const ChainTestPoint& tp : geometry.test_points) shape.test_points.push_back(tp.name);
  shape.fiducials = fiducials_in_object.size();
  shape.length_unit = geometry.length_unit;
  for (int e = 0; e < kNumEyes; ++e) {
    const Camera& camera = geometry.cameras[e];
    shape.renderer_lens[e] = renderer_lens ? (*renderer_lens)[e] : camera.model;
    // Every lens model extends the smaller ones' parameter layout ([fx … s, k1, k2, p1, p2, k3, k4 …]):
    // the true parameters, padded with zeros, are the renderer's nominal ones.
    const int n = LensModelNumParams(shape.renderer_lens[e]);
    VSTCAL_CHECK(n >= static_cast<int>(camera.params.size()), "the renderer's lens model must hold the camera's");
    m.renderer[e] = camera;
    m.renderer[e].model = shape.renderer_lens[e];
    m.renderer[e].params.resize(n, 0.0);
    m.renderer_valid_radius2[e] = m.renderer[e].ValidRadiusSquared();
    m.intrinsic_mixing[e] = Eigen::MatrixXd::Identity(n, n);
  }
  m.layout = ParameterLayout(shape);
  m.geometry = std::move(geometry);
  m.fiducials_in_object = std::move(fiducials_in_object);
  for (const SlotInfo& slot : m.layout.slots()) {
    m.parameters.push_back({slot, Declaration(slot.term).source, Distribution::MakeFixed(0)});
  }
  return m;
}

ChainParameter* ChainModel::Find(const std::string& name) {
  for (ChainParameter& p : parameters) {
    if (p.name() == name) return &p;
  }
  return nullptr;
}

std::vector<double> ChainModel::MeanTheta() const {
  std::vector<double> theta(parameters.size());
  for (size_t i = 0; i < parameters.size(); ++i) theta[i] = parameters[i].distribution.Mean();
  return theta;
}

ChainModel ChainModel::WithSources(const std::array<bool, kNumSources>& active) const {
  ChainModel m = *this;
  for (ChainParameter& p : m.parameters) {
    if (!active[static_cast<int>(p.source)]) p.distribution = Distribution::MakeFixed(0);
  }
  return m;
}

ChainModel ChainModel::WithSourceScaled(Source source, double factor) const {
  ChainModel m = *this;
  for (ChainParameter& p : m.parameters) {
    if (p.source == source) p.distribution = Scaled(p.distribution, factor);
  }
  return m;
}

bool ChainModel::SourceActive(Source source) const {
  for (const ChainParameter& p : parameters) {
    if (p.source == source && !(p.distribution.IsConstant() && p.distribution.Mean() == 0)) return true;
  }
  return false;
}

}  // namespace vstcal
