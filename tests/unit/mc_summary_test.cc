// Mergeable Monte Carlo statistics: moments against two-pass sums, percentile resolution of the
// log histogram, bit-identical results for any thread count and any shard split through JSON.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/sensitivity_models.h"
#include "vstcal/core/error.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/random/philox.h"
#include "vstcal/sensitivity/mc_summary_json.h"
#include "vstcal/sensitivity/monte_carlo.h"

namespace vstcal::sensitivity {
namespace {

std::string MethodName(const ::testing::TestParamInfo<SamplingMethod>& param) {
  return param.param == SamplingMethod::kSobol ? "Sobol" : "Philox";
}

std::vector<double> NormalSample(size_t n, double mean, double sigma, uint64_t seed) {
  const CounterRng rng(seed, 0);
  std::vector<double> x;
  for (size_t i = 0; i < n; ++i) x.push_back(mean + sigma * rng.Normal2(i, 0)[0]);
  return x;
}

TEST(Moments, OnePassAndMergedMatchTwoPassSums) {
  const std::vector<double> x = NormalSample(10000, 1e6, 3.0, 5);  // large mean: sums of powers would fail
  // Reference: deviations from 1e6 are exact (Sterbenz), so this mean is accurate to ~1 ulp.
  double offset_sum = 0;
  for (double v : x) offset_sum += v - 1e6;
  const double mean = 1e6 + offset_sum / static_cast<double>(x.size());
  double m2 = 0, m3 = 0, m4 = 0;
  for (double v : x) {
    const double d = v - mean;
    m2 += d * d;
    m3 += d * d * d;
    m4 += d * d * d * d;
  }
  Moments all, left, right;
  for (size_t i = 0; i < x.size(); ++i) {
    all.Add(x[i]);
    (i < 3000 ? left : right).Add(x[i]);
  }
  left.Merge(right);
  for (const Moments* m : {&all, &left}) {
    EXPECT_EQ(m->count, x.size());
    // One-pass updates round the mean 10⁴ times: a random walk of ~√N ulps of 1e6 (1.2e-10 each).
    EXPECT_NEAR(m->mean, mean, 1e-7);
    EXPECT_NEAR(m->m2, m2, 1e-9 * m2);
    EXPECT_NEAR(m->m3, m3, 1e-6 * std::sqrt(m2 * m4));  // m3 ≈ 0: compare on the scale of its spread
    EXPECT_NEAR(m->m4, m4, 1e-9 * m4);
    EXPECT_EQ(m->max, *std::max_element(x.begin(), x.end()));
    EXPECT_EQ(m->min, *std::min_element(x.begin(), x.end()));
  }
  // Normal data: the σ standard error is σ/√(2(N−1)) up to the sampling error of the kurtosis.
  EXPECT_NEAR(all.StandardDeviationStandardError(), 3.0 / std::sqrt(2.0 * 9999), 0.1 * 3.0 / std::sqrt(2.0 * 9999));
}

// The exact sample quantile the histogram approximates: the order statistic of rank ⌈pN⌉.
double OrderStatistic(std::vector<double> x, double p) {
  std::sort(x.begin(), x.end());
  return x[static_cast<size_t>(std::ceil(p * static_cast<double>(x.size()))) - 1];
}

TEST(LogHistogram, PercentilesWithinTheDocumentedResolution) {
  const std::vector<double> normal = NormalSample(100000, 0.0, 2.0, 9);
  std::vector<double> lognormal;
  for (double v : normal) lognormal.push_back(std::exp(v));
  for (int bins_per_decade : {10, 200}) {
    HistogramSpec spec;
    spec.bins_per_decade = bins_per_decade;
    const double resolution = spec.RelativeResolution();
    EXPECT_NEAR(resolution, std::pow(10.0, 0.5 / bins_per_decade) - 1, 1e-15);
    double worst = 0;
    for (const std::vector<double>* sample : std::initializer_list<const std::vector<double>*>{&normal, &lognormal}) {
      LogHistogram h(spec);
      for (double v : *sample) h.Add(v);
      const double lo = *std::min_element(sample->begin(), sample->end());
      const double hi = *std::max_element(sample->begin(), sample->end());
      for (double p : {0.01, 0.05, 0.3, 0.5, 0.95, 0.99}) {
        const double exact = OrderStatistic(*sample, p);
        const Percentile got = h.Quantile(p, lo, hi);
        ASSERT_TRUE(got.in_range);
        const double error = std::abs(got.value / exact - 1);
        EXPECT_LE(error, resolution) << "p = " << p << ", " << bins_per_decade << " bins/decade";
        worst = std::max(worst, error);
      }
    }
    // The bound is not vacuous: errors of the order of the resolution do occur.
    EXPECT_GT(worst, 0.1 * resolution);
  }
}

TEST(LogHistogram, CentralAndOverflowBins) {
  HistogramSpec spec{1e-3, 1e3, 20};
  LogHistogram h(spec);
  for (double v : {-5e3, -1.0, -1e-4, 0.0, 1e-4, 2.0, 7e3}) h.Add(v);
  EXPECT_EQ(h.counts()[spec.BinOf(0.0)], 3u);  // |y| < 1e-3 share the central bin
  EXPECT_EQ(h.counts().front(), 1u);
  EXPECT_EQ(h.counts().back(), 1u);
  EXPECT_EQ(h.Quantile(0.5, -5e3, 7e3).value, 0.0);
  EXPECT_FALSE(h.Quantile(0.99, -5e3, 7e3).in_range);
  EXPECT_EQ(h.Quantile(0.99, -5e3, 7e3).value, 7e3);
  EXPECT_THROW((HistogramSpec{1.0, 1.0, 10}.Validate()), InputError);
  EXPECT_THROW((HistogramSpec{1e-3, 1.0, 0}.Validate()), InputError);
}

// The binner without logarithms puts every value where BinOf's log10 does: at each bin edge (the
// doubles around min·10^(b/d), where log10's rounding decides), across the range, at the central
// and overflow bins, on both sides.
TEST(HistogramBinner, AgreesWithBinOfOnEveryValueTried) {
  const CounterRng rng(8, 0);
  for (const HistogramSpec& spec : {HistogramSpec{}, HistogramSpec{1e-3, 1e3, 20}, HistogramSpec{0.37, 5e4, 7},
                                    HistogramSpec{1e-12, 1e15, 1000}}) {
    const HistogramBinner binner(spec);
    size_t tried = 0, disagree = 0;
    auto check = [&](double y) {
      ++tried;
      disagree += binner.BinOf(y) != spec.BinOf(y) || binner.BinOf(-y) != spec.BinOf(-y);
    };
    const double decades = std::log10(spec.max_magnitude / spec.min_magnitude);
    for (int b = 0; b <= static_cast<int>(decades * spec.bins_per_decade) + 1; ++b) {
      double edge = spec.min_magnitude * std::pow(10.0, static_cast<double>(b) / spec.bins_per_decade);
      for (int step = 0; step < 4; ++step) edge = std::nextafter(edge, 0.0);
      for (int step = 0; step < 9; ++step, edge = std::nextafter(edge, HUGE_VAL)) check(edge);
    }
    for (uint64_t i = 0; i < 200000; ++i) {
      check(spec.min_magnitude * std::pow(10.0, (1.2 * rng.Uniform2(i, 0)[0] - 0.1) * decades));
    }
    for (double y : {0.0, spec.min_magnitude, spec.max_magnitude, 1e300, 1e-300}) check(y);
    EXPECT_EQ(disagree, 0u) << "of " << tried << " values, spec " << spec.min_magnitude << ", " << spec.max_magnitude
                            << ", " << spec.bins_per_decade;
    EXPECT_EQ(&HistogramBinner::For(spec), &HistogramBinner::For(spec));
  }
}

// Three outputs of different character: Ishigami (signed), its magnitude, and a constant.
struct ThreeOutputs {
  template <typename T>
  bool operator()(const T* x, T* y) const {
    testing::Ishigami{}(x, y);
    y[1] = y[0] * y[0];
    y[2] = T(4.0);
    return true;
  }
};

MonteCarloOptions Options(SamplingMethod method) {
  MonteCarloOptions o;
  o.samples = 10007;  // a last block shorter than the others
  o.block_size = 512;
  o.sampling = {method, 77, 0};
  o.run_id = "test";
  return o;
}

MonteCarloSummary ThroughJson(const MonteCarloSummary& s) {
  const std::string text = io::DumpJson(SummaryToJson(s));
  return SummaryFromJson(io::JsonDocument::Parse(text, "shard.json").root());
}

std::vector<double> Flatten(const MonteCarloSummary& s) {
  std::vector<double> v;
  for (const OutputStatistics& o : s.AllStatistics()) {
    v.insert(v.end(), {static_cast<double>(o.count), o.mean, o.standard_deviation, o.rms, o.min, o.max,
                       o.mean_standard_error, o.standard_deviation_standard_error, o.p50.value, o.p95.value,
                       o.p99.value});
  }
  return v;
}

class MonteCarloDeterminism : public ::testing::TestWithParam<SamplingMethod> {};

TEST_P(MonteCarloDeterminism, BitIdenticalForThreadsAndShards) {
  const ParameterSpace space = testing::IshigamiSpace();
  const Model model = Model::Templated(3, {"y", "y2", "c"}, ThreeOutputs{});
  MonteCarloOptions o = Options(GetParam());
  o.threads = 1;
  const MonteCarloSummary reference = RunMonteCarlo(space, model, o);
  ASSERT_TRUE(reference.complete());
  const std::vector<double> expected = Flatten(reference);
  const std::string expected_json = io::DumpJson(SummaryToJson(reference));
  for (unsigned threads : {2u, 4u}) {
    o.threads = threads;
    EXPECT_EQ(Flatten(RunMonteCarlo(space, model, o)), expected) << threads << " threads";
  }
  for (uint64_t shards : {2u, 3u, 7u}) {
    std::vector<MonteCarloSummary> parts;
    for (uint64_t i = 0; i < shards; ++i) {
      o.shard = i;
      o.shards = shards;
      o.threads = 1 + static_cast<unsigned>(i % 2);
      parts.push_back(ThroughJson(RunMonteCarlo(space, model, o)));
      EXPECT_EQ(parts.back().complete(), false);
    }
    // Merge in reverse order: arrival order must not matter.
    MonteCarloSummary merged = parts.back();
    for (size_t i = parts.size() - 1; i-- > 0;) merged.Merge(parts[i]);
    ASSERT_TRUE(merged.complete()) << shards << " shards";
    EXPECT_EQ(Flatten(merged), expected) << shards << " shards";
    EXPECT_EQ(io::DumpJson(SummaryToJson(merged)), expected_json);
  }
}

INSTANTIATE_TEST_SUITE_P(Sampling, MonteCarloDeterminism,
                         ::testing::Values(SamplingMethod::kPseudoRandom, SamplingMethod::kSobol),
                         MethodName);

TEST(MonteCarloSummary, StatisticsOfAKnownDistribution) {
  // y = x₁ ~ U(−π, π): mean 0, σ = π/√3, RMS = σ, max → π, p95 = 0.9π, p99 = 0.98π.
  const ParameterSpace space = testing::IshigamiSpace();
  const Model model(3, {"x1"}, [](const double* x, double* y) {
    y[0] = x[0];
    return true;
  });
  MonteCarloOptions o = Options(SamplingMethod::kPseudoRandom);
  o.samples = 100000;
  const OutputStatistics s = RunMonteCarlo(space, model, o).Statistics(0);
  const double pi = 3.14159265358979323846, sigma = pi / std::sqrt(3.0);
  EXPECT_EQ(s.count, 100000u);
  EXPECT_NEAR(s.mean, 0.0, 4 * s.mean_standard_error);
  EXPECT_NEAR(s.standard_deviation, sigma, 4 * s.standard_deviation_standard_error);
  EXPECT_NEAR(s.rms, sigma, 4 * s.standard_deviation_standard_error + 4 * s.mean_standard_error);
  EXPECT_NEAR(s.max, pi, 1e-3);
  // Quantile q of U(−π, π): SE of a sample quantile √(p(1−p)/N)/density = 2π√(p(1−p)/N), plus the
  // histogram's 0.58 %.
  for (auto [p, q] : {std::pair{0.95, 0.9 * pi}, std::pair{0.99, 0.98 * pi}}) {
    const double se = 2 * pi * std::sqrt(p * (1 - p) / 1e5);
    const double got = p == 0.95 ? s.p95.value : s.p99.value;
    EXPECT_NEAR(got, q, 4 * se + 0.0058 * q) << p;
  }
}

TEST(MonteCarloSummary, CountsUndefinedSamples) {
  const ParameterSpace space = testing::IshigamiSpace();
  const Model model(3, {"y"}, [](const double* x, double* y) {
    y[0] = x[0];
    return x[0] < 0;
  });
  MonteCarloOptions o = Options(SamplingMethod::kSobol);
  o.samples = 4096;
  const MonteCarloSummary s = RunMonteCarlo(space, model, o);
  EXPECT_EQ(s.undefined_samples() + s.Statistics(0).count, 4096u);
  EXPECT_EQ(s.undefined_samples(), 2048u);  // a net puts exactly half of its points at x₁ ≥ 0
  EXPECT_LT(s.Statistics(0).max, 0.0);
}

TEST(MonteCarloSummary, RefusesBadMerges) {
  const ParameterSpace space = testing::IshigamiSpace();
  const Model model = Model::Templated(3, {"y", "y2", "c"}, ThreeOutputs{});
  MonteCarloOptions o = Options(SamplingMethod::kPseudoRandom);
  o.shards = 2;
  const MonteCarloSummary first = RunMonteCarlo(space, model, o);
  MonteCarloSummary twice = first;
  EXPECT_THROW(twice.Merge(first), InputError);  // the same shard twice
  EXPECT_THROW(first.Statistics(0), InputError);  // incomplete
  o.run_id = "another run";
  o.shard = 1;
  MonteCarloSummary other_run = RunMonteCarlo(space, model, o);
  EXPECT_THROW(other_run.Merge(first), InputError);
  o.shard = 2;
  EXPECT_THROW(RunMonteCarlo(space, model, o), InputError);  // shard 2/2
  nlohmann::json bad = nlohmann::json::parse(io::DumpJson(SummaryToJson(first)));
  bad["format"] = "vstcal/mc-summary@2";
  EXPECT_THROW(SummaryFromJson(io::JsonDocument::Parse(bad.dump(), "x.json").root()), InputError);
  bad = nlohmann::json::parse(io::DumpJson(SummaryToJson(first)));
  bad["histograms"][0][0][1] = 999999;  // counts no longer match the moments
  EXPECT_THROW(SummaryFromJson(io::JsonDocument::Parse(bad.dump(), "x.json").root()), InputError);
}

}  // namespace
}  // namespace vstcal::sensitivity
