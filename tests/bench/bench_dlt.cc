// DLT solve + decomposition (issue 2 targets: 600 points ≤ 15 µs, 6,000 points ≤ 60 µs).
// Peer in the same run: the textbook route, SVD of the full 2N×12 normalized system.
//
// `bench_dlt --write-scenes DIR` writes each benchmarked scene (DIR/dlt_scene_<n>.txt: one
// "X Y Z u v" line a point, %.17g so that the doubles read back exactly) and exits, so that
// python/bench.py times the Python binding on the very points the C++ figure solved: the DLT's
// refusal certificate is data-dependent, and another draw of the same size can cost more or less.
#include <benchmark/benchmark.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "support/scenes.h"
#include "vstcal/estimators/decompose.h"
#include "vstcal/estimators/dlt.h"

namespace {

constexpr size_t kSceneSizes[] = {60, 600, 6000};
constexpr double kNoisePx = 0.2;
constexpr uint64_t kSeed = 42;

void Run(benchmark::State& state, vstcal::DltOptions::Solver solver) {
  const auto scene = vstcal::testing::RandomVolumeScene(static_cast<size_t>(state.range(0)), kNoisePx, kSeed);
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

void SceneSizes(benchmark::internal::Benchmark* b) {
  for (size_t n : kSceneSizes) b->Arg(static_cast<int64_t>(n));
}

BENCHMARK(BM_DltNormalEquations)->Apply(SceneSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DltFullSvd)->Apply(SceneSizes)->Unit(benchmark::kMicrosecond);

int WriteScenes(const std::string& dir) {
  for (size_t n : kSceneSizes) {
    const std::string path = dir + "/dlt_scene_" + std::to_string(n) + ".txt";
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (f == nullptr) {
      std::fprintf(stderr, "bench_dlt: cannot write %s: %s\n", path.c_str(), std::strerror(errno));
      return 1;
    }
    for (const auto& o : vstcal::testing::RandomVolumeScene(n, kNoisePx, kSeed).observations)
      std::fprintf(f, "%.17g %.17g %.17g %.17g %.17g\n", o.point.x(), o.point.y(), o.point.z(), o.pixel.x(), o.pixel.y());
    if (std::fclose(f) != 0) {
      std::fprintf(stderr, "bench_dlt: cannot write %s\n", path.c_str());
      return 1;
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "--write-scenes") == 0) return WriteScenes(argv[2]);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
