#include "vstcal/sensitivity/distribution.h"

#include <cmath>
#include <sstream>

#include "vstcal/core/error.h"
#include "vstcal/sensitivity/normal_quantile.h"

namespace vstcal {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// Spelled out for clang 14 (the fuzz build), which does not yet deduce an aggregate's arguments.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

void RequireFinite(double value, const char* what) {
  if (!std::isfinite(value)) {
    throw InputError(std::string("distribution: ") + what + " is not finite; give a finite number");
  }
}

}  // namespace

Distribution Distribution::MakeNormal(double mean, double sigma) {
  RequireFinite(mean, "normal mean");
  RequireFinite(sigma, "normal sigma");
  if (sigma < 0) throw InputError("distribution: normal sigma is negative; give sigma >= 0");
  return Distribution(Normal{mean, sigma});
}

Distribution Distribution::MakeUniform(double lo, double hi) {
  RequireFinite(lo, "uniform lo");
  RequireFinite(hi, "uniform hi");
  if (lo > hi) throw InputError("distribution: uniform lo > hi; swap the bounds");
  return Distribution(Uniform{lo, hi});
}

Distribution Distribution::MakeFixed(double value) {
  RequireFinite(value, "fixed value");
  return Distribution(Fixed{value});
}

double Distribution::Quantile(double u) const {
  if (!(u > 0.0 && u < 1.0)) {
    throw InputError("distribution: uniform draw " + std::to_string(u) + " is outside (0, 1)");
  }
  return std::visit(Overloaded{[u](const Normal& d) { return d.mean + d.sigma * NormalQuantile(u); },
                               // lo + (hi − lo)·u stays inside [lo, hi] (no overshoot as lo·(1−u) + hi·u can).
                               [u](const Uniform& d) { return d.lo + (d.hi - d.lo) * u; },
                               [](const Fixed& d) { return d.value; }},
                    form_);
}

double Distribution::Mean() const {
  return std::visit(Overloaded{[](const Normal& d) { return d.mean; },
                               [](const Uniform& d) { return 0.5 * (d.lo + d.hi); },
                               [](const Fixed& d) { return d.value; }},
                    form_);
}

double Distribution::Variance() const {
  return std::visit(Overloaded{[](const Normal& d) { return d.sigma * d.sigma; },
                               [](const Uniform& d) { return (d.hi - d.lo) * (d.hi - d.lo) / 12.0; },
                               [](const Fixed&) { return 0.0; }},
                    form_);
}

double Distribution::StandardDeviation() const { return std::sqrt(Variance()); }

bool Distribution::IsConstant() const { return Variance() == 0.0; }

std::string Distribution::Describe() const {
  std::ostringstream out;
  out.precision(6);
  std::visit(Overloaded{[&](const Normal& d) { out << "normal(" << d.mean << ", " << d.sigma << ")"; },
                        [&](const Uniform& d) { out << "uniform(" << d.lo << ", " << d.hi << ")"; },
                        [&](const Fixed& d) { out << "fixed(" << d.value << ")"; }},
             form_);
  return out.str();
}

}  // namespace vstcal
