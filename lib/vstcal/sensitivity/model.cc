#include "vstcal/sensitivity/model.h"

#include <cmath>

#include "vstcal/core/error.h"
#include "vstcal/sensitivity/parameter_space.h"

namespace vstcal {

Model::Model(size_t num_parameters, std::vector<std::string> output_names, Function function)
    : num_parameters_(num_parameters), output_names_(std::move(output_names)), function_(std::move(function)) {
  if (output_names_.empty()) throw InputError("model: no outputs; name at least one output");
  if (!function_) throw InputError("model: the evaluation function is empty");
}

bool Model::Evaluate(const double* theta, double* y) const {
  if (!function_(theta, y)) return false;
  for (size_t k = 0; k < num_outputs(); ++k) {
    if (!std::isfinite(y[k])) return false;
  }
  return true;
}

bool Model::EvaluateJet(const ChunkJet* theta, ChunkJet* y) const {
  VSTCAL_CHECK(has_jet(), "jet evaluation of a model built without a templated functor");
  if (!jet_function_(theta, y)) return false;
  for (size_t k = 0; k < num_outputs(); ++k) {
    if (!ceres::isfinite(y[k])) return false;
  }
  return true;
}

void RequireCompatible(const ParameterSpace& space, const Model& model) {
  if (space.size() != model.num_parameters()) {
    throw InputError("sensitivity: the model takes " + std::to_string(model.num_parameters()) +
                     " parameters but the parameter space has " + std::to_string(space.size()) +
                     "; build both from the same list");
  }
}

}  // namespace vstcal
