#include "vstcal/errsim/commands.h"

#include <cmath>
#include <set>

#include "vstcal/core/error.h"
#include "vstcal/core/suggest.h"
#include "vstcal/errsim/chain_io.h"
#include "vstcal/errsim/models.h"
#include "vstcal/errsim/report.h"
#include "vstcal/sensitivity/linear_propagation.h"
#include "vstcal/sensitivity/monte_carlo.h"
#include "vstcal/sensitivity/oat_sweep.h"
#include "vstcal/sensitivity/sobol_indices.h"

namespace vstcal::errsim {
namespace {

using io::OrderedJson;

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

OrderedJson Header(std::string_view format, const ChainRequest& request, const ChainModel& model) {
  OrderedJson j;
  j["format"] = format;
  j["chain"] = request.chain;
  j["chain_digest"] = ChainDigest(model);
  j["length_unit"] = LengthUnitName(model.geometry.length_unit);
  j["only"] = request.only;
  j["without"] = request.without;
  return j;
}

std::string ShardName(uint64_t shard, uint64_t shards) { return std::to_string(shard) + "/" + std::to_string(shards); }

}  // namespace

ChainModel LoadChain(const ChainRequest& request) {
  const std::vector<Source> only = ParseSources(request.only, "--only");  // flags before files
  const std::vector<Source> without = ParseSources(request.without, "--without");
  ChainModel model = ReadChain(request.chain);
  if (request.samples) model.samples = *request.samples;
  if (request.seed) model.seed = *request.seed;
  return SelectSources(model, only, without);
}

// The provenance records the seed the run used, whether it came from the flag or the chain file.
static io::Provenance WithSeed(io::Provenance provenance, uint64_t seed) {
  provenance.seed = seed;
  return provenance;
}

Outcome RunErrSim(const RunRequest& request, const io::Provenance& given, const Progress& progress) {
  const ChainModel model = LoadChain(request.chain);
  const io::Provenance provenance = WithSeed(given, model.seed);
  RunDescription run{request.chain.chain, ChainDigest(model), request.chain.only, request.chain.without, {}};
  run.options.samples = model.samples;
  run.options.budget_samples = request.budget_samples.value_or(model.samples);
  run.options.seed = model.seed;
  run.options.budget = request.budget;
  run.options.threads = request.chain.threads;
  run.options.shard = request.shard;
  run.options.shards = request.shards;
  const SimulationResult result = RunSimulation(MakeScenarios(model, request.budget), run.options, run.digest, progress);
  if (request.shards > 1) return {ShardToJson(result, run, provenance), ""};
  return {ReportToJson(model, result, run, provenance), ReportText(model, result, run)};
}

Outcome MergeErrSim(const std::string& chain, const std::vector<std::string>& shard_files, const io::Provenance& given) {
  if (shard_files.empty()) throw InputError("merge: no shard files; pass every shard file of the run");
  std::optional<SimulationResult> merged;
  RunDescription first;
  std::set<uint64_t> seen;
  for (const std::string& file : shard_files) {
    RunDescription run;
    const SimulationResult shard = ShardFromJson(io::JsonDocument::Load(file), &run);
    if (!merged) {
      first = run;
      merged = shard;
    } else {
      if (run.digest != first.digest || run.options.samples != first.options.samples || run.options.seed != first.options.seed ||
          run.options.budget != first.options.budget || run.options.shards != first.options.shards ||
          run.only != first.only || run.without != first.without) {
        throw InputError(file + ": comes from another run than " + shard_files[0] +
                         " (chain, samples, seed, sources or shard count differ); merge the shards of one run");
      }
      if (seen.count(run.options.shard)) throw InputError(file + ": shard " + ShardName(run.options.shard, run.options.shards) + " is given twice; pass each shard once");
      MergeSimulation(&*merged, shard);
    }
    seen.insert(run.options.shard);
  }
  for (uint64_t i = 0; i < first.options.shards; ++i) {
    if (!seen.count(i)) throw InputError("merge: shard " + ShardName(i, first.options.shards) + " is missing; pass every shard file of the run");
  }
  ChainRequest request{chain, first.only, first.without, first.options.samples, first.options.seed};
  const ChainModel model = LoadChain(request);
  if (ChainDigest(model) != first.digest) {
    throw InputError(chain + ": is not the chain the shards ran (digest " + ChainDigest(model) + ", shards " + first.digest +
                     "); pass the same chain file, unchanged");
  }
  first.chain_path = chain;
  const io::Provenance provenance = WithSeed(given, model.seed);
  first.options.shard = 0;
  first.options.shards = 1;
  return {ReportToJson(model, *merged, first, provenance), ReportText(model, *merged, first)};
}

Outcome SweepErrSim(const SweepRequest& request, const io::Provenance& provenance) {
  const ChainModel model = LoadChain(request.chain);
  const sensitivity::ParameterSpace space = MakeParameterSpace(model);
  const sensitivity::Model vector_model = VectorModel(model);
  std::vector<size_t> chosen;
  if (request.parameters.empty()) {
    for (size_t i = 0; i < model.parameters.size(); ++i) {
      if (!model.parameters[i].distribution.IsConstant()) chosen.push_back(i);
    }
  } else {
    for (const std::string& name : request.parameters) chosen.push_back(space.IndexOf(name));
  }
  const size_t points = model.geometry.test_points.size();
  OrderedJson j = Header("vstcal/err-sim-sweep@1", request.chain, model);
  j["outputs"] = VectorOutputNames(model);
  OrderedJson list = OrderedJson::array();
  std::string text = "err-sim sweep: " + request.chain.chain + ": " + std::to_string(chosen.size()) +
                     " parameters, slope at nominal of the RMS errors per unit of the parameter\n";
  for (const size_t i : chosen) {
    const ChainParameter& p = model.parameters[i];
    sensitivity::SweepOptions options;
    options.points = request.points;
    if (request.lo) options.lo = *request.lo / p.file_per_internal;
    if (request.hi) options.hi = *request.hi / p.file_per_internal;
    const sensitivity::SweepResult r = sensitivity::SweepParameter(space, vector_model, i, options);
    OrderedJson values = OrderedJson::array(), image = OrderedJson::array(), perceived = OrderedJson::array();
    for (size_t k = 0; k < r.values.size(); ++k) {
      values.push_back(r.values[k] * p.file_per_internal);
      if (!r.defined[k]) {
        image.push_back(nullptr);
        perceived.push_back(nullptr);
        continue;
      }
      double px = 0, mm = 0;
      for (size_t t = 0; t < points; ++t) {
        const auto row = r.outputs.row(k).segment(7 * t, 7);
        px += row.head<4>().squaredNorm();
        mm += row.tail<3>().squaredNorm();
      }
      image.push_back(std::sqrt(px / (2.0 * points)));
      perceived.push_back(std::sqrt(mm / points));
    }
    OrderedJson e;
    e["name"] = p.name;
    e["source"] = SourceKey(p.source);
    e["unit"] = p.file_unit;
    e["values"] = std::move(values);
    e["image_rms_px"] = std::move(image);
    e["perceived_rms"] = std::move(perceived);
    OrderedJson slope = nullptr;
    if (r.slope_defined) {
      slope = OrderedJson::array();
      for (Eigen::Index o = 0; o < r.slope.size(); ++o) slope.push_back(r.slope(o) / p.file_per_internal);
    }
    e["slope_per_unit"] = std::move(slope);
    list.push_back(std::move(e));
    if (r.slope_defined) {
      double px = 0, mm = 0;
      for (size_t t = 0; t < points; ++t) {
        px += r.slope.segment(7 * t, 4).squaredNorm();
        mm += r.slope.segment(7 * t + 4, 3).squaredNorm();
      }
      char line[256];
      std::snprintf(line, sizeof line, "  %-44s %10.4g px/%s  %10.4g %s/%s\n", p.name.c_str(), std::sqrt(px / (2.0 * points)) / p.file_per_internal,
                    p.file_unit.c_str(), std::sqrt(mm / points) / p.file_per_internal, std::string(LengthUnitName(model.geometry.length_unit)).c_str(),
                    p.file_unit.c_str());
      text += line;
    }
  }
  j["parameters"] = std::move(list);
  j["provenance"] = io::ProvenanceToJson(provenance);
  return {j, text};
}

Outcome SobolErrSim(const SobolRequest& request, const io::Provenance& given) {
  const ChainModel model = LoadChain(request.chain);
  const io::Provenance provenance = WithSeed(given, model.seed);
  sensitivity::SobolOptions options;
  options.samples = model.samples;
  options.sampling.method = sensitivity::ParseSamplingMethod(request.sampling);
  options.sampling.seed = model.seed;
  options.bootstrap_resamples = request.bootstrap;
  options.bootstrap_seed = model.seed;
  options.threads = request.chain.threads;
  const sensitivity::SobolResult r = sensitivity::EstimateSobolIndices(MakeParameterSpace(model), ErrorModel(model), options);
  if (r.status != sensitivity::SobolStatus::kOk) throw Error(ExitCode::kDegenerate, request.chain.chain + ": " + r.message);
  OrderedJson j = Header("vstcal/err-sim-sobol@1", request.chain, model);
  j["samples"] = options.samples;
  j["sampling"] = request.sampling;
  j["seed"] = model.seed;
  j["evaluations"] = r.evaluations;
  j["groups"] = r.group_names;
  auto estimate = [](const sensitivity::Estimate& e) {
    return OrderedJson{{"value", e.value}, {"standard_error", e.standard_error}, {"interval", {e.interval.lo, e.interval.hi}}};
  };
  OrderedJson outputs = OrderedJson::array();
  std::string text = "err-sim sobol: " + request.chain.chain + ": N = " + std::to_string(options.samples) + " (" + request.sampling +
                     "), " + std::to_string(r.evaluations) + " evaluations; total index S_T per source\n";
  text += "  " + std::string(28, ' ');
  for (const std::string& g : r.group_names) text += g.substr(0, 11) + std::string(g.size() < 12 ? 12 - std::min<size_t>(g.size(), 11) : 1, ' ');
  text += "\n";
  for (const sensitivity::OutputSensitivity& o : r.outputs) {
    OrderedJson groups;
    for (size_t g = 0; g < r.group_names.size(); ++g) {
      groups[r.group_names[g]] = {{"first", estimate(o.groups[g].first_order)}, {"total", estimate(o.groups[g].total)}};
    }
    outputs.push_back({{"name", o.name}, {"mean", o.mean}, {"variance", o.variance}, {"indices", groups}});
    if (o.name.find("pixel_px") != std::string::npos || o.name.ends_with(".linear")) {
      char line[64];
      std::snprintf(line, sizeof line, "  %-28s", o.name.substr(0, 27).c_str());
      text += line;
      for (const auto& g : o.groups) {
        std::snprintf(line, sizeof line, "%-12.3f", g.total.value);
        text += line;
      }
      text += "\n";
    }
  }
  j["outputs"] = std::move(outputs);
  j["provenance"] = io::ProvenanceToJson(provenance);
  return {j, text};
}

Outcome LinearErrSim(const ChainRequest& request, const io::Provenance& given) {
  const ChainModel model = LoadChain(request);
  const io::Provenance provenance = WithSeed(given, model.seed);
  const sensitivity::ParameterSpace space = MakeParameterSpace(model);
  const sensitivity::Model vector_model = VectorModel(model);
  const sensitivity::LinearPropagation linear = sensitivity::PropagateLinear(space, vector_model);
  if (!linear.defined) throw Error(ExitCode::kDegenerate, request.chain + ": " + linear.message);
  sensitivity::MonteCarloOptions mc;
  mc.samples = model.samples;
  mc.sampling.seed = model.seed;
  mc.threads = request.threads;
  mc.run_id = "err-sim-linear/" + ChainDigest(model);
  const sensitivity::MonteCarloSummary summary = sensitivity::RunMonteCarlo(space, vector_model, mc);
  const auto comparison = sensitivity::CompareLinearWithMonteCarlo(linear, summary);
  OrderedJson j = Header("vstcal/err-sim-linear@1", request, model);
  j["samples"] = model.samples;
  j["seed"] = model.seed;
  j["derivatives"] = sensitivity::DerivativeMethodName(linear.method);
  j["undefined_samples"] = summary.undefined_samples();
  OrderedJson outputs = OrderedJson::array();
  int disagreements = 0;
  std::string text = "err-sim linear: " + request.chain + ": first-order σ (J Σ Jᵀ, autodiff) vs Monte Carlo (" +
                     std::to_string(model.samples) + " samples)\n  output                          linear σ     MC σ         rel. diff   \n";
  for (size_t k = 0; k < comparison.size(); ++k) {
    const auto& c = comparison[k];
    OrderedJson groups;
    for (size_t g = 0; g < linear.group_names.size(); ++g) groups[linear.group_names[g]] = std::sqrt(linear.group_variance(k, g));
    outputs.push_back({{"name", c.name},
                       {"linear_mean", c.linear_mean},
                       {"monte_carlo_mean", c.monte_carlo_mean},
                       {"mean_standard_error", c.mean_standard_error},
                       {"linear_sigma", c.linear_sigma},
                       {"monte_carlo_sigma", c.monte_carlo_sigma},
                       {"sigma_standard_error", c.sigma_standard_error},
                       {"sigma_relative_difference", c.sigma_relative_difference},
                       {"mean_disagrees", c.mean_disagrees},
                       {"sigma_disagrees", c.sigma_disagrees},
                       {"linear_sigma_by_source", groups}});
    disagreements += c.mean_disagrees || c.sigma_disagrees;
    char line[160];
    std::snprintf(line, sizeof line, "  %-30s %-12.4g %-12.4g %+8.2f %%%s\n", c.name.substr(0, 30).c_str(), c.linear_sigma, c.monte_carlo_sigma,
                  100 * c.sigma_relative_difference, c.mean_disagrees || c.sigma_disagrees ? "  ← not linear here" : "");
    text += line;
  }
  text += "  " + std::to_string(disagreements) + " of " + std::to_string(comparison.size()) +
          " outputs differ by more than the Monte Carlo error explains (3 standard errors)\n";
  j["outputs"] = std::move(outputs);
  j["disagreements"] = disagreements;
  j["provenance"] = io::ProvenanceToJson(provenance);
  return {j, text};
}

}  // namespace vstcal::errsim
