// err-sim's command line (docs/tools/err-sim.md): its six subcommands and their flags declared on
// one CLI11 app, and, once the app has parsed argv, the library call (app/err_sim.h) that the
// chosen subcommand names. main only parses and writes the returned file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "vstcal/app/err_sim.h"
#include "vstcal/app/err_sim_check.h"

namespace vstcal::tools {

class ErrSimCommandLine {
 public:
  // Declares the subcommands on `app`, which must outlive this object.
  explicit ErrSimCommandLine(CLI::App& app);

  // After app.parse: runs the chosen subcommand. InputError for flags that contradict each other.
  app::ErrSimDocument Run(int argc, char** argv);
  const std::string& output() const { return output_; }
  bool quiet() const { return quiet_; }
  const std::string& html() const { return html_; }  // run, merge, sweep, sobol, linear: the page to write too (empty: none)

  // `check`: whether it was chosen, its JUnit file (empty: none), and the check itself, after
  // app.parse. InputError for a --max-rise that is not [METRIC=]AMOUNT[%].
  bool checking() const;
  const std::string& junit() const { return check_request_.junit; }
  app::Outcome Check(int argc, char** argv);

 private:
  CLI::App* AddCommon(CLI::App* app, bool sources, bool sampling);

  CLI::App *check_ = nullptr;
  app::ErrSimCheckRequest check_request_;
  std::vector<std::string> max_rise_;
  CLI::App *run_ = nullptr, *merge_ = nullptr, *sweep_ = nullptr, *sobol_ = nullptr, *linear_ = nullptr;
  // Shared by every subcommand: the chain, which sources, samples, seed, threads, output.
  app::ChainRequest chain_;
  uint64_t samples_ = 0, seed_ = 0;
  std::string output_, html_;
  bool quiet_ = false;
  // run
  std::string shard_ = "0/1";
  uint64_t budget_samples_ = 0, shard_count_ = 0;
  bool no_budget_ = false;
  // merge, sweep, sobol
  std::vector<std::string> shards_;
  app::SweepRequest sweep_request_;
  app::SobolRequest sobol_request_;
};

}  // namespace vstcal::tools
