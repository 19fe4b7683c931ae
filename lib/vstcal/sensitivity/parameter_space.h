// The inputs θ of a model y = f(θ): n independent scalar parameters, each with a name, a group
// and a distribution. Groups are what err-sim ranks (one per error source: "tracking",
// "display", …): Sobol indices are reported per group, all of a group's parameters resampled
// together, so parameters may be freely dependent in how the model uses them inside a group.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "vstcal/sensitivity/distribution.h"

namespace vstcal {

struct Parameter {
  std::string name;   // unique in the space
  std::string group;  // non-empty; groups are numbered in order of first appearance
  Distribution distribution;
  // The value the model is linearised at and sweeps hold the others at. Absent → the
  // distribution's mean. Set it for a bias: e.g. an error parameter with nominal 0 and
  // distribution fixed(0.3) is a 0.3 bias, and linear propagation reports the mean shift it causes.
  std::optional<double> nominal;
};

class ParameterSpace {
 public:
  ParameterSpace() = default;
  // InputError for an empty or duplicate name, an empty group, a non-finite nominal.
  explicit ParameterSpace(std::vector<Parameter> parameters);
  void Add(Parameter parameter);

  size_t size() const { return parameters_.size(); }
  const Parameter& parameter(size_t i) const { return parameters_.at(i); }
  const std::vector<Parameter>& parameters() const { return parameters_; }
  // Index of a parameter by name; InputError naming the parameter when absent.
  size_t IndexOf(const std::string& name) const;

  size_t num_groups() const { return group_names_.size(); }
  const std::vector<std::string>& group_names() const { return group_names_; }
  size_t GroupOf(size_t parameter) const { return group_of_.at(parameter); }
  // The parameters of group g, in parameter order.
  const std::vector<size_t>& GroupMembers(size_t group) const { return group_members_.at(group); }

  std::vector<double> Nominal() const;  // θ₀
  std::vector<double> Mean() const;     // E[θ]
  std::vector<double> Variance() const;  // Var θᵢ (independent parameters: Σ_θ is diagonal)

  // θᵢ = Qᵢ(uᵢ) for the n coordinates of a point of the unit cube.
  void ToParameters(const double* u, double* theta) const;

 private:
  std::vector<Parameter> parameters_;
  std::vector<std::string> group_names_;
  std::vector<size_t> group_of_;
  std::vector<std::vector<size_t>> group_members_;
};

}  // namespace vstcal
