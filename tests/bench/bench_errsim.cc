// err-sim throughput on the shipped seed 001 chain (datasets/vst/seed001.json: both eyes, 5 test
// points, all seven sources active, 75 random parameters). Targets (issues 4 and 12): ≥ 2 million
// chain samples per second per core; the whole `err-sim run` loop, statistics included, ≥ 1.5
// million per core.
//   BM_DrawTheta          θ for one sample (ThetaSampler::FillLanes): the random numbers alone
//   BM_ChainSample        θ + the chain (both eyes, 5 points) + every error measure: one chain
//                         sample, four at a time as err-sim run evaluates them (SampleMeasurer)
//   BM_ChainSample/rig_covariance  the same with the right camera's pose error mixed from a rig's
//                         6 × 6 covariance (camera_extrinsic.right.covariance): the mixing's cost
//   BM_ChainSample/joint_covariance  the same with both lenses and the right camera's pose drawn
//                         from one joint covariance (joint_covariance): the couplings' cost
//   BM_ChainSampleScalar  the same one sample at a time throughout (θ by Fill, the chain with
//                         double): what drawing and evaluating four together gains
//   BM_EngineSample       the whole Monte Carlo loop of `err-sim run` per sample, with the mergeable
//                         statistics (moments of 64 outputs, histograms of 30), one thread
//   BM_EngineBudgetSample the same for a budget scenario (the totals' 26 outputs, no histograms)
//   BM_ErrSimRun          the library call of `err-sim run` (app::RunErrSim: the chain read, every
//                         scenario of the budget, the report document), 16,384 samples, one thread:
//                         the C++ side of the Python binding's vstcal.err_sim (python/bench.py)
// The NumPy peer (scripts/bench-errsim-numpy.py) runs the same chain; scripts/bench prints both.
#include <benchmark/benchmark.h>

#include <memory>

#include "vstcal/app/err_sim.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/engine.h"
#include "vstcal/formats/errsim/chain_reader.h"
#include "vstcal/formats/errsim/chain_spec.h"
#include "vstcal/scene/stereo_rig.h"
#include "vstcal/errsim/measures.h"
#include "vstcal/errsim/sample_measurer.h"
#include "vstcal/errsim/sampler.h"

using namespace vstcal;

namespace {

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

// Seed 001 with the right camera's pose error from a rig covariance: its six slots standard
// normals mixed by a dense 6 × 6 (σ ≈ 0.05° and 0.2 mm, correlated), as BuildChainModel makes it.
const ChainModel& Seed001OnARig() {
  static const ChainModel model = [] {
    ChainModel m = Seed001();
    for (const Term term : {Term::kCameraRotation, Term::kCameraTranslation}) {
      for (int i = 0; i < m.layout.Size(term, 1); ++i) {
        m.parameters[m.layout.Offset(term, 1) + i].distribution = Distribution::MakeNormal(0, 1);
      }
    }
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c <= r; ++c) m.extrinsic_mixing[1](r, c) = (r < 3 ? 9e-4 : 0.2) * (r == c ? 1.0 : 0.3);
    }
    return m;
  }();
  return model;
}

// Seed 001 with both cameras' lens errors and the right camera's pose error drawn as one from a
// rig's joint covariance (docs/math/vst-chain.md#joint-draw): every lens parameter of both eyes
// and right_from_left's six tangents, a dense positive definite Σ, so L D Lᵀ couples each slot
// to every one before it (n(n − 1)/2 couplings a sample).
const ChainModel& Seed001WithAJointCovariance() {
  static const ChainModel model = [] {
    ChainSpec spec = ReadChainSpec(std::string(VSTCAL_SOURCE_DIR) + "/datasets/vst/seed001.json");
    JointCovarianceSpec joint;
    for (int e = 0; e < kNumEyes; ++e) {
      for (const std::string_view p : LensModelParamNames(spec.cameras[e].camera.model)) {
        joint.covariance.parameters.push_back(JointCovarianceName(e, p));
      }
    }
    for (const std::string& t : RelativePoseTangentNames()) joint.covariance.parameters.push_back(t);
    // A dense correlation, scaled to seed 001's σ's: 1 px for fx … s, 10⁻³ for a distortion
    // term, 10⁻³ rad and 0.3 mm for right_from_left (no sample leaves the image).
    const int n = static_cast<int>(joint.covariance.parameters.size());
    Eigen::MatrixXd a(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) a(i, j) = (i == j ? 1.0 : 0.2) * std::cos(0.9 * i + 0.4 * j);
    Eigen::MatrixXd c = a * a.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd scale(n);
    for (int i = 0; i < n; ++i) {
      const std::string& name = joint.covariance.parameters[i];
      const std::string p = name.substr(name.find('.') + 1);
      const bool pixel = p == "fx" || p == "fy" || p == "cx" || p == "cy" || p == "s";
      scale(i) = (pixel ? 1.0 : p[0] == 'r' ? 1e-3 : p[0] == 't' ? 0.3 : 1e-3) / std::sqrt(c(i, i));
    }
    joint.covariance.matrix = scale.asDiagonal() * c * scale.asDiagonal();
    spec.joint_covariance = std::move(joint);
    return BuildChainModel(spec);
  }();
  return model;
}

// What a chain sample needs, on seed 001 (or another model).
struct ChainSampleSetup {
  explicit ChainSampleSetup(const ChainModel& model = Seed001()) : sampler(model, 1), chain(model), outputs(model) {}
  const ThetaSampler sampler;
  const ChainEvaluator chain;
  const ErrorOutputs outputs;
  SampleMeasurer measurer{chain, outputs};
};

void BM_ChainSample(benchmark::State& state, const ChainModel& (*model)()) {
  ChainSampleSetup setup(model());
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
BENCHMARK_CAPTURE(BM_ChainSample, seed001, &Seed001)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ChainSample, rig_covariance, &Seed001OnARig)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ChainSample, joint_covariance, &Seed001WithAJointCovariance)->Unit(benchmark::kMicrosecond);
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

void BM_ErrSimRun(benchmark::State& state) {
  app::RunRequest request;
  request.chain.chain = std::string(VSTCAL_SOURCE_DIR) + "/datasets/vst/seed001.json";
  request.chain.samples = 16384;
  request.chain.seed = 1;
  request.chain.threads = 1;
  for (auto _ : state) benchmark::DoNotOptimize(app::RunErrSim(request, Provenance{"bench", {}, {}}));
  state.SetItemsProcessed(state.iterations() * 16384);
}
BENCHMARK(BM_ErrSimRun)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
