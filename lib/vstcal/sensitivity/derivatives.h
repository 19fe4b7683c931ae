// First derivatives of a model's outputs with respect to its parameters, at one point θ.
//
// A templated model (Model::has_jet) is differentiated exactly by forward-mode automatic
// differentiation: ⌈n / kJetChunk⌉ passes of ceres::Jet, each seeding kJetChunk parameters'
// tangents — exact to rounding and the same model code as every other analysis.
// A black-box model gets central differences, h_j = ε^(1/3)·max(|θ_j|, s_j) with s_j the
// parameter's standard deviation (1 when it has none): truncation O(h²) and rounding O(ε/h) balance
// there, so about 2/3 of the digits are right (docs/math/sensitivity.md#derivatives).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/sensitivity/model.h"
#include "vstcal/sensitivity/parameter_space.h"
#include "vstcal/core/enum_names.h"

namespace vstcal {

enum class DerivativeMethod { kAutodiff, kCentralDifference };
inline constexpr EnumNames<DerivativeMethod, 2> kDerivativeMethodNames = {{{DerivativeMethod::kAutodiff, "autodiff"}, {DerivativeMethod::kCentralDifference, "central-difference"}}};
std::string DerivativeMethodName(DerivativeMethod method);  // "autodiff" / "central-difference"

struct JacobianResult {
  bool valid = false;        // false when the model is undefined at θ or at a difference step
  Eigen::VectorXd value;     // y(θ), m
  Eigen::MatrixXd jacobian;  // ∂y/∂θ, m × n
  DerivativeMethod method = DerivativeMethod::kAutodiff;
};

// Jacobian for `parameters` only (all when empty): columns of the others are left zero, so a
// sweep differentiates one parameter in one pass.
JacobianResult ComputeJacobian(const ParameterSpace& space, const Model& model, const std::vector<double>& theta,
                               const std::vector<size_t>& parameters = {});

}  // namespace vstcal
