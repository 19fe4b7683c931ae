#include "vstcal/sensitivity/parameter_space.h"

#include <algorithm>
#include <cmath>

#include "vstcal/core/error.h"

namespace vstcal {

ParameterSpace::ParameterSpace(std::vector<Parameter> parameters) {
  for (Parameter& p : parameters) Add(std::move(p));
}

void ParameterSpace::Add(Parameter parameter) {
  if (parameter.name.empty()) throw InputError("parameter space: a parameter has an empty name; name it");
  if (parameter.group.empty()) {
    throw InputError("parameter space: parameter '" + parameter.name + "' has an empty group; give it one");
  }
  for (const Parameter& p : parameters_) {
    if (p.name == parameter.name) {
      throw InputError("parameter space: parameter '" + parameter.name + "' is defined twice; rename one");
    }
  }
  if (parameter.nominal && !std::isfinite(*parameter.nominal)) {
    throw InputError("parameter space: parameter '" + parameter.name + "' has a non-finite nominal");
  }
  const auto found = std::find(group_names_.begin(), group_names_.end(), parameter.group);
  const size_t group = static_cast<size_t>(found - group_names_.begin());
  if (found == group_names_.end()) {
    group_names_.push_back(parameter.group);
    group_members_.emplace_back();
  }
  group_members_[group].push_back(parameters_.size());
  group_of_.push_back(group);
  parameters_.push_back(std::move(parameter));
}

size_t ParameterSpace::IndexOf(const std::string& name) const {
  for (size_t i = 0; i < parameters_.size(); ++i) {
    if (parameters_[i].name == name) return i;
  }
  throw InputError("parameter space: no parameter named '" + name + "'");
}

std::vector<double> ParameterSpace::Nominal() const {
  std::vector<double> theta(size());
  for (size_t i = 0; i < size(); ++i) {
    theta[i] = parameters_[i].nominal.value_or(parameters_[i].distribution.Mean());
  }
  return theta;
}

std::vector<double> ParameterSpace::Mean() const {
  std::vector<double> mean(size());
  for (size_t i = 0; i < size(); ++i) mean[i] = parameters_[i].distribution.Mean();
  return mean;
}

std::vector<double> ParameterSpace::Variance() const {
  std::vector<double> variance(size());
  for (size_t i = 0; i < size(); ++i) variance[i] = parameters_[i].distribution.Variance();
  return variance;
}

void ParameterSpace::ToParameters(const double* u, double* theta) const {
  for (size_t i = 0; i < size(); ++i) theta[i] = parameters_[i].distribution.Quantile(u[i]);
}

}  // namespace vstcal
