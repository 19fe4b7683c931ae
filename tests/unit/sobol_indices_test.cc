// Sobol indices against closed forms (Ishigami, Sobol' G, a grouped model), with pseudo-random
// and quasi-random sampling; determinism across thread counts; undefined and constant models.
//
// Tolerance: an estimate must lie within 4 bootstrap standard errors of the analytic index
// (two-sided probability 6e-5 per check for a normal estimator, under 0.5 % over the ~70 checks
// here). Each test also shows the check has teeth: the standard errors are small enough that a
// neighbouring model's indices would fail it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/sensitivity_models.h"
#include "vstcal/core/error.h"
#include "vstcal/sensitivity/sobol_indices.h"

namespace vstcal {
namespace {

std::string MethodName(const ::testing::TestParamInfo<SamplingMethod>& param) {
  return param.param == SamplingMethod::kSobol ? "Sobol" : "Philox";
}

constexpr double kSigmas = 4.0;

void ExpectMatches(const OutputSensitivity& out, const testing::AnalyticIndices& truth, const char* label) {
  ASSERT_EQ(out.groups.size(), truth.first.size());
  for (size_t g = 0; g < truth.first.size(); ++g) {
    const Estimate& s = out.groups[g].first_order;
    const Estimate& st = out.groups[g].total;
    EXPECT_NEAR(s.value, truth.first[g], kSigmas * s.standard_error) << label << " S of group " << g;
    EXPECT_NEAR(st.value, truth.total[g], kSigmas * st.standard_error) << label << " ST of group " << g;
    EXPECT_LE(s.interval.lo, s.value);
    EXPECT_GE(s.interval.hi, s.value);
  }
}

// The largest distance, in standard errors, between the estimates and another set of indices.
double WorstZ(const OutputSensitivity& out, const testing::AnalyticIndices& other) {
  double worst = 0;
  for (size_t g = 0; g < other.first.size(); ++g) {
    const Estimate& s = out.groups[g].first_order;
    const Estimate& st = out.groups[g].total;
    if (s.standard_error > 0) worst = std::max(worst, std::abs(s.value - other.first[g]) / s.standard_error);
    if (st.standard_error > 0) worst = std::max(worst, std::abs(st.value - other.total[g]) / st.standard_error);
  }
  return worst;
}

SobolOptions Options(SamplingMethod method, uint64_t samples, uint64_t seed) {
  SobolOptions o;
  o.samples = samples;
  o.sampling = {method, seed, 0};
  o.bootstrap_resamples = 300;
  o.bootstrap_seed = seed + 1;
  o.threads = 2;
  return o;
}

class IshigamiTest : public ::testing::TestWithParam<SamplingMethod> {};

TEST_P(IshigamiTest, ReproducesAnalyticIndices) {
  const testing::AnalyticIndices truth = testing::IshigamiIndices(7.0, 0.1);
  // The closed form gives the published values (Saltelli et al. 2008, §4.1).
  EXPECT_NEAR(truth.first[0], 0.3139, 5e-5);
  EXPECT_NEAR(truth.first[1], 0.4424, 5e-5);
  EXPECT_NEAR(truth.total[0], 0.5576, 5e-5);
  EXPECT_NEAR(truth.total[2], 0.2437, 5e-5);

  const Model model = Model::Templated(3, {"y"}, testing::Ishigami{7.0, 0.1});
  const SobolResult r = EstimateSobolIndices(testing::IshigamiSpace(), model, Options(GetParam(), 1 << 14, 2024));
  ASSERT_EQ(r.status, SobolStatus::kOk) << r.message;
  EXPECT_EQ(r.evaluations, (1u << 14) * 5u);
  EXPECT_EQ(r.group_names, (std::vector<std::string>{"x1", "x2", "x3"}));
  ExpectMatches(r.outputs[0], truth, SamplingMethodName(GetParam()).c_str());
  // Teeth: Ishigami with b = 0.13 has S₁ = 0.36, ST₃ = 0.32 — far outside the tolerance.
  EXPECT_GT(WorstZ(r.outputs[0], testing::IshigamiIndices(7.0, 0.13)), 2 * kSigmas);
  // V = a²/8 + bπ⁴/5 + b²π⁸/18 + ½ = 13.845; its estimate within a few per cent.
  EXPECT_NEAR(r.outputs[0].variance, 13.8446, 0.05 * 13.8446);
}

INSTANTIATE_TEST_SUITE_P(Sampling, IshigamiTest,
                         ::testing::Values(SamplingMethod::kPseudoRandom, SamplingMethod::kSobol),
                         MethodName);

TEST(SobolIndices, QuasiRandomBeatsPseudoRandomOnIshigami) {
  // Same N: the QMC estimate's total absolute error should be below the pseudo-random one's
  // bootstrap standard errors summed (the QMC error converges nearly as 1/N, MC as 1/√N).
  const testing::AnalyticIndices truth = testing::IshigamiIndices(7.0, 0.1);
  const Model model = Model::Templated(3, {"y"}, testing::Ishigami{});
  const SobolResult mc = EstimateSobolIndices(testing::IshigamiSpace(), model, Options(SamplingMethod::kPseudoRandom, 1 << 14, 7));
  const SobolResult qmc = EstimateSobolIndices(testing::IshigamiSpace(), model, Options(SamplingMethod::kSobol, 1 << 14, 7));
  double qmc_error = 0, mc_se = 0;
  for (size_t g = 0; g < 3; ++g) {
    qmc_error += std::abs(qmc.outputs[0].groups[g].first_order.value - truth.first[g]) +
                 std::abs(qmc.outputs[0].groups[g].total.value - truth.total[g]);
    mc_se += mc.outputs[0].groups[g].first_order.standard_error + mc.outputs[0].groups[g].total.standard_error;
  }
  EXPECT_LT(qmc_error, mc_se);
}

TEST(SobolIndices, SobolGFunction) {
  const std::vector<double> a = {0, 1, 4.5, 9, 99, 99, 99, 99};
  const testing::AnalyticIndices truth = testing::SobolGIndices(a);
  const double published[] = {0.7162, 0.1790, 0.0237, 0.0072, 7.2e-5, 7.2e-5, 7.2e-5, 7.2e-5};
  for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(truth.first[i], published[i], 5e-5 * std::max(1.0, published[i] / 0.01));
  const Model model = Model::Templated(8, {"y"}, testing::SobolG{a});
  for (SamplingMethod method : {SamplingMethod::kPseudoRandom, SamplingMethod::kSobol}) {
    const SobolResult r = EstimateSobolIndices(testing::SobolGSpace(8), model, Options(method, 1 << 14, 11));
    ASSERT_EQ(r.status, SobolStatus::kOk);
    ExpectMatches(r.outputs[0], truth, SamplingMethodName(method).c_str());
    // Teeth: swapping the first two variables' roles is detected.
    testing::AnalyticIndices swapped = truth;
    std::swap(swapped.first[0], swapped.first[1]);
    EXPECT_GT(WorstZ(r.outputs[0], swapped), 2 * kSigmas);
  }
}

TEST(SobolIndices, GroupedIndicesOfAGroupedModel) {
  const testing::AnalyticIndices truth = testing::GroupedIndices();
  const Model model = Model::Templated(6, {"y"}, testing::GroupedModel{});
  for (SamplingMethod method : {SamplingMethod::kPseudoRandom, SamplingMethod::kSobol}) {
    const SobolResult r = EstimateSobolIndices(testing::GroupedSpace(), model, Options(method, 1 << 14, 5));
    ASSERT_EQ(r.status, SobolStatus::kOk);
    EXPECT_EQ(r.group_names, (std::vector<std::string>{"g1", "g2", "g3", "bias"}));
    // The constant "bias" group is not evaluated and is exactly zero.
    EXPECT_EQ(r.evaluations, (1u << 14) * 5u);
    EXPECT_EQ(r.outputs[0].groups[3].first_order.value, 0.0);
    EXPECT_EQ(r.outputs[0].groups[3].total.standard_error, 0.0);
    ExpectMatches(r.outputs[0], truth, SamplingMethodName(method).c_str());
    // Teeth: g1's index is not the sum of its members' (v₁ + v₂)/V: the in-group interaction counts.
    testing::AnalyticIndices ungrouped = truth;
    ungrouped.first[0] = ungrouped.total[0] = (1.0 + 0.64) / 7.8;
    EXPECT_GT(WorstZ(r.outputs[0], ungrouped), 2 * kSigmas);
  }
}

std::vector<double> Flatten(const SobolResult& r) {
  std::vector<double> v;
  for (const OutputSensitivity& o : r.outputs) {
    v.push_back(o.mean);
    v.push_back(o.variance);
    for (const GroupSensitivity& g : o.groups) {
      for (const Estimate* e : {&g.first_order, &g.total}) {
        v.insert(v.end(), {e->value, e->standard_error, e->interval.lo, e->interval.hi});
      }
    }
  }
  return v;
}

TEST(SobolIndices, BitIdenticalForAnyThreadCount) {
  const Model model = Model::Templated(3, {"y"}, testing::Ishigami{});
  for (SamplingMethod method : {SamplingMethod::kPseudoRandom, SamplingMethod::kSobol}) {
    SobolOptions o = Options(method, 1000, 3);  // not a multiple of the task size
    o.bootstrap_resamples = 50;
    o.threads = 1;
    const std::vector<double> one = Flatten(EstimateSobolIndices(testing::IshigamiSpace(), model, o));
    for (unsigned threads : {2u, 4u}) {
      o.threads = threads;
      EXPECT_EQ(Flatten(EstimateSobolIndices(testing::IshigamiSpace(), model, o)), one) << threads << " threads";
    }
    o.sampling.seed = 4;
    EXPECT_NE(Flatten(EstimateSobolIndices(testing::IshigamiSpace(), model, o)), one);
  }
}

TEST(SobolIndices, UndefinedModelGivesAStatusNotNumbers) {
  const Model model(3, {"y"}, [](const double* x, double* y) {
    y[0] = x[0];
    return x[0] < 3.0;  // undefined on a sliver of the cube
  });
  const SobolResult r = EstimateSobolIndices(testing::IshigamiSpace(), model, Options(SamplingMethod::kPseudoRandom, 4096, 1));
  EXPECT_EQ(r.status, SobolStatus::kModelUndefined);
  EXPECT_GT(r.undefined_evaluations, 0u);
  EXPECT_TRUE(r.outputs.empty());
  EXPECT_NE(r.message.find("undefined"), std::string::npos);
}

TEST(SobolIndices, ConstantOutputHasZeroIndices) {
  const Model model(3, {"y", "c"}, [](const double* x, double* y) {
    y[0] = x[0];
    y[1] = 1.0;
    return true;
  });
  const SobolResult r = EstimateSobolIndices(testing::IshigamiSpace(), model, Options(SamplingMethod::kSobol, 256, 1));
  ASSERT_EQ(r.status, SobolStatus::kOk);
  EXPECT_EQ(r.outputs[1].variance, 0.0);
  for (const GroupSensitivity& g : r.outputs[1].groups) EXPECT_EQ(g.total.value, 0.0);
  // y = x₁ exactly: S₁ = ST₁ = 1 up to sampling error; the others 0 exactly (A_B^g equals A).
  EXPECT_NEAR(r.outputs[0].groups[0].total.value, 1.0, 0.05);
  EXPECT_EQ(r.outputs[0].groups[1].total.value, 0.0);
}

TEST(SobolIndices, RefusesBadOptions) {
  const Model model = Model::Templated(3, {"y"}, testing::Ishigami{});
  SobolOptions o;
  o.samples = 1;
  EXPECT_THROW(EstimateSobolIndices(testing::IshigamiSpace(), model, o), InputError);
  o.samples = 16;
  o.confidence = 1.0;
  EXPECT_THROW(EstimateSobolIndices(testing::IshigamiSpace(), model, o), InputError);
  const Model wrong = Model::Templated(8, {"y"}, testing::SobolG{std::vector<double>(8, 1.0)});
  EXPECT_THROW(EstimateSobolIndices(testing::IshigamiSpace(), wrong, SobolOptions{}), InputError);
}

}  // namespace
}  // namespace vstcal
