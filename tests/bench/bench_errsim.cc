// err-sim throughput on the shipped seed 001 chain (datasets/vst/seed001.json: both eyes, 5 test
// points, all seven sources active, 75 random parameters). Targets (issues 4 and 12): ≥ 2 million
// chain samples per second per core; the whole `err-sim run` loop, statistics included, ≥ 1.5
// million per core.
//   BM_DrawTheta          θ for one sample (ThetaSampler::FillLanes): the random numbers alone
//   BM_ChainSample        θ + the chain (both eyes, 5 points) + every error measure: one chain
//                         sample, four at a time as err-sim run evaluates them (SampleMeasurer)
//   BM_ChainSampleScalar  the same one sample at a time throughout (θ by Fill, the chain with
//                         double): what drawing and evaluating four together gains
//   BM_EngineSample       the whole Monte Carlo loop of `err-sim run` per sample, with the mergeable
//                         statistics (moments of 64 outputs, histograms of 30), one thread
//   BM_EngineBudgetSample the same for a budget scenario (the totals' 26 outputs, no histograms)
// The NumPy peer (scripts/bench-errsim-numpy.py) runs the same chain; scripts/bench prints both.
#include <benchmark/benchmark.h>

#include <memory>

#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/engine.h"
#include "vstcal/errsim/formats/chain_reader.h"
#include "vstcal/errsim/measures.h"
#include "vstcal/errsim/sample_measurer.h"
#include "vstcal/errsim/sampler.h"

namespace {

using namespace vstcal::errsim;
using vstcal::SimdDouble;

const ChainModel& Seed001() {
  static const ChainModel model = ReadChain(std::string(VSTCAL_SOURCE_DIR) + "/datasets/vst/seed001.json");
  return model;
}

constexpr size_t kBatch = 1024;  // samples per call, as one Monte Carlo block

void BM_DrawTheta(benchmark::State& state) {
  const ThetaSampler sampler(Seed001(), 1);
  std::vector<SimdDouble> theta(kBatch / ThetaSampler::kLanes * sampler.size());
  uint64_t first = 0;
  for (auto _ : state) {
    sampler.FillLanes(first, kBatch / ThetaSampler::kLanes, theta.data());
    first += kBatch;
    benchmark::DoNotOptimize(theta.data());
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
  state.counters["random_per_sample"] = static_cast<double>(sampler.num_random());
}
BENCHMARK(BM_DrawTheta)->Unit(benchmark::kMicrosecond);

// What a chain sample needs, on seed 001.
struct ChainSampleSetup {
  const ThetaSampler sampler{Seed001(), 1};
  const ChainEvaluator chain{Seed001()};
  const ErrorOutputs outputs{Seed001()};
  SampleMeasurer measurer{chain, outputs};
};

void BM_ChainSample(benchmark::State& state) {
  ChainSampleSetup setup;
  constexpr size_t kLanes = SampleMeasurer::kLanes;
  const size_t n = setup.sampler.size();
  std::vector<SimdDouble> theta(kBatch / kLanes * n);
  std::vector<double> y(kLanes * setup.outputs.size());
  std::vector<uint8_t> defined(setup.outputs.size());
  uint64_t first = 0;
  for (auto _ : state) {
    setup.sampler.FillLanes(first, kBatch / kLanes, theta.data());
    first += kBatch;
    for (size_t g = 0; g < kBatch / kLanes; ++g) {
      setup.measurer.MeasureLanes(&theta[g * n], y.data(), defined.data());
      benchmark::DoNotOptimize(y.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
  state.counters["divergent_groups"] = static_cast<double>(setup.measurer.divergent_groups());
}

// The same one sample at a time throughout (θ by Fill, the chain with double, the path of a group
// whose lanes diverge): what drawing and evaluating four together gains.
void BM_ChainSampleScalar(benchmark::State& state) {
  ChainSampleSetup setup;
  const size_t n = setup.sampler.size();
  std::vector<double> theta(kBatch * n), y(setup.outputs.size());
  std::unique_ptr<bool[]> defined(new bool[setup.chain.num_points()]);
  uint64_t first = 0;
  for (auto _ : state) {
    setup.sampler.Fill(first, kBatch, theta.data());
    first += kBatch;
    for (size_t s = 0; s < kBatch; ++s) {
      setup.measurer.MeasureOne(&theta[s * n], y.data(), defined.get());
      benchmark::DoNotOptimize(y.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}
BENCHMARK(BM_ChainSample)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ChainSampleScalar)->Unit(benchmark::kMicrosecond);

void EngineSample(benchmark::State& state, OutputSet outputs) {
  ChainMonteCarloOptions options;
  options.samples = 16 * kBatch;
  options.threads = 1;
  options.outputs = outputs;
  for (auto _ : state) {
    benchmark::DoNotOptimize(RunChainMonteCarlo(Seed001(), options));
    ++options.seed;
  }
  state.SetItemsProcessed(state.iterations() * options.samples);
  state.counters["outputs"] = static_cast<double>(ErrorOutputs(Seed001(), outputs).size());
}
void BM_EngineSample(benchmark::State& state) { EngineSample(state, OutputSet::kFull); }
void BM_EngineBudgetSample(benchmark::State& state) { EngineSample(state, OutputSet::kTotals); }
BENCHMARK(BM_EngineSample)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EngineBudgetSample)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
