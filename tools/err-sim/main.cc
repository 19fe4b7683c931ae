// err-sim: Monte Carlo and sensitivity analysis of the seven VST error sources through the
// registration chain of seed 001 (docs/tools/err-sim.md).
#include <cstdlib>
#include <iostream>

#include "common/progress.h"
#include "common/run_tool.h"
#include "common/scheduler.h"
#include "common/validators.h"
#include "vstcal/core/error.h"
#include "vstcal/errsim/commands.h"

namespace {

using vstcal::tools::kNonEmpty;

// Flags every subcommand shares: the chain, which sources, samples, seed, threads, output.
struct Common {
  vstcal::errsim::ChainRequest chain;
  uint64_t samples = 0, seed = 0;
  std::string output;
  bool quiet = false;

  CLI::App* Add(CLI::App* app, bool sources, bool sampling) {
    app->add_option("CHAIN", chain.chain, "vstcal/vst-chain@1 file")->required()->check(kNonEmpty);
    app->add_option("-o,--output", output, "file to write (JSON)")->required()->check(kNonEmpty);
    if (sources) {
      app->add_option("--only", chain.only, "simulate only these sources (repeat or comma-separate)")->delimiter(',');
      app->add_option("--without", chain.without, "leave these sources out")->delimiter(',');
    }
    if (sampling) {
      app->add_option("--samples", samples, "samples (default: the chain's \"samples\"; at most 10^12)")->check(vstcal::tools::kPositiveCount);
      app->add_option("--seed", seed, "random seed (default: the chain's \"seed\")")->check(vstcal::tools::kSeed);
      app->add_option("--threads", chain.threads, "threads (0: all cores, at most 256; results do not depend on it)");
    }
    app->add_flag("-q,--quiet", quiet, "print only errors (no summary)");
    return app;
  }
  void Finish(CLI::App* app) {
    if (app->get_option_no_throw("--samples") && app->count("--samples")) chain.samples = samples;
    if (app->get_option_no_throw("--seed") && app->count("--seed")) chain.seed = seed;
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Propagates the seven VST error sources (tracker_alignment, tracking, camera_extrinsic, camera_intrinsic, "
               "rendering, display, virtual_object_alignment) through the registration chain of a stereo video see-through "
               "system: image misregistration (px), the 3-D misregistration the user sees and the misperception of where "
               "things are (Holloway's terms), each source's contribution and an error budget ranked for each.\n"
               "Exit codes: 0 ok, 1 internal error, 2 bad usage or input, 3 degenerate model (every sample of a test point undefined).",
               "err-sim"};
  app.require_subcommand(1);
  Common common;
  vstcal::errsim::RunRequest run;
  std::string shard = "0/1";
  uint64_t budget_samples = 0, shard_count = 0;
  bool no_budget = false;
  CLI::App* run_app = common.Add(app.add_subcommand("run", "Monte Carlo: error statistics, contributions and the error budget"), true, true);
  run_app->add_flag("--no-budget", no_budget, "skip the per-source scenarios (contributions and budget)");
  run_app->add_option("--budget-samples", budget_samples, "samples per budget scenario (default: --samples)")->check(vstcal::tools::kPositiveCount);
  run_app->add_option("--shard", shard, "run shard i of N (i/N), or \"auto\" from a Slurm array or Kubernetes Indexed Job, and write a shard file for `err-sim merge`");
  run_app->add_option("--shard-count", shard_count, "with --shard auto under Kubernetes: the shard count (the Job's completions)")->check(vstcal::tools::kPositiveCount);

  std::vector<std::string> shards;
  CLI::App* merge_app = app.add_subcommand("merge", "merge the shard files of one run into its report");
  merge_app->add_option("CHAIN", common.chain.chain, "the chain the shards ran")->required()->check(kNonEmpty);
  merge_app->add_option("SHARDS", shards, "shard files (vstcal/err-sim-shard@2)")->required()->check(CLI::ExistingFile);
  merge_app->add_option("-o,--output", common.output, "report to write")->required()->check(kNonEmpty);
  merge_app->add_flag("-q,--quiet", common.quiet, "print only errors (no summary)");

  vstcal::errsim::SweepRequest sweep;
  CLI::App* sweep_app = common.Add(app.add_subcommand("sweep", "one-at-a-time sweeps with the local slope (autodiff)"), true, false);
  sweep_app->add_option("--parameter", sweep.parameters, "parameter names (default: every random one)")->delimiter(',');
  sweep_app->add_option("--lo", sweep.lo, "lower end of the range, in the parameter's unit (one --parameter; default: mean − 3σ or the support)")->check(vstcal::tools::kFinite);
  sweep_app->add_option("--hi", sweep.hi, "upper end of the range (one --parameter; default: mean + 3σ or the support)")->check(vstcal::tools::kFinite);
  sweep_app->add_option("--points", sweep.points, "points per sweep (2 … 1001)")->capture_default_str();

  vstcal::errsim::SobolRequest sobol;
  CLI::App* sobol_app = common.Add(app.add_subcommand("sobol", "first-order and total Sobol indices per source"), true, true);
  sobol_app->add_option("--sampling", sobol.sampling, "sobol or pseudo-random")->check(CLI::IsMember({"sobol", "pseudo-random"}))->capture_default_str();
  sobol_app->add_option("--bootstrap", sobol.bootstrap, "bootstrap resamples for the intervals (0: none; at most 10000)")->capture_default_str();

  CLI::App* linear_app = common.Add(app.add_subcommand("linear", "first-order propagation (autodiff) compared with Monte Carlo"), true, true);
  common.Add(app.add_subcommand("normalize", "write the chain in the canonical vst-chain@1 layout, defaults spelled out"), false, false);

  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    CLI::App* used = app.get_subcommands().front();
    common.Finish(used);
    const io::Provenance provenance = io::MakeProvenance("err-sim", argc, argv, common.chain.seed);
    errsim::Outcome outcome;
    if (used == run_app) {
      run.chain = common.chain;
      run.budget = !no_budget;
      if (run_app->count("--budget-samples")) run.budget_samples = budget_samples;
      if (run_app->count("--shard-count") && shard != "auto") throw InputError("--shard-count: only with --shard auto; give --shard i/N or --shard auto");
      const std::optional<uint64_t> count = run_app->count("--shard-count") ? std::optional(shard_count) : std::nullopt;
      std::tie(run.shard, run.shards) = shard == "auto" ? tools::ShardFromScheduler(std::getenv, count, "--shard-count")
                                                        : tools::ParseShard(shard, "--shard");
      tools::ProgressBar bar("err-sim run", !common.quiet);
      outcome = errsim::RunErrSim(run, provenance, [&](double f) { bar.Update(f); });
    } else if (used == merge_app) {
      outcome = errsim::MergeErrSim(common.chain.chain, shards, provenance);
    } else if (used == sweep_app) {
      sweep.chain = common.chain;
      outcome = errsim::SweepErrSim(sweep, provenance);
    } else if (used == sobol_app) {
      sobol.chain = common.chain;
      outcome = errsim::SobolErrSim(sobol, provenance);
    } else if (used == linear_app) {
      outcome = errsim::LinearErrSim(common.chain, provenance);
    } else {
      outcome = errsim::NormalizeErrSim(common.chain.chain, common.output, provenance);
    }
    io::WriteFilesAtomically({{common.output, outcome.Text()}});
    if (!common.quiet) std::cerr << outcome.text << "  wrote " << common.output << "\n";
    return 0;
  });
}
