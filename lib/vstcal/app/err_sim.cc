#include "vstcal/app/err_sim.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "vstcal/core/error.h"
#include "vstcal/core/suggest.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/engine.h"
#include "vstcal/formats/errsim/chain_reader.h"
#include "vstcal/formats/errsim/chain_writer.h"
#include "vstcal/formats/errsim/report_format.h"
#include "vstcal/formats/errsim/sensitivity_format.h"
#include "vstcal/formats/errsim/shard_format.h"
#include "vstcal/errsim/models.h"
#include "vstcal/errsim/sampler.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/sensitivity/linear_propagation.h"
#include "vstcal/sensitivity/monte_carlo.h"
#include "vstcal/sensitivity/oat_sweep.h"
#include "vstcal/sensitivity/sobol_indices.h"
#include "vstcal/core/option_name.h"

namespace vstcal::app {
namespace {

std::vector<Source> ParseSources(const std::vector<std::string>& keys, const std::string& flag) {
  std::vector<Source> out;
  const std::vector<std::string_view> known(kSourceKeys.begin(), kSourceKeys.end());
  for (const std::string& k : keys) {
    const auto s = SourceFromKey(k);
    if (!s) throw InputError(flag + ": unknown error source \"" + k + "\"; " + SuggestKey(k, known));
    out.push_back(*s);
  }
  return out;
}

std::string ShardName(uint64_t shard, uint64_t shards) { return std::to_string(shard) + "/" + std::to_string(shards); }

// The provenance records the seed the run used, whether it came from the flag or the chain file.
Provenance WithSeed(Provenance provenance, uint64_t seed) {
  provenance.seed = seed;
  return provenance;
}

RunDescription Describe(const ChainRequest& request, const ChainModel& model) {
  RunDescription run{request.chain, ChainDigest(model), request.only, request.without, {}};
  run.options.samples = model.samples;
  run.options.seed = model.seed;
  run.options.threads = request.threads;
  return run;
}

void CheckThreads(unsigned threads) {
  if (threads > kMaxThreads) {
    throw InputError(VSTCAL_OPT("threads") ": " + std::to_string(threads) + " is more than " + std::to_string(kMaxThreads) +
                     "; give at most " + std::to_string(kMaxThreads) + " (0: one per core)");
  }
}

void CheckSamples(uint64_t samples, const std::string& flag) {
  if (samples == 0 || samples > kMaxSamples) {
    throw InputError(flag + ": " + std::to_string(samples) + " is outside 1 … 10^12; give at most 10^12 (split larger runs into " VSTCAL_OPT("shard") " i/N)");
  }
}

// Why sample 0 of the chain leaves test point k undefined, for the message of a point that is
// undefined in every sample.
std::string FirstSampleCause(const ChainModel& model, size_t k) {
  const ChainEvaluator chain(model);
  const ThetaSampler sampler(model, model.seed);
  std::vector<double> theta(sampler.size());
  sampler.Fill(0, 1, theta.data());
  ChainSample<double> sample(chain.num_points());
  chain.Evaluate(theta.data(), &sample);
  const PointSample<double>& s = sample.points[k];
  std::string cause = UndefinedName(s.undefined);
  if (s.undefined != Undefined::kParallelRays && s.undefined != Undefined::kNone) {
    cause += std::string(" in the ") + std::string(kEyeNames[s.undefined_eye]) + " eye";
  }
  return cause;
}

// Exit code 3 when a test point has no defined sample in the "all" scenario.
void RequireDefinedPoints(const ChainModel& model, const SimulationResult& result, const std::string& chain_path) {
  const ErrorOutputs outputs(model);
  const MonteCarloSummary& all = result.summaries.at(0);
  for (size_t k = 0; k < outputs.num_points(); ++k) {
    if (all.Statistics(outputs.offset(k)).count > 0) continue;
    throw DegenerateError(chain_path + ": test point \"" + model.geometry.test_points[k].name + "\": every one of the " +
                          std::to_string(model.samples) + " samples is undefined (sample 0: " + FirstSampleCause(model, k) +
                          "); reduce the errors that move the overlay out of the cameras' view, or move the point");
  }
}

// The warnings of the chain's measurement files, after the budget's provenance: empty when none.
std::string MeasurementWarnings(const ChainModel& model) {
  if (model.measurement_warnings.empty()) return "";
  std::string out = "  the measurement files warn (their σ's are used as written):\n";
  for (const std::string& w : model.measurement_warnings) out += "    " + w + "\n";
  return out;
}

}  // namespace

std::string ErrSimDocument::Text() const { return compact ? DumpJsonCompact(json) : DumpJson(json); }

ChainModel LoadChain(const ChainRequest& request) {
  const std::vector<Source> only = ParseSources(request.only, VSTCAL_OPT("only"));  // flags before files
  const std::vector<Source> without = ParseSources(request.without, VSTCAL_OPT("without"));
  for (const Source s : without) {
    if (std::find(only.begin(), only.end(), s) != only.end()) {
      throw InputError(VSTCAL_OPT("without") ": \"" + std::string(SourceKey(s)) +
                       "\" is also given to " VSTCAL_OPT("only") "; give each source to one of them (" VSTCAL_OPT("only") " keeps, " VSTCAL_OPT("without") " drops)");
    }
  }
  CheckThreads(request.threads);
  if (request.samples) CheckSamples(*request.samples, VSTCAL_OPT("samples"));
  ChainModel model = ReadChain(request.chain);
  if (request.samples) model.samples = *request.samples;
  if (request.seed) model.seed = *request.seed;
  return SelectSources(model, only, without);
}

ErrSimDocument RunErrSim(const RunRequest& request, const Provenance& given, const Progress& progress) {
  if (!request.budget && request.budget_samples) {
    throw InputError(VSTCAL_OPT("budget_samples") ": there is no budget with " VSTCAL_OPT("no_budget") "; drop one of the two flags");
  }
  if (request.budget_samples) CheckSamples(*request.budget_samples, VSTCAL_OPT("budget_samples"));
  if (request.shards == 0 || request.shards > kMaxShards || request.shard >= request.shards) {
    throw InputError(VSTCAL_OPT("shard") ": " + ShardName(request.shard, request.shards) + " is not a shard i/N with 0 ≤ i < N ≤ 10^6");
  }
  const ChainModel model = LoadChain(request.chain);
  const Provenance provenance = WithSeed(given, model.seed);
  RunDescription run = Describe(request.chain, model);
  run.options.budget_samples = request.budget_samples.value_or(model.samples);
  run.options.budget = request.budget;
  run.options.shard = request.shard;
  run.options.shards = request.shards;
  const SimulationResult result = RunSimulation(MakeScenarios(model, request.budget), run.options, run.digest, progress);
  if (request.shards > 1) return {ShardToJson(result, run, provenance), "", true};
  RequireDefinedPoints(model, result, request.chain.chain);
  const ChainEvaluator chain(model);
  return {ReportToJson(chain, result, run, provenance), ReportText(chain, result, run) + MeasurementWarnings(model)};
}

ErrSimDocument MergeErrSim(const std::string& chain, const std::vector<std::string>& shard_files, const Provenance& given) {
  if (shard_files.empty()) throw InputError("merge: no shard files; pass every shard file of the run");
  std::vector<RunDescription> runs;
  std::vector<SimulationResult> shards;
  for (const std::string& file : shard_files) {
    RunDescription run;
    shards.push_back(ShardFromJson(JsonDocument::Load(file), &run));
    runs.push_back(std::move(run));
  }
  const RunDescription& first = runs[0];
  for (size_t i = 1; i < runs.size(); ++i) {
    const RunDescription& run = runs[i];
    if (run.digest != first.digest || run.options.samples != first.options.samples || run.options.seed != first.options.seed ||
        run.options.budget != first.options.budget || run.options.budget_samples != first.options.budget_samples ||
        run.options.shards != first.options.shards || run.options.block_size != first.options.block_size ||
        run.only != first.only || run.without != first.without) {
      throw InputError(shard_files[i] + ": comes from another run than " + shard_files[0] +
                       " (chain, samples, seed, sources or shard count differ); merge the shards of one run");
    }
    for (size_t j = 0; j < i; ++j) {
      if (runs[j].options.shard == run.options.shard) {
        throw InputError(shard_files[i] + ": shard " + ShardName(run.options.shard, run.options.shards) + " is given twice (also " +
                         shard_files[j] + "); pass each shard once");
      }
    }
  }
  std::set<uint64_t> seen;
  for (const RunDescription& run : runs) seen.insert(run.options.shard);
  for (uint64_t i = 0; i < first.options.shards; ++i) {
    if (!seen.count(i)) throw InputError("merge: shard " + ShardName(i, first.options.shards) + " is missing; pass every shard file of the run");
  }
  ChainRequest request{chain, first.only, first.without, first.options.samples, first.options.seed};
  const ChainModel model = LoadChain(request);
  if (ChainDigest(model) != first.digest) {
    throw InputError(chain + ": is not the chain the shards ran (digest " + ChainDigest(model) + ", shards " + first.digest +
                     "); pass the same chain file, unchanged");
  }
  // Every shard must hold exactly the summaries this chain's run makes: the same scenarios, each
  // with the plan (outputs, sizes, run id) the run gives it.
  RunDescription run = first;
  run.chain_path = chain;
  run.options.shard = 0;
  run.options.shards = 1;
  const SimulationResult expected = EmptySimulation(MakeScenarios(model, run.options.budget), run.options, run.digest);
  SimulationResult merged = expected;
  for (size_t i = 0; i < shards.size(); ++i) {
    const SimulationResult& shard = shards[i];
    if (shard.scenarios != expected.scenarios) {
      throw InputError(shard_files[i] + ": scenarios: not the scenarios of this run (" + std::to_string(shard.scenarios.size()) +
                       " given, " + std::to_string(expected.scenarios.size()) + " expected); regenerate the shard file");
    }
    for (size_t s = 0; s < shard.summaries.size(); ++s) {
      if (!(shard.summaries[s].plan() == expected.summaries[s].plan())) {
        throw InputError(shard_files[i] + ": scenarios[" + std::to_string(s) + "].summary: its plan is not the one this chain's run makes; regenerate the shard file");
      }
      try {
        merged.summaries[s].Merge(shard.summaries[s]);
      } catch (const InputError& e) {
        throw InputError(shard_files[i] + ": scenarios[" + std::to_string(s) + "].summary: " + e.what());
      }
    }
  }
  if (!merged.complete()) throw InputError("merge: the shards do not cover every block of the run; regenerate the missing shards");
  RequireDefinedPoints(model, merged, chain);
  const Provenance provenance = WithSeed(given, model.seed);
  const ChainEvaluator evaluator(model);
  return {ReportToJson(evaluator, merged, run, provenance), ReportText(evaluator, merged, run)};
}

ErrSimDocument SweepErrSim(const SweepRequest& request, const Provenance& provenance) {
  if (request.points < 2 || request.points > kMaxSweepPoints) {
    throw InputError(VSTCAL_OPT("points") ": " + std::to_string(request.points) + " is outside 2 … " + std::to_string(kMaxSweepPoints) +
                     "; give at most " + std::to_string(kMaxSweepPoints));
  }
  if ((request.lo || request.hi) && request.parameters.size() != 1) {
    throw InputError(std::string(request.lo ? VSTCAL_OPT("lo") : VSTCAL_OPT("hi")) +
                     ": a range is in one parameter's unit; give it with exactly one " VSTCAL_OPT("parameter"));
  }
  if (request.lo && request.hi && !(*request.lo < *request.hi)) {
    throw InputError(VSTCAL_OPT("lo") ": " + ShortestDecimal(*request.lo) + " is not below " VSTCAL_OPT("hi") " " + ShortestDecimal(*request.hi) +
                     "; give " VSTCAL_OPT("lo") " < " VSTCAL_OPT("hi"));
  }
  const ChainModel model = LoadChain(request.chain);
  const ParameterSpace space = MakeParameterSpace(model);
  const Model vector_model = VectorModel(model);
  std::vector<std::string_view> names;
  for (const ChainParameter& p : model.parameters) names.push_back(p.name());
  std::vector<size_t> chosen;
  if (request.parameters.empty()) {
    for (size_t i = 0; i < model.parameters.size(); ++i) {
      if (!model.parameters[i].distribution.IsConstant()) chosen.push_back(i);
    }
  } else {
    for (const std::string& name : request.parameters) {
      const auto it = std::find(names.begin(), names.end(), name);
      if (it == names.end()) {
        throw InputError(request.chain.chain + ": " VSTCAL_OPT("parameter") ": the chain has no parameter \"" + name + "\"; " +
                         SuggestKey(name, names));
      }
      const size_t i = static_cast<size_t>(it - names.begin());
      if (model.parameters[i].distribution.IsConstant() && !(request.lo && request.hi)) {
        throw InputError(VSTCAL_OPT("parameter") " " + name + ": the chain gives it a constant value (" +
                         model.parameters[i].distribution.Describe() + "), which has no default range; give " VSTCAL_OPT("lo") " and " VSTCAL_OPT("hi"));
      }
      chosen.push_back(i);
    }
  }
  const uint64_t outputs = VectorOutputNames(model).size();
  const uint64_t values = chosen.size() * (request.points + 1) * outputs;
  if (values > kMaxSweepValues) {
    throw InputError(request.chain.chain + ": " VSTCAL_OPT("points") ": sweeping " + std::to_string(chosen.size()) + " parameters at " +
                     std::to_string(request.points) + " points (and their slopes) for " + std::to_string(outputs) +
                     " outputs is " + std::to_string(values) + " values, more than the " + std::to_string(kMaxSweepValues) +
                     " of one sweep; name fewer parameters with " VSTCAL_OPT("parameter") ", give fewer " VSTCAL_OPT("points") ", or split the test points");
  }
  std::vector<ParameterSweep> sweeps;
  for (const size_t i : chosen) {
    const double per = model.parameters[i].slot.file_per_internal;
    SweepOptions options;
    options.points = request.points;
    if (request.lo) options.lo = *request.lo / per;
    if (request.hi) options.hi = *request.hi / per;
    sweeps.push_back({i, SweepParameter(space, vector_model, i, options)});
  }
  RunDescription run = Describe(request.chain, model);
  const TextAndJson out = SweepOutput(model, run, sweeps, provenance);
  return {out.json, out.text};
}

ErrSimDocument SobolErrSim(const SobolRequest& request, const Provenance& given) {
  if (request.bootstrap > kMaxBootstrap) {
    throw InputError(VSTCAL_OPT("bootstrap") ": " + std::to_string(request.bootstrap) + " is more than " + std::to_string(kMaxBootstrap) +
                     "; give at most " + std::to_string(kMaxBootstrap) + " (the interval's own error is already below 1 % there)");
  }
  const ChainModel model = LoadChain(request.chain);
  if (model.samples < 2 || model.samples > kMaxSobolSamples) {
    throw InputError(VSTCAL_OPT("samples") ": " + std::to_string(model.samples) + " is outside 2 … 2^24 for sobol; give a power of two up to 16777216");
  }
  int groups = 0;
  for (int s = 0; s < kNumSources; ++s) groups += model.SourceActive(static_cast<Source>(s));
  const double bytes = 8.0 * static_cast<double>(model.samples) * (groups + 2) * static_cast<double>(ErrorOutputs(model).size());
  if (bytes > kMaxSobolBytes) {
    throw InputError(VSTCAL_OPT("samples") ": sobol keeps 8·N·(sources + 2)·outputs bytes, " + std::to_string(static_cast<long long>(bytes / (1 << 20))) +
                     " MiB for N = " + std::to_string(model.samples) + "; give fewer samples (at most 1 GiB) or fewer sources");
  }
  const Provenance provenance = WithSeed(given, model.seed);
  SobolOptions options;
  options.samples = model.samples;
  options.sampling.method = ParseSamplingMethod(request.sampling);
  options.sampling.seed = model.seed;
  options.bootstrap_resamples = request.bootstrap;
  options.bootstrap_seed = model.seed;
  options.threads = request.chain.threads;
  const SobolResult r = EstimateSobolIndices(MakeParameterSpace(model), ErrorModel(model), options);
  if (r.status != SobolStatus::kOk) throw DegenerateError(request.chain.chain + ": " + r.message);
  const TextAndJson out = SobolOutput(model, Describe(request.chain, model), request.sampling, r, provenance);
  return {out.json, out.text};
}

ErrSimDocument LinearErrSim(const ChainRequest& request, const Provenance& given) {
  const ChainModel model = LoadChain(request);
  const size_t outputs = VectorOutputNames(model).size();
  if (outputs > kMaxLinearOutputs) {
    throw InputError(request.chain + ": linear propagation keeps an outputs² covariance: " + std::to_string(outputs) +
                     " outputs are more than " + std::to_string(kMaxLinearOutputs) + "; give at most " +
                     std::to_string(kMaxLinearOutputs / kVectorOutputsPerPoint) + " test points");
  }
  const Provenance provenance = WithSeed(given, model.seed);
  const ParameterSpace space = MakeParameterSpace(model);
  const Model vector_model = VectorModel(model);
  const LinearPropagation linear = PropagateLinear(space, vector_model);
  if (!linear.defined && linear.beyond_range) throw InputError(request.chain + ": " + linear.message);
  if (!linear.defined) throw DegenerateError(request.chain + ": " + linear.message);
  MonteCarloOptions mc;
  mc.samples = model.samples;
  mc.sampling.seed = model.seed;
  mc.threads = request.threads;
  mc.run_id = "err-sim-linear/" + ChainDigest(model);
  const MonteCarloSummary summary = RunMonteCarlo(space, vector_model, mc);
  // Samples that overflow (a σ near 1e300) sum to infinity: refused, never written as null, which
  // means "undefined" in the file (docs/formats.md#err-sim-sensitivity).
  for (size_t k = 0; k < outputs; ++k) {
    const OutputStatistics s = summary.Statistics(k);
    if (std::isinf(s.mean) || std::isinf(s.standard_deviation)) {
      throw InputError(request.chain + ": Monte Carlo: " + s.name +
                       ": the samples' mean or σ is beyond double precision; give σ's in the chain's units, far below 1e150");
    }
  }
  const TextAndJson out = LinearOutput(model, Describe(request, model), linear, summary, provenance);
  return {out.json, out.text};
}

ErrSimDocument NormalizeErrSim(const std::string& chain, const std::string& output, const Provenance& provenance) {
  ChainSpec spec = ReadChainSpec(chain);
  const ChainModel model = BuildChainModel(spec);
  // Camera and rig files stay where they are: their references are made relative to the output's folder.
  namespace fs = std::filesystem;
  const fs::path from = fs::path(chain).parent_path(), to = fs::path(output).parent_path();
  auto rebase = [&](std::string& file) {
    if (file.empty()) return;
    std::error_code ec;
    const fs::path target = fs::weakly_canonical(fs::absolute(from / file), ec);
    const fs::path base = fs::weakly_canonical(fs::absolute(to.empty() ? fs::path(".") : to), ec);
    const fs::path rebased = ec ? fs::path() : target.lexically_relative(base);
    if (!rebased.empty()) file = rebased.generic_string();
  };
  for (CameraSpec& camera : spec.cameras) rebase(camera.file);
  if (spec.rig) rebase(spec.rig->file);
  int random = 0;
  for (const ChainParameter& p : model.parameters) random += !p.distribution.IsConstant();
  std::string text = "err-sim normalize: " + chain + ": " + std::to_string(model.parameters.size()) + " parameters, " +
                     std::to_string(random) + " random; renderer lenses " + std::string(LensModelName(model.renderer[0].model)) +
                     " and " + std::string(LensModelName(model.renderer[1].model)) + "\n";
  return {ChainSpecToJson(spec, provenance), text};
}

}  // namespace vstcal::app
