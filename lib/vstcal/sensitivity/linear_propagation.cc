#include "vstcal/sensitivity/linear_propagation.h"

#include <cmath>
#include <limits>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

Eigen::VectorXd ToEigen(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

// z of a difference against its standard error; a difference with no sampling error at all is
// infinitely significant, and none at all is not.
double ZScore(double difference, double standard_error) {
  if (standard_error > 0) return difference / standard_error;
  if (difference == 0) return 0.0;
  return std::copysign(std::numeric_limits<double>::infinity(), difference);
}

bool Disagrees(double difference, double z, double scale, const ComparisonOptions& options) {
  return std::abs(z) > options.z_threshold && std::abs(difference) > options.relative_tolerance * scale;
}

}  // namespace

LinearPropagation PropagateLinear(const ParameterSpace& space, const Model& model) {
  LinearPropagation out;
  out.output_names = model.output_names();
  out.group_names = space.group_names();
  const std::vector<double> theta0 = space.Nominal();
  const JacobianResult jac = ComputeJacobian(space, model, theta0);
  out.method = jac.method;
  if (!jac.valid) {
    out.message = "linear propagation: the model is undefined at the nominal parameters" +
                  std::string(jac.method == DerivativeMethod::kCentralDifference ? " or a difference step" : "") +
                  "; check the nominal values";
    return out;
  }
  out.defined = true;
  const Eigen::VectorXd variance = ToEigen(space.Variance());
  out.nominal_parameters = ToEigen(theta0);
  out.nominal_output = jac.value;
  out.jacobian = jac.jacobian;
  out.mean_shift = jac.jacobian * (ToEigen(space.Mean()) - out.nominal_parameters);
  out.mean = out.nominal_output + out.mean_shift;
  out.covariance = jac.jacobian * variance.asDiagonal() * jac.jacobian.transpose();
  out.sigma = out.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  const Eigen::Index m = out.jacobian.rows();
  out.group_variance = Eigen::MatrixXd::Zero(m, static_cast<Eigen::Index>(space.num_groups()));
  for (size_t i = 0; i < space.size(); ++i) {
    const Eigen::Index g = static_cast<Eigen::Index>(space.GroupOf(i));
    const Eigen::Index col = static_cast<Eigen::Index>(i);
    out.group_variance.col(g) += out.jacobian.col(col).cwiseAbs2() * variance(col);
  }
  if (!out.mean.allFinite() || !out.covariance.allFinite() || !out.group_variance.allFinite()) {
    size_t widest = 0;  // the parameter of the largest variance (an infinite one, most likely)
    for (size_t i = 1; i < space.size(); ++i) {
      if (!(variance(static_cast<Eigen::Index>(i)) <= variance(static_cast<Eigen::Index>(widest)))) widest = i;
    }
    LinearPropagation failed;
    failed.method = out.method;
    failed.beyond_range = true;
    failed.message = "linear propagation: J Σ Jᵀ is beyond double precision (the widest parameter, " +
                     space.parameter(widest).name + ", is " + space.parameter(widest).distribution.Describe() +
                     "); give σ's whose squares times the model's slopes stay within double precision (σ < 1e150)";
    return failed;
  }
  return out;
}

std::vector<OutputComparison> CompareLinearWithMonteCarlo(const LinearPropagation& linear,
                                                          const MonteCarloSummary& monte_carlo,
                                                          const ComparisonOptions& options) {
  if (!linear.defined) throw InputError(linear.message);
  if (linear.output_names != monte_carlo.plan().output_names) {
    throw InputError("linear vs monte carlo: the two runs have different outputs; compare runs of one model");
  }
  std::vector<OutputComparison> rows;
  for (size_t k = 0; k < linear.output_names.size(); ++k) {
    const OutputStatistics mc = monte_carlo.Statistics(k);
    const Eigen::Index i = static_cast<Eigen::Index>(k);
    OutputComparison c;
    c.name = mc.name;
    c.linear_mean = linear.mean(i);
    c.monte_carlo_mean = mc.mean;
    c.mean_standard_error = mc.mean_standard_error;
    c.mean_z = ZScore(c.linear_mean - c.monte_carlo_mean, c.mean_standard_error);
    c.mean_disagrees = Disagrees(c.linear_mean - c.monte_carlo_mean, c.mean_z, mc.standard_deviation, options);
    c.linear_sigma = linear.sigma(i);
    c.monte_carlo_sigma = mc.standard_deviation;
    c.sigma_standard_error = mc.standard_deviation_standard_error;
    c.sigma_z = ZScore(c.linear_sigma - c.monte_carlo_sigma, c.sigma_standard_error);
    c.sigma_relative_difference =
        c.monte_carlo_sigma > 0 ? (c.linear_sigma - c.monte_carlo_sigma) / c.monte_carlo_sigma : 0.0;
    c.sigma_disagrees = Disagrees(c.linear_sigma - c.monte_carlo_sigma, c.sigma_z, c.monte_carlo_sigma, options);
    rows.push_back(c);
  }
  return rows;
}

}  // namespace vstcal
