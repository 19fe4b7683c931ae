#include "vstcal/sensitivity/derivatives.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

bool Autodiff(const Model& model, const std::vector<double>& theta, const std::vector<size_t>& wanted,
              JacobianResult& out) {
  const size_t n = theta.size(), m = model.num_outputs();
  std::vector<ChunkJet> theta_jet(n), y_jet(m);
  for (size_t start = 0; start < wanted.size(); start += kJetChunk) {
    const size_t chunk = std::min<size_t>(kJetChunk, wanted.size() - start);
    for (size_t i = 0; i < n; ++i) theta_jet[i] = ChunkJet(theta[i]);
    for (size_t c = 0; c < chunk; ++c) theta_jet[wanted[start + c]].v[static_cast<int>(c)] = 1.0;
    if (!model.EvaluateJet(theta_jet.data(), y_jet.data())) return false;
    for (size_t k = 0; k < m; ++k) {
      out.value(static_cast<Eigen::Index>(k)) = y_jet[k].a;
      for (size_t c = 0; c < chunk; ++c) {
        out.jacobian(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(wanted[start + c])) =
            y_jet[k].v[static_cast<int>(c)];
      }
    }
  }
  return true;
}

bool CentralDifference(const ParameterSpace& space, const Model& model, const std::vector<double>& theta,
                       const std::vector<size_t>& wanted, JacobianResult& out) {
  const size_t m = model.num_outputs();
  std::vector<double> y_plus(m), y_minus(m), probe = theta;
  if (!model.Evaluate(theta.data(), out.value.data())) return false;
  const double cbrt_eps = std::cbrt(std::numeric_limits<double>::epsilon());
  for (size_t j : wanted) {
    const double sd = space.parameter(j).distribution.StandardDeviation();
    const double scale = std::max(std::abs(theta[j]), sd > 0 ? sd : 1.0);
    // Rounding the step through θ ± h makes (θ + h) − (θ − h) exactly the divisor.
    const double plus = theta[j] + cbrt_eps * scale, minus = theta[j] - cbrt_eps * scale;
    probe[j] = plus;
    if (!model.Evaluate(probe.data(), y_plus.data())) return false;
    probe[j] = minus;
    if (!model.Evaluate(probe.data(), y_minus.data())) return false;
    probe[j] = theta[j];
    for (size_t k = 0; k < m; ++k) {
      out.jacobian(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) = (y_plus[k] - y_minus[k]) / (plus - minus);
    }
  }
  return true;
}

}  // namespace

std::string DerivativeMethodName(DerivativeMethod method) {
  return std::string(NameOf(kDerivativeMethodNames, method));
}

JacobianResult ComputeJacobian(const ParameterSpace& space, const Model& model, const std::vector<double>& theta,
                               const std::vector<size_t>& parameters) {
  RequireCompatible(space, model);
  if (theta.size() != space.size()) throw InputError("jacobian: θ has the wrong number of parameters");
  std::vector<size_t> wanted = parameters;
  if (wanted.empty()) {
    wanted.resize(space.size());
    std::iota(wanted.begin(), wanted.end(), size_t{0});
  }
  for (size_t j : wanted) {
    if (j >= space.size()) throw InputError("jacobian: parameter index " + std::to_string(j) + " is out of range");
  }
  JacobianResult out;
  out.value = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(model.num_outputs()));
  out.jacobian = Eigen::MatrixXd::Zero(out.value.size(), static_cast<Eigen::Index>(space.size()));
  if (model.has_jet()) {
    out.method = DerivativeMethod::kAutodiff;
    // With no parameter to seed, one pass still yields the value.
    out.valid = wanted.empty() ? model.Evaluate(theta.data(), out.value.data()) : Autodiff(model, theta, wanted, out);
  } else {
    out.method = DerivativeMethod::kCentralDifference;
    out.valid = CentralDifference(space, model, theta, wanted, out);
  }
  return out;
}

}  // namespace vstcal
