#include "vstcal/errsim/chain_model.h"

#include "vstcal/core/error.h"

namespace vstcal::errsim {

double ChainGeometry::CameraBaseline() const {
  const Eigen::Vector3d left = camera_from_hmd[0].inverse().t;
  const Eigen::Vector3d right = camera_from_hmd[1].inverse().t;
  return (right - left).norm();
}

Distribution Scaled(const Distribution& d, double s) {
  VSTCAL_CHECK(s >= 0, "a scale factor must not be negative");
  if (const auto* n = std::get_if<Distribution::Normal>(&d.form())) return Distribution::MakeNormal(s * n->mean, s * n->sigma);
  if (const auto* u = std::get_if<Distribution::Uniform>(&d.form())) return Distribution::MakeUniform(s * u->lo, s * u->hi);
  return Distribution::MakeFixed(s * d.Mean());
}

ParameterLayout ParameterLayout::For(size_t num_test_points, size_t num_fiducials) {
  ParameterLayout l;
  int at = 0;
  l.tracker_alignment = at, at += kTrackerAlignmentSize;
  l.tracking = at, at += kTrackingSize;
  l.camera_extrinsic = at, at += kCameraExtrinsicSize;
  l.camera_intrinsic = at, at += kCameraIntrinsicSize;
  l.rendering = at, at += 1 + static_cast<int>(num_test_points);
  l.display = at, at += kDisplaySize;
  l.virtual_object_alignment = at, at += num_fiducials == 0 ? 6 : 3 * static_cast<int>(num_fiducials);
  l.size = at;
  return l;
}

int ParameterLayout::Begin(Source source) const {
  switch (source) {
    case Source::kTrackerAlignment: return tracker_alignment;
    case Source::kTracking: return tracking;
    case Source::kCameraExtrinsic: return camera_extrinsic;
    case Source::kCameraIntrinsic: return camera_intrinsic;
    case Source::kRendering: return rendering;
    case Source::kDisplay: return display;
    case Source::kVirtualObjectAlignment: return virtual_object_alignment;
  }
  return size;
}

int ParameterLayout::End(Source source) const {
  const int next = static_cast<int>(source) + 1;
  return next == kNumSources ? size : Begin(static_cast<Source>(next));
}

namespace {

constexpr double kDegPerRad = 180.0 / kPi;
constexpr std::array<const char*, 3> kAxes = {"x", "y", "z"};

class ParameterNamer {
 public:
  ParameterNamer(std::vector<ChainParameter>* out, std::string length_unit)
      : out_(out), length_unit_(std::move(length_unit)) {}

  void Add(Source source, const std::string& name, const std::string& unit, double file_per_internal = 1) {
    out_->push_back({std::string(SourceKey(source)) + "." + name, source, Distribution::MakeFixed(0), unit,
                     file_per_internal});
  }
  void Rotation(Source source, const std::string& prefix) {
    for (const char* axis : kAxes) Add(source, prefix + "rotation." + axis, "deg", kDegPerRad);
  }
  void Translation(Source source, const std::string& prefix, const std::string& what = "translation") {
    for (const char* axis : kAxes) Add(source, prefix + what + "." + axis, length_unit_);
  }
  const std::string& length_unit() const { return length_unit_; }

 private:
  std::vector<ChainParameter>* out_;
  std::string length_unit_;
};

}  // namespace

ChainModel ChainModel::WithZeroErrors(ChainGeometry geometry, std::vector<Eigen::Vector3d> fiducials_in_object) {
  ChainModel m;
  m.layout = ParameterLayout::For(geometry.test_points.size(), fiducials_in_object.size());
  m.geometry = std::move(geometry);
  m.fiducials_in_object = std::move(fiducials_in_object);
  for (auto& mixing : m.intrinsic_mixing) mixing.setIdentity();

  ParameterNamer n(&m.parameters, std::string(LengthUnitName(m.geometry.length_unit)));
  n.Rotation(Source::kTrackerAlignment, "");
  n.Translation(Source::kTrackerAlignment, "");
  n.Rotation(Source::kTracking, "");
  n.Translation(Source::kTracking, "");
  n.Add(Source::kTracking, "latency", "s");
  for (const std::string_view eye : kEyeNames) {
    n.Rotation(Source::kCameraExtrinsic, std::string(eye) + ".");
    n.Translation(Source::kCameraExtrinsic, std::string(eye) + ".");
  }
  n.Add(Source::kCameraExtrinsic, "baseline", n.length_unit());
  n.Rotation(Source::kCameraExtrinsic, "rig.");
  n.Translation(Source::kCameraExtrinsic, "rig.");
  for (const std::string_view eye : kEyeNames) {
    for (const std::string_view p : VirtualLens::kParamNames) {
      n.Add(Source::kCameraIntrinsic, std::string(eye) + "." + std::string(p), p[0] == 'f' || p[0] == 'c' || p == "s" ? "px" : "1");
    }
  }
  n.Add(Source::kRendering, "latency", "s");
  for (const TestPoint& tp : m.geometry.test_points) n.Add(Source::kRendering, "disparity[" + tp.name + "]", "px");
  for (const std::string_view eye : kEyeNames) {
    const std::string e = std::string(eye) + ".";
    n.Translation(Source::kDisplay, e, "eyepoint");
    n.Add(Source::kDisplay, e + "screen_shift.u", "px");
    n.Add(Source::kDisplay, e + "screen_shift.v", "px");
    n.Add(Source::kDisplay, e + "magnification", "1");
    n.Add(Source::kDisplay, e + "lens_k1", "1");
  }
  n.Add(Source::kDisplay, "ipd", n.length_unit());
  n.Add(Source::kDisplay, "latency", "s");
  if (m.fiducials_in_object.empty()) {
    n.Rotation(Source::kVirtualObjectAlignment, "");
    n.Translation(Source::kVirtualObjectAlignment, "");
  } else {
    for (size_t k = 0; k < m.fiducials_in_object.size(); ++k) {
      n.Translation(Source::kVirtualObjectAlignment, "", "fiducial[" + std::to_string(k) + "]");
    }
  }
  VSTCAL_CHECK(static_cast<int>(m.parameters.size()) == m.layout.size, "parameter names and layout disagree");
  return m;
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

}  // namespace vstcal::errsim
