// Sensitivity module throughput (docs/performance.md#sensitivity).
//  - Sobol-index estimation on Ishigami: model evaluations per second through the whole
//    estimator (points, inverse CDFs, evaluations, sums), without and with the bootstrap.
//  - Sampling cost per draw: one coordinate of a point of the unit cube mapped through Φ⁻¹, from
//    Philox and from Boost's Sobol sequence (with the digital shift).
#include <benchmark/benchmark.h>

#include <vector>

#include "support/sensitivity_models.h"
#include "vstcal/sensitivity/normal_quantile.h"
#include "vstcal/sensitivity/sobol_indices.h"
#include "vstcal/sensitivity/unit_points.h"

using namespace vstcal;

namespace {


void SobolIshigami(benchmark::State& state, SamplingMethod method, size_t bootstrap) {
  const ParameterSpace space = vstcal::testing::IshigamiSpace();
  const Model model = Model::Templated(3, {"y"}, vstcal::testing::Ishigami{});
  SobolOptions options;
  options.samples = static_cast<uint64_t>(state.range(0));
  options.sampling = {method, 1, 0};
  options.bootstrap_resamples = bootstrap;
  options.threads = static_cast<unsigned>(state.range(1));
  uint64_t evaluations = 0;
  for (auto _ : state) {
    const SobolResult r = EstimateSobolIndices(space, model, options);
    evaluations += r.evaluations;
    benchmark::DoNotOptimize(r.outputs.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(evaluations));
}

void BM_SobolIshigamiPhilox(benchmark::State& state) { SobolIshigami(state, SamplingMethod::kPseudoRandom, 0); }
void BM_SobolIshigamiQmc(benchmark::State& state) { SobolIshigami(state, SamplingMethod::kSobol, 0); }
void BM_SobolIshigamiQmcBootstrap500(benchmark::State& state) { SobolIshigami(state, SamplingMethod::kSobol, 500); }

// Wall time: the two-thread runs are what a user waits for.
BENCHMARK(BM_SobolIshigamiPhilox)->Args({1 << 14, 1})->Args({1 << 14, 2})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SobolIshigamiQmc)->Args({1 << 14, 1})->Args({1 << 14, 2})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SobolIshigamiQmcBootstrap500)->Args({1 << 14, 2})->UseRealTime()->Unit(benchmark::kMillisecond);

// Points of d = 8 dimensions in batches of 1,024, each coordinate through Φ⁻¹.
void Draws(benchmark::State& state, SamplingMethod method) {
  constexpr size_t kDims = 8, kBatch = 1024;
  const UnitPoints points({method, 1, 0}, kDims);
  std::vector<double> u(kDims * kBatch);
  uint64_t first = 0;
  for (auto _ : state) {
    points.Fill(first, kBatch, u.data());
    for (double& x : u) x = NormalQuantile(x);
    benchmark::DoNotOptimize(u.data());
    first += kBatch;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kDims * kBatch));
}

void BM_DrawPhiloxNormal(benchmark::State& state) { Draws(state, SamplingMethod::kPseudoRandom); }
void BM_DrawSobolNormal(benchmark::State& state) { Draws(state, SamplingMethod::kSobol); }
BENCHMARK(BM_DrawPhiloxNormal)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DrawSobolNormal)->Unit(benchmark::kMicrosecond);

// The uniform alone, to split each draw's cost between the generator and Φ⁻¹.
void Uniforms(benchmark::State& state, SamplingMethod method) {
  constexpr size_t kDims = 8, kBatch = 1024;
  const UnitPoints points({method, 1, 0}, kDims);
  std::vector<double> u(kDims * kBatch);
  uint64_t first = 0;
  for (auto _ : state) {
    points.Fill(first, kBatch, u.data());
    benchmark::DoNotOptimize(u.data());
    first += kBatch;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kDims * kBatch));
}
void BM_DrawPhiloxUniform(benchmark::State& state) { Uniforms(state, SamplingMethod::kPseudoRandom); }
void BM_DrawSobolUniform(benchmark::State& state) { Uniforms(state, SamplingMethod::kSobol); }
BENCHMARK(BM_DrawPhiloxUniform)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DrawSobolUniform)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
