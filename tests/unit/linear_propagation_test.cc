// Derivatives (autodiff in chunks vs closed form vs central differences), linear propagation
// against exact answers and against Monte Carlo, and one-at-a-time sweeps.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/sensitivity_models.h"
#include "vstcal/core/error.h"
#include "vstcal/sensitivity/linear_propagation.h"
#include "vstcal/sensitivity/monte_carlo.h"
#include "vstcal/sensitivity/oat_sweep.h"

namespace vstcal {
namespace {

// y_k = Σᵢ wᵢ sin((k + 1) θᵢ), n = 21 parameters: three jet chunks, the last one partial.
struct Wavy {
  template <typename T>
  bool operator()(const T* theta, T* y) const {
    using std::sin;
    for (int k = 0; k < 2; ++k) {
      y[k] = T(0.0);
      for (int i = 0; i < 21; ++i) y[k] += (1.0 + 0.1 * i) * sin((k + 1.0) * theta[i]);
    }
    return true;
  }
};

ParameterSpace WavySpace() {
  ParameterSpace space;
  for (int i = 0; i < 21; ++i) {
    std::string name = "t";  // appended: GCC 12 warns falsely (-Wrestrict) on "t" + to_string()
    name += std::to_string(i);
    space.Add({name, i < 10 ? "a" : "b", Distribution::MakeNormal(0.05 * i, 0.1), {}});
  }
  return space;
}

TEST(Derivatives, AutodiffInChunksIsExactAndCentralDifferencesAgree) {
  const ParameterSpace space = WavySpace();
  const Model templated = Model::Templated(21, {"y1", "y2"}, Wavy{});
  const Model black_box(21, {"y1", "y2"}, [](const double* t, double* y) { return Wavy{}(t, y); });
  const std::vector<double> theta = space.Nominal();
  const JacobianResult ad = ComputeJacobian(space, templated, theta);
  const JacobianResult cd = ComputeJacobian(space, black_box, theta);
  ASSERT_TRUE(ad.valid && cd.valid);
  EXPECT_EQ(ad.method, DerivativeMethod::kAutodiff);
  EXPECT_EQ(cd.method, DerivativeMethod::kCentralDifference);
  for (int k = 0; k < 2; ++k) {
    for (int i = 0; i < 21; ++i) {
      const double exact = (1.0 + 0.1 * i) * (k + 1.0) * std::cos((k + 1.0) * theta[i]);
      EXPECT_NEAR(ad.jacobian(k, i), exact, 1e-14 * (k + 1) * 3) << k << "," << i;
      // Central differences: truncation h²/6·|f'''| with h ≈ 6e-6·0.1 plus rounding ε·|f|/h.
      EXPECT_NEAR(cd.jacobian(k, i), exact, 2e-8) << k << "," << i;
    }
  }
  EXPECT_EQ(ad.value, cd.value);
}

// y = A θ, with normals, uniforms, an off-nominal mean and a fixed bias.
struct Linear {
  template <typename T>
  bool operator()(const T* t, T* y) const {
    y[0] = 2.0 * t[0] - t[1] + 0.5 * t[2] + 3.0 * t[5];
    y[1] = t[0] + t[3] - 4.0 * t[4];
    y[2] = 10.0 + t[2] - t[3] + t[5];
    return true;
  }
};

ParameterSpace LinearSpace() {
  return ParameterSpace({{"a", "tracking", Distribution::MakeNormal(0, 0.3), {}},
                         {"b", "tracking", Distribution::MakeUniform(-1, 1), {}},
                         {"c", "camera", Distribution::MakeNormal(1.0, 0.2), 0.0},  // mean off nominal
                         {"d", "camera", Distribution::MakeUniform(0, 2), {}},
                         {"e", "display", Distribution::MakeNormal(0, 0.05), {}},
                         {"f", "bias", Distribution::MakeFixed(0.5), 0.0}});
}

TEST(LinearPropagation, IsExactOnALinearModel) {
  const LinearPropagation lin = PropagateLinear(LinearSpace(), Model::Templated(6, {"p", "q", "r"}, Linear{}));
  ASSERT_TRUE(lin.defined);
  Eigen::MatrixXd a(3, 6);
  a << 2, -1, 0.5, 0, 0, 3,  //
      1, 0, 0, 1, -4, 0,     //
      0, 0, 1, -1, 0, 1;
  EXPECT_TRUE(lin.jacobian.isApprox(a, 1e-15));
  const Eigen::VectorXd var = (Eigen::VectorXd(6) << 0.09, 1.0 / 3, 0.04, 1.0 / 3, 0.0025, 0).finished();
  EXPECT_TRUE(lin.covariance.isApprox(a * var.asDiagonal() * a.transpose(), 1e-14));
  // Nominal θ₀ = (0, 0, 0, 1, 0, 0), E[θ] = (0, 0, 1, 1, 0, 0.5): shift = A (E[θ] − θ₀).
  EXPECT_NEAR(lin.mean_shift(0), 0.5 + 1.5, 1e-15);
  EXPECT_NEAR(lin.mean_shift(1), 0.0, 1e-15);
  EXPECT_NEAR(lin.mean_shift(2), 1.0 + 0.5, 1e-15);
  EXPECT_NEAR(lin.mean(2), 10.0 - 1.0 + 1.5, 1e-14);
  // The group budget adds up to the variance; the bias group contributes none.
  EXPECT_TRUE(lin.group_variance.rowwise().sum().isApprox(lin.covariance.diagonal(), 1e-14));
  EXPECT_EQ(lin.group_variance(0, 3), 0.0);
  EXPECT_NEAR(lin.group_variance(1, 2), 16 * 0.0025, 1e-16);
}

MonteCarloOptions McOptions(uint64_t samples, uint64_t seed) {
  MonteCarloOptions o;
  o.samples = samples;
  o.sampling = {SamplingMethod::kPseudoRandom, seed, 0};
  o.threads = 2;
  return o;
}

// Flags at 4 standard errors here: 6 independent-ish checks at 3σ would fail a correct method
// 1.6 % of the time; at 4σ, 0.04 %.
TEST(LinearPropagation, AgreesWithMonteCarloOnALinearModel) {
  const ParameterSpace space = LinearSpace();
  const Model model = Model::Templated(6, {"p", "q", "r"}, Linear{});
  const LinearPropagation lin = PropagateLinear(space, model);
  const MonteCarloSummary mc = RunMonteCarlo(space, model, McOptions(40000, 17));
  const std::vector<OutputComparison> rows = CompareLinearWithMonteCarlo(lin, mc, {4.0, 0.0});
  ASSERT_EQ(rows.size(), 3u);
  for (const OutputComparison& c : rows) {
    EXPECT_FALSE(c.sigma_disagrees) << c.name << " z = " << c.sigma_z;
    EXPECT_FALSE(c.mean_disagrees) << c.name << " z = " << c.mean_z;
    // σ/√(2(N−1)) is 0.35 % of σ at N = 40,000: the agreement is tight, not vacuous.
    EXPECT_LT(c.sigma_standard_error, 0.01 * c.monte_carlo_sigma);
  }
}

// y₁ = exp(θ), y₂ = θ², θ ~ N(0, 0.5²): linear σ's are 0.5 and 0, the true ones
// √((e^{σ²} − 1) e^{σ²}) = 0.604 and √2 σ² = 0.354.
struct Curved {
  template <typename T>
  bool operator()(const T* t, T* y) const {
    using std::exp;
    y[0] = exp(t[0]);
    y[1] = t[0] * t[0];
    return true;
  }
};

TEST(LinearPropagation, DisagreesWithMonteCarloOnANonlinearModel) {
  const ParameterSpace space({{"theta", "g", Distribution::MakeNormal(0, 0.5), {}}});
  const Model model = Model::Templated(1, {"exp", "square"}, Curved{});
  const LinearPropagation lin = PropagateLinear(space, model);
  EXPECT_NEAR(lin.sigma(0), 0.5, 1e-15);
  EXPECT_EQ(lin.sigma(1), 0.0);
  const MonteCarloSummary mc = RunMonteCarlo(space, model, McOptions(40000, 23));
  const std::vector<OutputComparison> rows = CompareLinearWithMonteCarlo(lin, mc);
  const double lognormal_sigma = std::sqrt((std::exp(0.25) - 1) * std::exp(0.25));
  EXPECT_NEAR(rows[0].monte_carlo_sigma, lognormal_sigma, 4 * rows[0].sigma_standard_error);
  EXPECT_NEAR(rows[1].monte_carlo_sigma, std::sqrt(2.0) * 0.25, 4 * rows[1].sigma_standard_error);
  EXPECT_TRUE(rows[0].sigma_disagrees);
  EXPECT_TRUE(rows[1].sigma_disagrees);
  EXPECT_TRUE(rows[1].mean_disagrees);  // linear mean 0, true mean σ² = 0.25
  EXPECT_LT(rows[0].sigma_relative_difference, -0.15);
  // A practical tolerance silences the flag where the difference is small: 17 % < 20 %.
  EXPECT_FALSE(CompareLinearWithMonteCarlo(lin, mc, {3.0, 0.2})[0].sigma_disagrees);
}

TEST(LinearPropagation, UndefinedAtNominalIsAStatus) {
  const ParameterSpace space({{"z", "g", Distribution::MakeNormal(0, 1), {}}});
  const Model model(1, {"y"}, [](const double* t, double* y) {
    y[0] = 1.0 / t[0];
    return t[0] != 0.0;
  });
  const LinearPropagation lin = PropagateLinear(space, model);
  EXPECT_FALSE(lin.defined);
  EXPECT_NE(lin.message.find("undefined"), std::string::npos);
  EXPECT_THROW(CompareLinearWithMonteCarlo(lin, RunMonteCarlo(space, Model(1, {"y"}, [](const double* t, double* y) {
                                                                 y[0] = t[0];
                                                                 return true;
                                                               }),
                                                               McOptions(10, 1))),
               InputError);
}

TEST(OatSweep, CurveAndSlopeAtNominal) {
  ParameterSpace space = testing::IshigamiSpace();
  ParameterSpace shifted;
  for (Parameter p : space.parameters()) {
    if (p.name == "x2") p.nominal = 0.7;
    shifted.Add(p);
  }
  const Model model = Model::Templated(3, {"y"}, testing::Ishigami{});
  const SweepResult sweep = SweepParameter(shifted, model, 1, {.points = 41});
  ASSERT_EQ(sweep.values.size(), 41u);
  EXPECT_EQ(sweep.values.front(), -3.14159265358979323846);
  EXPECT_EQ(sweep.values.back(), 3.14159265358979323846);
  for (size_t i = 0; i < 41; ++i) {
    ASSERT_TRUE(sweep.defined[i]);
    const double s = std::sin(sweep.values[i]);
    EXPECT_NEAR(sweep.outputs(static_cast<Eigen::Index>(i), 0), 7 * s * s, 1e-14);
  }
  // ∂f/∂x₂ = 2a sin x₂ cos x₂ = a sin 2x₂ at x₂ = 0.7 (x₁ = x₃ = 0).
  ASSERT_TRUE(sweep.slope_defined);
  EXPECT_EQ(sweep.method, DerivativeMethod::kAutodiff);
  EXPECT_NEAR(sweep.slope(0), 7 * std::sin(1.4), 1e-14);
  const Model black_box(3, {"y"}, [](const double* x, double* y) { return testing::Ishigami{}(x, y); });
  const SweepResult cd = SweepParameter(shifted, black_box, 1, {.points = 3, .lo = 0.0, .hi = 1.0});
  EXPECT_EQ(cd.method, DerivativeMethod::kCentralDifference);
  EXPECT_NEAR(cd.slope(0), 7 * std::sin(1.4), 1e-8 * 7);
  EXPECT_EQ(cd.values, (std::vector<double>{0.0, 0.5, 1.0}));
}

TEST(OatSweep, MarksUndefinedPointsAndRefusesBadRanges) {
  const ParameterSpace space({{"z", "g", Distribution::MakeNormal(1, 1), {}},
                              {"k", "g", Distribution::MakeFixed(2), {}}});
  const Model model(2, {"y"}, [](const double* t, double* y) {
    y[0] = std::sqrt(t[0]) * t[1];
    return t[0] >= 0;
  });
  const SweepResult sweep = SweepParameter(space, model, 0, {.points = 7});  // −2 … 4
  EXPECT_EQ(sweep.defined, (std::vector<bool>{false, false, true, true, true, true, true}));
  EXPECT_THROW(SweepParameter(space, model, 1), InputError);  // constant: needs a range
  EXPECT_NO_THROW(SweepParameter(space, model, 1, {.points = 5, .lo = 1.0, .hi = 3.0}));
  EXPECT_THROW(SweepParameter(space, model, 0, {.points = 1}), InputError);
  EXPECT_THROW(SweepParameter(space, model, 0, {.points = 5, .lo = 2.0, .hi = 1.0}), InputError);
  EXPECT_THROW(SweepParameter(space, model, 2), InputError);
}

}  // namespace
}  // namespace vstcal
