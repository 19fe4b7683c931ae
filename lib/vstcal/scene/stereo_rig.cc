#include "vstcal/scene/stereo_rig.h"

#include <algorithm>
#include <cmath>

#include "vstcal/core/error.h"

namespace vstcal {

const std::array<std::string, 6>& RelativePoseTangentNames() {
  static const std::array<std::string, 6> kNames = {"right_from_left.rx", "right_from_left.ry", "right_from_left.rz",
                                                    "right_from_left.tx", "right_from_left.ty", "right_from_left.tz"};
  return kNames;
}

std::string JointCovarianceName(int eye, std::string_view lens_parameter) {
  return std::string(eye == 0 ? "left." : "right.").append(lens_parameter);
}

namespace {

// Σ over (ω, ρ) in RelativePoseTangentNames() order, whatever order the file lists them in.
Eigen::Matrix<double, 6, 6> TangentCovariance(const ParameterCovariance& c) {
  Eigen::Matrix<double, 6, 6> m;
  const auto& names = RelativePoseTangentNames();
  for (int r = 0; r < 6; ++r) {
    for (int k = 0; k < 6; ++k) {
      const auto i = c.Find(names[r]), j = c.Find(names[k]);
      VSTCAL_CHECK(i && j, "a rig's covariance names every tangent of right_from_left");
      m(r, k) = c.matrix(static_cast<Eigen::Index>(*i), static_cast<Eigen::Index>(*j));
    }
  }
  return m;
}

}  // namespace

std::optional<double> BaselineSigma(const StereoRig& rig) {
  if (!rig.covariance) return std::nullopt;
  const Eigen::Vector3d direction = rig.right_from_left.t.normalized();
  const Eigen::Matrix3d rho = TangentCovariance(*rig.covariance).bottomRightCorner<3, 3>();
  return std::sqrt(std::max(0.0, direction.dot(rho * direction)));
}

std::optional<Eigen::Vector3d> RelativeRotationSigma(const StereoRig& rig) {
  if (!rig.covariance) return std::nullopt;
  return TangentCovariance(*rig.covariance).diagonal().head<3>().cwiseMax(0.0).cwiseSqrt();
}

CalibratedCamera IntrinsicsOnly(const CalibratedCamera& camera) {
  CalibratedCamera c;
  c.name = camera.name;
  c.camera = camera.camera;
  c.length_unit = camera.length_unit;
  c.method = camera.method;
  if (camera.covariance) {
    const auto lens = LensModelParamNames(camera.camera.model);
    std::vector<size_t> keep;
    for (size_t i = 0; i < camera.covariance->parameters.size(); ++i) {
      if (std::find(lens.begin(), lens.end(), camera.covariance->parameters[i]) != lens.end()) keep.push_back(i);
    }
    if (!keep.empty()) {
      ParameterCovariance marginal;
      marginal.matrix.resize(static_cast<Eigen::Index>(keep.size()), static_cast<Eigen::Index>(keep.size()));
      for (size_t r = 0; r < keep.size(); ++r) {
        marginal.parameters.push_back(camera.covariance->parameters[keep[r]]);
        for (size_t k = 0; k < keep.size(); ++k) {
          marginal.matrix(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) =
              camera.covariance->matrix(static_cast<Eigen::Index>(keep[r]), static_cast<Eigen::Index>(keep[k]));
        }
      }
      c.covariance = std::move(marginal);
    }
  }
  return c;
}

void CheckBaseline(const Rigid3d& right_from_left, std::string_view where) {
  const double b = right_from_left.t.norm();
  if (!std::isfinite(b)) {
    throw InputError(std::string(where) +
                     ": the baseline is too large to compute with (its square overflows); check the translation of "
                     "right_from_left and its unit");
  }
  if (!(b > 0)) {
    throw InputError(std::string(where) +
                     ": the two cameras coincide (baseline 0): a stereo rig needs its cameras apart; check the "
                     "translation of right_from_left");
  }
}

StereoRig AssembleRig(const AssembleInput& input) {
  StereoRig rig;
  rig.method = "assembled";
  if (input.right_from_left) {
    rig.right_from_left = *input.right_from_left;
    rig.length_unit = input.length_unit;
  } else {
    const auto& l = input.left.camera_from_world;
    const auto& r = input.right.camera_from_world;
    if (!l || !r) {
      const std::string& unposed = l ? input.right_name : input.left_name;
      throw InputError(unposed +
                       ": camera_from_world: absent, so right_from_left cannot be derived from the cameras' poses; "
                       "give right_from_left (its rotation and translation), or two cameras posed in one world frame");
    }
    if (input.left.length_unit != input.right.length_unit) {
      throw InputError(input.right_name + ": length_unit: \"" + std::string(LengthUnitName(input.right.length_unit)) +
                       "\", but " + input.left_name + " is in \"" + std::string(LengthUnitName(input.left.length_unit)) +
                       "\": their poses cannot be composed; give both cameras in one length unit");
    }
    rig.right_from_left = *r * l->inverse();
    rig.length_unit = input.left.length_unit;
  }
  CheckBaseline(rig.right_from_left, input.right_from_left ? "right_from_left" : input.right_name + " vs " + input.left_name);
  rig.left = IntrinsicsOnly(input.left);
  rig.right = IntrinsicsOnly(input.right);
  for (CalibratedCamera* c : {&rig.left, &rig.right}) c->length_unit = rig.length_unit;
  if (rig.left.name.empty()) rig.left.name = "left";
  if (rig.right.name.empty()) rig.right.name = "right";
  return rig;
}

}  // namespace vstcal
