// err-sim throughput (issue 4 targets: ≥ 2 million chain samples per second per core, both eyes,
// 5 test points, all seven sources active; time per sample ≤ 3× the time to draw its random numbers).
#include <benchmark/benchmark.h>

#include "support/vst_scenes.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/holloway.h"
#include "vstcal/random/philox.h"

namespace {

using namespace vstcal;
using namespace vstcal::errsim;

ChainModel BenchModel(bool fiducials) {
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d p : {Eigen::Vector3d(-200, -100, 600), Eigen::Vector3d(150, 80, 800), Eigen::Vector3d(0, 0, 1000),
                                  Eigen::Vector3d(-300, 150, 1200), Eigen::Vector3d(250, -120, 1500)}) {
    points.push_back(testing::WorldFromHmdPoint(p));
  }
  ChainGeometry g = testing::ParallelRig(points);
  g.head_angular_velocity = Eigen::Vector3d(0.1, 0.8, 0.05);
  g.head_linear_velocity = Eigen::Vector3d(100, 20, 30);
  std::vector<Eigen::Vector3d> f;
  if (fiducials) f = {{-120, -80, 0}, {150, -60, 20}, {130, 90, -30}, {-100, 110, 10}};
  ChainModel m = ChainModel::WithZeroErrors(g, f);
  for (auto& p : m.parameters) p.distribution = Distribution::MakeNormal(0, 1e-3);
  return m;
}

void BM_ChainEvaluate(benchmark::State& state) {
  const ChainModel model = BenchModel(state.range(0) != 0);
  const ChainEvaluator chain(model);
  std::vector<double> theta(model.layout.size);
  const CounterRng rng(1, 0);
  for (size_t i = 0; i < theta.size(); ++i) theta[i] = 1e-3 * rng.Normal2(i, 0)[0];
  ChainSample<double> sample(chain.num_points());
  for (auto _ : state) {
    chain.Evaluate(theta.data(), &sample);
    benchmark::DoNotOptimize(sample.points[0].perceived);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ChainEvaluate)->Arg(0)->Arg(1);

void BM_ChainEvaluateAndMeasure(benchmark::State& state) {
  const ChainModel model = BenchModel(state.range(0) != 0);
  const ChainEvaluator chain(model);
  const ErrorOutputs outputs(model);
  std::vector<double> theta(model.layout.size), y(outputs.size());
  const CounterRng rng(1, 0);
  for (size_t i = 0; i < theta.size(); ++i) theta[i] = 1e-3 * rng.Normal2(i, 0)[0];
  ChainSample<double> sample(chain.num_points());
  for (auto _ : state) {
    chain.Evaluate(theta.data(), &sample);
    outputs.Measure(chain, sample, theta.data(), y.data());
    benchmark::DoNotOptimize(y.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ChainEvaluateAndMeasure)->Arg(0)->Arg(1);

}  // namespace

BENCHMARK_MAIN();
