#include "err-sim/command_line.h"

#include <cmath>
#include <cstdlib>
#include <optional>
#include <tuple>

#include "common/progress.h"
#include "common/scheduler.h"
#include "common/validators.h"
#include "vstcal/core/error.h"
#include "vstcal/sensitivity/unit_points.h"

namespace vstcal::tools {

CLI::App* ErrSimCommandLine::AddCommon(CLI::App* app, bool sources, bool sampling) {
  app->add_option("CHAIN", chain_.chain, "vstcal/vst-chain@1 file")->required()->check(kNonEmpty);
  app->add_option("-o,--output", output_, "file to write (JSON)")->required()->check(kNonEmpty);
  if (sources) {
    app->add_option("--only", chain_.only, "simulate only these sources (repeat or comma-separate)")->delimiter(',');
    app->add_option("--without", chain_.without, "leave these sources out")->delimiter(',');
  }
  if (sampling) {
    app->add_option("--samples", samples_, "samples (default: the chain's \"samples\"; at most 10^12)")->check(kPositiveCount);
    app->add_option("--seed", seed_, "random seed (default: the chain's \"seed\")")->check(kSeed);
    app->add_option("--threads", chain_.threads, "threads (0: all cores, at most 256; results do not depend on it)");
  }
  app->add_flag("-q,--quiet", quiet_, "print only errors (no summary)");
  return app;
}

ErrSimCommandLine::ErrSimCommandLine(CLI::App& app) {
  app.require_subcommand(1);
  run_ = AddCommon(app.add_subcommand("run", "Monte Carlo: error statistics, contributions and the error budget"), true, true);
  run_->add_flag("--no-budget", no_budget_, "skip the per-source scenarios (contributions and budget)");
  run_->add_option("--budget-samples", budget_samples_, "samples per budget scenario (default: --samples)")->check(kPositiveCount);
  run_->add_option("--shard", shard_, "run shard i of N (i/N), or \"auto\" from a Slurm array or Kubernetes Indexed Job, and write a shard file for `err-sim merge`");
  const char* const html_help = "also write a self-contained HTML page of the report (charts by gnuplot; opens offline)";
  run_->add_option("--html", html_, html_help)->check(kNonEmpty);
  run_->add_option("--shard-count", shard_count_, "with --shard auto under Kubernetes: the shard count (the Job's completions)")->check(kPositiveCount);

  merge_ = app.add_subcommand("merge", "merge the shard files of one run into its report");
  merge_->add_option("CHAIN", chain_.chain, "the chain the shards ran")->required()->check(kNonEmpty);
  merge_->add_option("SHARDS", shards_, "shard files (vstcal/err-sim-shard@2)")->required()->check(CLI::ExistingFile);
  merge_->add_option("-o,--output", output_, "report to write")->required()->check(kNonEmpty);
  merge_->add_option("--html", html_, html_help)->check(kNonEmpty);
  merge_->add_flag("-q,--quiet", quiet_, "print only errors (no summary)");

  sweep_ = AddCommon(app.add_subcommand("sweep", "one-at-a-time sweeps with the local slope (autodiff)"), true, false);
  sweep_->add_option("--parameter", sweep_request_.parameters, "parameter names (default: every random one)")->delimiter(',');
  sweep_->add_option("--lo", sweep_request_.lo, "lower end of the range, in the parameter's unit (one --parameter; default: mean − 3σ or the support)")->check(kFinite);
  sweep_->add_option("--hi", sweep_request_.hi, "upper end of the range (one --parameter; default: mean + 3σ or the support)")->check(kFinite);
  sweep_->add_option("--html", html_, html_help)->check(kNonEmpty);
  sweep_->add_option("--points", sweep_request_.points, "points per sweep (2 … 1001)")->capture_default_str();

  sobol_ = AddCommon(app.add_subcommand("sobol", "first-order and total Sobol indices per source"), true, true);
  sobol_->add_option("--sampling", sobol_request_.sampling, "sobol or pseudo-random")->check(CLI::IsMember(vstcal::NamesOf(kSamplingMethodNames)))->capture_default_str();
  sobol_->add_option("--bootstrap", sobol_request_.bootstrap, "bootstrap resamples for the intervals (0: none; at most 10000)")->capture_default_str();
  sobol_->add_option("--html", html_, html_help)->check(kNonEmpty);

  linear_ = AddCommon(app.add_subcommand("linear", "first-order propagation (autodiff) compared with Monte Carlo"), true, true);
  linear_->add_option("--html", html_, html_help)->check(kNonEmpty);
  CLI::App* normalize = AddCommon(app.add_subcommand("normalize", "write the chain in the canonical vst-chain@1 layout, defaults spelled out"), false, false);
  normalize->add_option("--html", html_, "refused: a chain has no page (run, merge, sweep, sobol and linear have one)");

  check_ = app.add_subcommand("check", "compare a new run (or --report) with an accepted report: fail (exit code 4) "
                                       "when a metric rose beyond its allowance by more than the Monte Carlo noise");
  check_->add_option("ACCEPTED", check_request_.accepted, "the accepted report (vstcal/err-sim-report@3 or @2)")->required()->check(kNonEmpty);
  check_->add_option("--report", check_request_.report, "the new report (default: re-run the accepted report's chain "
                                                         "with its samples, seed and sources)")->check(kNonEmpty);
  check_->add_option("--chain", check_request_.chain, "the chain to re-run (default: the accepted report's \"chain\")")->check(kNonEmpty);
  check_->add_option("--max-rise", max_rise_, "how much a metric may rise: AMOUNT (in its unit) or PERCENT% of the accepted "
                                              "value, for every metric, or METRIC=… or MEASURE=… for one (repeat; default 10%)");
  check_->add_option("--z", check_request_.z, "standard errors of the difference a rise may exceed its allowance by before it fails")
      ->capture_default_str();
  check_->add_option("--junit", check_request_.junit, "write the verdicts as JUnit XML to this file (for CI)")->check(kNonEmpty);
  check_->add_option("--threads", check_request_.threads, "threads of the re-run (0: all cores, at most 256; results do not depend on it)");
  check_->add_flag("-q,--quiet", quiet_, "print only errors (the exit code says pass or fail)");
}

bool ErrSimCommandLine::checking() const { return check_->parsed(); }

namespace {

// [NAME=]AMOUNT[%]: NAME a metric or measure (the last '=' splits, a test point's name may hold one).
void AddRise(app::ErrSimCheckRequest& request, const std::string& text, bool* default_given) {
  const size_t eq = text.rfind('=');
  const std::string name = eq == std::string::npos ? "" : text.substr(0, eq);
  std::string amount = eq == std::string::npos ? text : text.substr(eq + 1);
  const bool relative = !amount.empty() && amount.back() == '%';
  if (relative) amount.pop_back();
  const char* begin = amount.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (amount.empty() || end != begin + amount.size() || !std::isfinite(value) || !(value > 0)) {
    throw InputError("--max-rise: \"" + text + "\": not a positive amount; give AMOUNT (0.5, in the metric's unit) or "
                     "PERCENT% (10%), optionally after METRIC= or MEASURE=");
  }
  const RiseAllowance allowance{relative ? value / 100 : value, relative};
  if (name.empty()) {
    if (*default_given) throw InputError("--max-rise: \"" + text + "\": a second default; give one AMOUNT without a name");
    *default_given = true;
    request.by_default = allowance;
  } else {
    request.rules.push_back({name, allowance});
  }
}

}  // namespace

app::Outcome ErrSimCommandLine::Check(int argc, char** argv) {
  bool default_given = false;
  for (const std::string& text : max_rise_) AddRise(check_request_, text, &default_given);
  ProgressBar bar("err-sim check", !quiet_ && check_request_.report.empty());
  return app::CheckErrSim(check_request_, MakeProvenance("err-sim", argc, argv, std::nullopt),
                          [&](double f) { bar.Update(f); });
}

app::ErrSimDocument ErrSimCommandLine::Run(int argc, char** argv) {
  CLI::App* used = run_->get_parent()->get_subcommands().front();
  if (used->get_option_no_throw("--samples") && used->count("--samples")) chain_.samples = samples_;
  if (used->get_option_no_throw("--seed") && used->count("--seed")) chain_.seed = seed_;
  const Provenance provenance = MakeProvenance("err-sim", argc, argv, chain_.seed);
  if (used == run_) {
    app::RunRequest run;
    run.chain = chain_;
    run.budget = !no_budget_;
    if (run_->count("--budget-samples")) run.budget_samples = budget_samples_;
    if (run_->count("--shard-count") && shard_ != "auto") throw InputError("--shard-count: only with --shard auto; give --shard i/N or --shard auto");
    const std::optional<uint64_t> count = run_->count("--shard-count") ? std::optional(shard_count_) : std::nullopt;
    std::tie(run.shard, run.shards) = shard_ == "auto" ? ShardFromScheduler(std::getenv, count, "--shard-count")
                                                       : ParseShard(shard_, "--shard");
    if (run.shards > 1 && !html_.empty()) {
      throw InputError("--html: a shard file is not a report; give --html to `err-sim merge` of the shards");
    }
    ProgressBar bar("err-sim run", !quiet_);
    return app::RunErrSim(run, provenance, [&](double f) { bar.Update(f); });
  }
  if (used == merge_) return app::MergeErrSim(chain_.chain, shards_, provenance);
  if (used == sweep_) {
    sweep_request_.chain = chain_;
    return app::SweepErrSim(sweep_request_, provenance);
  }
  if (used == sobol_) {
    sobol_request_.chain = chain_;
    return app::SobolErrSim(sobol_request_, provenance);
  }
  if (used == linear_) return app::LinearErrSim(chain_, provenance);
  if (!html_.empty()) throw InputError("--html: normalize writes a chain, which has no page; give --html to run, merge, sweep, sobol or linear");
  return app::NormalizeErrSim(chain_.chain, output_, provenance);
}

}  // namespace vstcal::tools
