// A model y = f(θ): n parameters in, m named outputs out. The analyses here see nothing else.
//
// Write the model once, templated on the scalar, in the Ceres cost-functor pattern:
//
//   struct MyModel {
//     template <typename T> bool operator()(const T* theta, T* y) const;  // false: undefined here
//   };
//   Model model = Model::Templated(space.size(), {"u_px", "v_px"}, MyModel{...});
//
// The same code then runs with double (Monte Carlo, Sobol, sweeps) and with ceres::Jet (exact
// first derivatives for linear propagation and sweep slopes). A model known only in double
// (a black box) is accepted too; its derivatives are then central differences.
//
// Contract: evaluation is const and thread-safe (it is called from several threads at once),
// and deterministic. Returning false marks θ where the model is undefined (e.g. a point behind the
// camera): the analyses count such samples and report them, never replace them by a value.
// A non-finite output is treated the same way.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <ceres/jet.h>

namespace vstcal {

// Partial derivatives carried per forward-mode pass: n parameters take ⌈n/8⌉ passes (8 for n = 60).
inline constexpr int kJetChunk = 8;
using ChunkJet = ceres::Jet<double, kJetChunk>;

class Model {
 public:
  using Function = std::function<bool(const double* theta, double* y)>;
  using JetFunction = std::function<bool(const ChunkJet* theta, ChunkJet* y)>;

  // A black-box model (double only). InputError for m = 0 or an empty function.
  Model(size_t num_parameters, std::vector<std::string> output_names, Function function);

  // A model templated on the scalar (see above); Functor is copied once and shared by both paths.
  template <typename Functor>
  static Model Templated(size_t num_parameters, std::vector<std::string> output_names, Functor functor) {
    auto shared = std::make_shared<const Functor>(std::move(functor));
    Model model(num_parameters, std::move(output_names),
                [shared](const double* theta, double* y) { return (*shared)(theta, y); });
    model.jet_function_ = [shared](const ChunkJet* theta, ChunkJet* y) { return (*shared)(theta, y); };
    return model;
  }

  size_t num_parameters() const { return num_parameters_; }
  size_t num_outputs() const { return output_names_.size(); }
  const std::vector<std::string>& output_names() const { return output_names_; }
  bool has_jet() const { return static_cast<bool>(jet_function_); }

  // y = f(θ); false when the model returned false or any output is not finite.
  bool Evaluate(const double* theta, double* y) const;
  // The same with jets; requires has_jet() (InternalError otherwise).
  bool EvaluateJet(const ChunkJet* theta, ChunkJet* y) const;

 private:
  size_t num_parameters_;
  std::vector<std::string> output_names_;
  Function function_;
  JetFunction jet_function_;
};

// InputError unless the model takes exactly the space's parameters: the most likely wiring bug.
class ParameterSpace;
void RequireCompatible(const ParameterSpace& space, const Model& model);

}  // namespace vstcal
