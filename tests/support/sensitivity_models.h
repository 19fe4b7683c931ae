// Test models for the sensitivity module with closed-form Sobol indices, shared by unit tests and
// benchmarks. Each is a functor templated on the scalar (double and ceres::Jet), as err-sim's
// chain will be. Derivations: docs/math/sensitivity.md#ishigami, #sobol-g, #grouped-model.
#pragma once

#include <cmath>
#include <vector>

#include "vstcal/sensitivity/parameter_space.h"

namespace vstcal::testing {

struct AnalyticIndices {
  std::vector<double> first;  // S per group
  std::vector<double> total;  // ST per group
};

// Ishigami & Homma (1990): f = sin x₁ + a sin² x₂ + b x₃⁴ sin x₁, xᵢ ~ U(−π, π).
struct Ishigami {
  double a = 7.0;
  double b = 0.1;
  template <typename T>
  bool operator()(const T* x, T* y) const {
    using std::sin;
    const T s2 = sin(x[1]);
    const T x3_2 = x[2] * x[2];
    y[0] = sin(x[0]) + a * s2 * s2 + b * x3_2 * x3_2 * sin(x[0]);
    return true;
  }
};

// x1, x2, x3 ~ U(−π, π), each in its own group named after it.
inline ParameterSpace IshigamiSpace() {
  const double pi = 3.14159265358979323846;
  ParameterSpace space;
  for (const char* name : {"x1", "x2", "x3"}) space.Add({name, name, Distribution::MakeUniform(-pi, pi), {}});
  return space;
}

// V₁ = ½(1 + bπ⁴/5)², V₂ = a²/8, V₁₃ = b²π⁸(1/18 − 1/50), V = V₁ + V₂ + V₁₃.
inline AnalyticIndices IshigamiIndices(double a, double b) {
  const double pi = 3.14159265358979323846, pi4 = std::pow(pi, 4), pi8 = pi4 * pi4;
  const double v1 = 0.5 * (1 + b * pi4 / 5) * (1 + b * pi4 / 5);
  const double v2 = a * a / 8;
  const double v13 = b * b * pi8 * (1.0 / 18 - 1.0 / 50);
  const double v = v1 + v2 + v13;
  return {{v1 / v, v2 / v, 0.0}, {(v1 + v13) / v, v2 / v, v13 / v}};
}

// Sobol' G function: f = Πᵢ (|4xᵢ − 2| + aᵢ) / (1 + aᵢ), xᵢ ~ U(0, 1).
struct SobolG {
  std::vector<double> a;
  template <typename T>
  bool operator()(const T* x, T* y) const {
    using std::abs;
    T product(1.0);
    for (size_t i = 0; i < a.size(); ++i) product *= (abs(4.0 * x[i] - 2.0) + a[i]) / (1.0 + a[i]);
    y[0] = product;
    return true;
  }
};

inline ParameterSpace SobolGSpace(size_t n) {
  ParameterSpace space;
  for (size_t i = 0; i < n; ++i) {
    // Appended rather than "x" + to_string(): GCC 12 warns falsely (-Wrestrict) on the latter.
    std::string name = "x";
    name += std::to_string(i + 1);
    space.Add({name, name, Distribution::MakeUniform(0, 1), {}});
  }
  return space;
}

// Vᵢ = 1 / (3(1 + aᵢ)²), V = Π(1 + Vᵢ) − 1, Sᵢ = Vᵢ/V, STᵢ = Vᵢ Π_{j≠i}(1 + Vⱼ) / V.
inline AnalyticIndices SobolGIndices(const std::vector<double>& a) {
  std::vector<double> vi;
  double product = 1;
  for (double ai : a) {
    vi.push_back(1.0 / (3 * (1 + ai) * (1 + ai)));
    product *= 1 + vi.back();
  }
  const double v = product - 1;
  AnalyticIndices out;
  for (double x : vi) {
    out.first.push_back(x / v);
    out.total.push_back(x * product / (1 + x) / v);
  }
  return out;
}

// A model with grouped terms, interactions inside groups and one across groups:
//   y = x₁ + x₂ + x₁x₂ + 2x₃ + x₄x₅ + x₃x₄ + x₆
// groups g1 = {x₁, x₂}, g2 = {x₃}, g3 = {x₄, x₅}, bias = {x₆ fixed}. All xᵢ have mean 0, so every
// term is orthogonal to the others and its variance is the product of its factors' variances.
struct GroupedModel {
  template <typename T>
  bool operator()(const T* x, T* y) const {
    y[0] = x[0] + x[1] + x[0] * x[1] + 2.0 * x[2] + x[3] * x[4] + x[2] * x[3] + x[5];
    return true;
  }
};

struct GroupedSetup {
  double s1 = 1.0, s2 = 0.8, h3 = 1.5, s4 = 1.2, s5 = 1.0, bias = 2.0;
};

inline ParameterSpace GroupedSpace(const GroupedSetup& c = {}) {
  return ParameterSpace({{"x1", "g1", Distribution::MakeNormal(0, c.s1), {}},
                                      {"x2", "g1", Distribution::MakeNormal(0, c.s2), {}},
                                      {"x3", "g2", Distribution::MakeUniform(-c.h3, c.h3), {}},
                                      {"x4", "g3", Distribution::MakeNormal(0, c.s4), {}},
                                      {"x5", "g3", Distribution::MakeNormal(0, c.s5), {}},
                                      {"x6", "bias", Distribution::MakeFixed(c.bias), 0.0}});
}

// V_g1 = v₁ + v₂ + v₁v₂ (no cross-group term), V_g2 = 4v₃, V_g3 = v₄v₅; the x₃x₄ term adds v₃v₄
// to the totals of g2 and g3 only; the fixed bias contributes nothing.
inline AnalyticIndices GroupedIndices(const GroupedSetup& c = {}) {
  const double v1 = c.s1 * c.s1, v2 = c.s2 * c.s2, v3 = c.h3 * c.h3 / 3, v4 = c.s4 * c.s4, v5 = c.s5 * c.s5;
  const double g1 = v1 + v2 + v1 * v2, g2 = 4 * v3, g3 = v4 * v5, cross = v3 * v4;
  const double v = g1 + g2 + g3 + cross;
  return {{g1 / v, g2 / v, g3 / v, 0.0}, {g1 / v, (g2 + cross) / v, (g3 + cross) / v, 0.0}};
}

}  // namespace vstcal::testing
