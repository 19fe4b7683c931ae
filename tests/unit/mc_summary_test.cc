// Mergeable Monte Carlo statistics: moments against two-pass sums, percentile resolution of the
// log-linear histogram, bit-identical results for any thread count and any shard split through
// JSON, memory and shard size that do not grow with the samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "support/sensitivity_models.h"
#include "vstcal/core/error.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/random/philox.h"
#include "vstcal/formats/errsim/mc_summary_json.h"
#include "vstcal/sensitivity/monte_carlo.h"

namespace vstcal {
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
  for (int sub_bins_log2 : {3, 6}) {
    HistogramSpec spec;
    spec.sub_bins_log2 = sub_bins_log2;
    const double resolution = spec.RelativeResolution();
    EXPECT_EQ(resolution, std::ldexp(1.0, -(sub_bins_log2 + 1)));
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
        EXPECT_LE(error, resolution) << "p = " << p << ", 2^" << sub_bins_log2 << " bins an octave";
        worst = std::max(worst, error);
      }
    }
    // The bound is not vacuous: errors of the order of the resolution do occur.
    EXPECT_GT(worst, 0.1 * resolution);
  }
}

TEST(LogHistogram, CentralAndOverflowBins) {
  const HistogramSpec spec{-10, 10, 4};  // |y| in [2^-10, 2^10) ≈ [1e-3, 1024)
  LogHistogram h(spec);
  for (double v : {-5e3, -1.0, -1e-4, 0.0, 1e-4, 2.0, 7e3}) h.Add(v);
  EXPECT_EQ(h.count(spec.BinOf(0.0)), 3u);  // |y| < 2^-10 share the central bin
  EXPECT_EQ(h.count(0), 1u);
  EXPECT_EQ(h.count(spec.NumBins() - 1), 1u);
  EXPECT_EQ(h.Quantile(0.5, -5e3, 7e3).value, 0.0);
  EXPECT_FALSE(h.Quantile(0.99, -5e3, 7e3).in_range);
  EXPECT_EQ(h.Quantile(0.99, -5e3, 7e3).value, 7e3);
  EXPECT_EQ(spec.BinOf(std::nan("")), spec.BinOf(0.0));
  EXPECT_THROW((HistogramSpec{1, 1, 4}.Validate()), InputError);
  EXPECT_THROW((HistogramSpec{-10, 10, 13}.Validate()), InputError);
  // Memory only for the pages in use: a few values far apart touch a few pages.
  EXPECT_LT(h.MemoryBytes(), 8 * 2048 + 1024);
}

// Every value lands in the bin whose [BinLow, BinHigh) holds its magnitude, on its side, and the
// four-lane binning agrees with the one-value one: at every bin edge (the doubles around it), at
// random magnitudes across the range, and at the central and overflow bins.
TEST(LogHistogram, BinsHoldTheirValuesAndFourLanesAgree) {
  const CounterRng rng(8, 0);
  for (const HistogramSpec& spec : {HistogramSpec{}, HistogramSpec{-10, 10, 4}, HistogramSpec{-3, 40, 0}}) {
    const size_t k = spec.BinsPerSide();
    size_t tried = 0, wrong = 0;
    std::vector<double> values;
    auto check = [&](double y) {
      for (const double v : {y, -y}) {
        ++tried;
        values.push_back(v);
        const size_t bin = spec.BinOf(v);
        const double m = std::abs(v);
        if (bin == k + 1) {
          wrong += !(m < spec.BinLow(k + 2));
        } else if (bin == 0 || bin == 2 * k + 2) {
          wrong += !(m >= std::ldexp(1.0, spec.max_exponent)) || (bin == 0) != (v < 0);
        } else {
          wrong += !(spec.BinLow(bin) <= m && m < spec.BinHigh(bin)) || (bin < k + 1) != (v < 0);
        }
      }
    };
    for (size_t b = k + 2; b < 2 * k + 2; ++b) {
      double edge = spec.BinLow(b);
      for (int step = 0; step < 3; ++step) edge = std::nextafter(edge, 0.0);
      for (int step = 0; step < 7; ++step, edge = std::nextafter(edge, HUGE_VAL)) check(edge);
    }
    for (uint64_t i = 0; i < 100000; ++i) {
      check(std::ldexp(1.0 + rng.Uniform2(i, 0)[0], static_cast<int>(rng.Uniform2(i, 0)[1] * (spec.max_exponent - spec.min_exponent + 6)) +
                                                         spec.min_exponent - 3));
    }
    for (double y : {0.0, 1e300, 1e-300, HUGE_VAL}) check(y);
    EXPECT_EQ(wrong, 0u) << "of " << tried;
    values.resize(values.size() / 4 * 4);
    size_t disagree = 0;
    for (size_t i = 0; i < values.size(); i += 4) {
      uint32_t four[4];
      spec.BinsOf4(&values[i], four);
      for (int l = 0; l < 4; ++l) disagree += four[l] != spec.BinOf(values[i + l]);
    }
    EXPECT_EQ(disagree, 0u);
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
  const std::string text = DumpJson(SummaryToJson(s));
  return SummaryFromJson(JsonDocument::Parse(text, "shard.json").root());
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
  const std::string expected_json = DumpJson(SummaryToJson(reference));
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
    EXPECT_EQ(DumpJson(SummaryToJson(merged)), expected_json);
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
    EXPECT_NEAR(got, q, 4 * se + 0.0078 * q) << p;
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
  nlohmann::json bad = nlohmann::json::parse(DumpJson(SummaryToJson(first)));
  bad["format"] = "vstcal/mc-summary@1";
  EXPECT_THROW(SummaryFromJson(JsonDocument::Parse(bad.dump(), "x.json").root()), InputError);
  bad = nlohmann::json::parse(DumpJson(SummaryToJson(first)));
  bad["histograms"][0][0][1] = 999999;  // counts no longer match the moments
  EXPECT_THROW(SummaryFromJson(JsonDocument::Parse(bad.dump(), "x.json").root()), InputError);
}

// A block's moments from four lanes of power sums about one of its values equal two-pass sums,
// also with a mean far from zero.
TEST(BlockAccumulator, PowerSumsMatchTwoPassMoments) {
  const std::vector<double> x = NormalSample(1024, 1e6, 3.0, 6);
  SummaryPlan plan;
  plan.output_names = {"x"};
  plan.total_samples = x.size();
  BlockAccumulator block(plan);
  for (double v : x) block.Add(&v);
  MonteCarloSummary summary(plan);
  summary.AddBlock(0, block);
  double offset = 0;
  for (double v : x) offset += v - 1e6;
  const double mean = 1e6 + offset / static_cast<double>(x.size());
  double m2 = 0;
  for (double v : x) m2 += (v - mean) * (v - mean);
  const OutputStatistics s = summary.Statistics(0);
  EXPECT_NEAR(s.mean, mean, 1e-9);
  EXPECT_NEAR(s.standard_deviation, std::sqrt(m2 / (x.size() - 1)), 1e-9);
  EXPECT_EQ(s.max, *std::max_element(x.begin(), x.end()));
  // A constant gives exactly zero spread (the shift is one of its values).
  BlockAccumulator constant(plan);
  for (size_t i = 0; i < x.size(); ++i) {
    const double c = 0.1;
    constant.Add(&c);
  }
  MonteCarloSummary constant_summary(plan);
  constant_summary.AddBlock(0, constant);
  EXPECT_EQ(constant_summary.Statistics(0).standard_deviation, 0.0);
  EXPECT_EQ(constant_summary.Statistics(0).mean, 0.1);
}

// err-sim's loop adds four samples at a time (AddLanes): groups where every output is defined in
// every lane take a path without masks and are counted once for all outputs. Both paths, and a
// last partial group, must give the bits of adding the samples one at a time (Add, AddUndefined).
TEST(BlockAccumulator, FourLanesAtATimeGiveTheBitsOfOneAtATime) {
  constexpr size_t kLanes = BlockAccumulator::kLanes, kSamples = 1022;  // 255 groups and a half
  SummaryPlan plan;
  plan.output_names = {"a", "b", "c"};
  plan.total_samples = kSamples;
  plan.higher_moments = true;
  const std::vector<double> a = NormalSample(kSamples, 1e3, 2.0, 7), b = NormalSample(kSamples, -5.0, 0.1, 8);
  // Sample s is undefined where s % 37 == 5: about one group in nine takes the masked path.
  auto undefined = [](size_t s) { return s % 37 == 5; };
  BlockAccumulator lanes(plan), one(plan);
  for (size_t first = 0; first < kSamples; first += kLanes) {
    const size_t count = std::min(kLanes, kSamples - first);
    double y[3 * kLanes] = {};
    uint8_t defined[3] = {};
    uint64_t incomplete = 0;
    for (size_t l = 0; l < count; ++l) {
      const size_t s = first + l;
      const double row[3] = {a[s], b[s], a[s] * b[s]};
      for (size_t k = 0; k < 3; ++k) y[kLanes * k + l] = row[k];
      if (undefined(s)) {
        ++incomplete;
        one.AddUndefined();
      } else {
        for (uint8_t& d : defined) d |= static_cast<uint8_t>(1u << l);
        one.Add(row);
      }
    }
    lanes.AddLanes(y, defined, count, incomplete);
  }
  MonteCarloSummary by_lanes(plan), by_one(plan);
  by_lanes.AddBlock(0, lanes);
  by_one.AddBlock(0, one);
  size_t expected_count = 0;
  for (size_t s = 0; s < kSamples; ++s) expected_count += !undefined(s);
  EXPECT_EQ(by_lanes.undefined_samples(), kSamples - expected_count);
  for (size_t k = 0; k < 3; ++k) {
    const OutputStatistics x = by_lanes.Statistics(k), y = by_one.Statistics(k);
    EXPECT_EQ(x.count, expected_count);
    EXPECT_EQ(y.count, expected_count);
    EXPECT_EQ(std::bit_cast<uint64_t>(x.mean), std::bit_cast<uint64_t>(y.mean)) << k;
    EXPECT_EQ(std::bit_cast<uint64_t>(x.standard_deviation), std::bit_cast<uint64_t>(y.standard_deviation)) << k;
    EXPECT_EQ(std::bit_cast<uint64_t>(x.standard_deviation_standard_error),
              std::bit_cast<uint64_t>(y.standard_deviation_standard_error))
        << k;
    EXPECT_EQ(x.min, y.min);
    EXPECT_EQ(x.max, y.max);
    EXPECT_EQ(x.p95.value, y.p95.value);
  }
}

// A summary holds a few tree nodes per level: its memory and its JSON do not grow with the number
// of samples (only with log₂ of the blocks), and a shard's nodes are at most two a level.
TEST(MonteCarloSummary, MemoryAndShardSizeDoNotGrowWithTheSamples) {
  const ParameterSpace space = testing::IshigamiSpace();
  const Model model = Model::Templated(3, {"y", "y2", "c"}, ThreeOutputs{});
  MonteCarloOptions o = Options(SamplingMethod::kPseudoRandom);
  o.block_size = 64;
  std::vector<size_t> bytes, text;
  for (uint64_t samples : {6400u, 640000u}) {
    o.samples = samples;
    o.shard = 1;
    o.shards = 3;
    const MonteCarloSummary shard = RunMonteCarlo(space, model, o);
    bytes.push_back(shard.MemoryBytes());
    text.push_back(DumpJson(SummaryToJson(shard)).size());
    const uint64_t levels = static_cast<uint64_t>(std::ceil(std::log2(static_cast<double>(samples / 64)))) + 1;
    EXPECT_LE(shard.nodes().size(), 2 * levels) << samples;
  }
  // 100× the samples: the histograms fill a few more bins and the tree has 7 more levels.
  EXPECT_LT(bytes[1], 2 * bytes[0]);
  EXPECT_LT(text[1], 3 * text[0]);
}

}  // namespace
}  // namespace vstcal
