// One-at-a-time sweep: each output as a function of one parameter over a range, every other
// parameter held at its nominal value, plus the local slope ∂y/∂θ_j at the nominal point (exact by
// autodiff for a templated model, central differences for a black box — derivatives.h).
// It shows the shape (saturation, a kink, where the model becomes undefined) that variance-based
// indices summarise away.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/sensitivity/derivatives.h"
#include "vstcal/sensitivity/model.h"
#include "vstcal/sensitivity/parameter_space.h"

namespace vstcal {

struct SweepOptions {
  size_t points = 41;  // ≥ 2, evenly spaced from lo to hi inclusive
  // Default range: mean ± 3σ for a normal, the support for a uniform; a constant parameter needs
  // an explicit one.
  std::optional<double> lo = std::nullopt;
  std::optional<double> hi = std::nullopt;
};

struct SweepResult {
  std::string parameter;
  double nominal = 0;             // θ₀ of the swept parameter
  std::vector<double> values;     // the swept values
  Eigen::MatrixXd outputs;        // points × m; rows where !defined[i] are 0 and must be skipped
  std::vector<bool> defined;      // the model was defined at values[i]
  bool slope_defined = false;     // the model was defined at (and around) θ₀
  Eigen::VectorXd slope;          // ∂y/∂θ_j at θ₀, m
  DerivativeMethod method = DerivativeMethod::kAutodiff;
};

// InputError for a bad parameter index, fewer than 2 points, lo ≥ hi or non-finite bounds.
SweepResult SweepParameter(const ParameterSpace& space, const Model& model, size_t parameter,
                           const SweepOptions& options = {});

}  // namespace vstcal
