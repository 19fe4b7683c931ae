#include "vstcal/sensitivity/oat_sweep.h"

#include <cmath>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

struct Range {
  double lo, hi;
};

Range DefaultRange(const Parameter& p) {
  const auto& form = p.distribution.form();
  if (const auto* normal = std::get_if<Distribution::Normal>(&form); normal && normal->sigma > 0) {
    return {normal->mean - 3 * normal->sigma, normal->mean + 3 * normal->sigma};
  }
  if (const auto* uniform = std::get_if<Distribution::Uniform>(&form); uniform && uniform->lo < uniform->hi) {
    return {uniform->lo, uniform->hi};
  }
  throw InputError("sweep: parameter '" + p.name + "' is constant (" + p.distribution.Describe() +
                   "); give the sweep range explicitly");
}

}  // namespace

SweepResult SweepParameter(const ParameterSpace& space, const Model& model, size_t parameter,
                           const SweepOptions& options) {
  RequireCompatible(space, model);
  if (parameter >= space.size()) {
    throw InputError("sweep: parameter index " + std::to_string(parameter) + " is out of range");
  }
  if (options.points < 2) throw InputError("sweep: need at least 2 points");
  const Parameter& p = space.parameter(parameter);
  Range range{0, 0};
  if (!options.lo || !options.hi) range = DefaultRange(p);
  range.lo = options.lo.value_or(range.lo);
  range.hi = options.hi.value_or(range.hi);
  if (!(std::isfinite(range.lo) && std::isfinite(range.hi) && range.lo < range.hi)) {
    throw InputError("sweep: range of '" + p.name + "' must be finite with lo < hi");
  }

  std::vector<double> theta = space.Nominal();
  SweepResult out;
  out.parameter = p.name;
  out.nominal = theta[parameter];
  const size_t m = model.num_outputs();
  out.outputs = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(options.points), static_cast<Eigen::Index>(m));
  std::vector<double> y(m);
  for (size_t i = 0; i < options.points; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(options.points - 1);
    // Ends exactly at lo and hi (lo + t·(hi − lo) may round past hi).
    const double value = i + 1 == options.points ? range.hi : range.lo + t * (range.hi - range.lo);
    theta[parameter] = value;
    out.values.push_back(value);
    const bool ok = model.Evaluate(theta.data(), y.data());
    out.defined.push_back(ok);
    if (ok) {
      for (size_t k = 0; k < m; ++k) out.outputs(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = y[k];
    }
  }
  const JacobianResult jac = ComputeJacobian(space, model, space.Nominal(), {parameter});
  out.method = jac.method;
  out.slope_defined = jac.valid;
  out.slope = jac.valid ? Eigen::VectorXd(jac.jacobian.col(static_cast<Eigen::Index>(parameter)))
                        : Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m));
  return out;
}

}  // namespace vstcal
