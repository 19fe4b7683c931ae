// First-order (linear) propagation of the parameter distribution through the model
// (docs/math/sensitivity.md#linear): around the nominal θ₀, y ≈ f(θ₀) + J (θ − θ₀), so
//
//   E[y]  ≈ f(θ₀) + J (E[θ] − θ₀)        the mean shift: fixed biases and off-nominal means
//   Σ_y   ≈ J Σ_θ Jᵀ,  Σ_θ = diag(Var θᵢ)  (independent parameters)
//
// J comes from derivatives.h: forward-mode autodiff through the same templated model code that
// Monte Carlo runs, or central differences for a black box. Per group, the diagonal of
// J_g Σ_g J_gᵀ is the linear variance budget: for a linear model it is V·S_g exactly.
//
// Where the model is not linear over the spread of θ, this is wrong; compare it with Monte Carlo
// (CompareLinearWithMonteCarlo) to see where.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/sensitivity/derivatives.h"
#include "vstcal/sensitivity/mc_summary.h"
#include "vstcal/sensitivity/model.h"
#include "vstcal/sensitivity/parameter_space.h"

namespace vstcal {

struct LinearPropagation {
  bool defined = false;  // false: the model is undefined at θ₀ (message says so); nothing else is set
  // Not defined because J Σ Jᵀ is beyond double precision (a σ of 1e300 squares to infinity): the
  // parameters are out of range rather than the model degenerate. Never a non-finite result.
  bool beyond_range = false;
  std::string message;
  DerivativeMethod method = DerivativeMethod::kAutodiff;
  std::vector<std::string> output_names;
  std::vector<std::string> group_names;
  Eigen::VectorXd nominal_parameters;  // θ₀, n
  Eigen::VectorXd nominal_output;      // f(θ₀), m
  Eigen::MatrixXd jacobian;            // m × n
  Eigen::VectorXd mean_shift;          // J (E[θ] − θ₀), m
  Eigen::VectorXd mean;                // f(θ₀) + mean_shift
  Eigen::MatrixXd covariance;          // m × m
  Eigen::VectorXd sigma;               // √diag(covariance)
  Eigen::MatrixXd group_variance;      // m × G: Σ_{i∈g} J_ki² Var θᵢ
};

LinearPropagation PropagateLinear(const ParameterSpace& space, const Model& model);

// Linear vs Monte Carlo of the same model, per output. The Monte Carlo σ has standard error
// ≈ σ/√(2(N − 1)) for normal outputs (moments.h gives the kurtosis-aware form used here), its
// mean σ/√N. An output is flagged where the difference exceeds z_threshold standard errors AND
// relative_tolerance·σ_MC (0 by default: any difference the sampling error cannot explain).
struct ComparisonOptions {
  double z_threshold = 3.0;
  double relative_tolerance = 0.0;
};

struct OutputComparison {
  std::string name;
  double linear_mean = 0, monte_carlo_mean = 0, mean_standard_error = 0, mean_z = 0;
  double linear_sigma = 0, monte_carlo_sigma = 0, sigma_standard_error = 0, sigma_z = 0;
  double sigma_relative_difference = 0;  // (linear − MC) / MC
  bool mean_disagrees = false;
  bool sigma_disagrees = false;
};

// InputError when the two describe different outputs, the linear result is undefined, or the
// summary is incomplete.
std::vector<OutputComparison> CompareLinearWithMonteCarlo(const LinearPropagation& linear,
                                                          const MonteCarloSummary& monte_carlo,
                                                          const ComparisonOptions& options = {});

}  // namespace vstcal
