// DLT solve + decomposition (issue 2 targets: 600 points ≤ 15 µs, 6,000 points ≤ 60 µs).
// Peer in the same run: the textbook route, SVD of the full 2N×12 normalized system.
#include <benchmark/benchmark.h>

#include "support/scenes.h"
#include "vstcal/estimators/decompose.h"
#include "vstcal/calib/dlt.h"

namespace {

void Run(benchmark::State& state, vstcal::DltOptions::Solver solver) {
  const auto scene = vstcal::testing::RandomVolumeScene(static_cast<size_t>(state.range(0)), 0.2, 42);
  vstcal::DltOptions options;
  options.solver = solver;
  for (auto _ : state) {
    const vstcal::DltResult r = vstcal::SolveDlt(scene.observations, options);
    auto d = vstcal::DecomposeProjection(r.P);
    benchmark::DoNotOptimize(d);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_DltNormalEquations(benchmark::State& state) { Run(state, vstcal::DltOptions::Solver::kNormalEquations); }
void BM_DltFullSvd(benchmark::State& state) { Run(state, vstcal::DltOptions::Solver::kFullSvd); }

BENCHMARK(BM_DltNormalEquations)->Arg(60)->Arg(600)->Arg(6000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DltFullSvd)->Arg(60)->Arg(600)->Arg(6000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
