// err-sim check as a library call (docs/tools/err-sim.md#check): an accepted vstcal/err-sim-report@3 (or @2)
// against a new one — given, or made by re-running the accepted report's chain with its samples,
// seed and sources — metric by metric (errsim/report_check.h), with the verdicts as a table and as
// JUnit XML for CI.
#pragma once

#include <string>
#include <vector>

#include "vstcal/app/outcome.h"
#include "vstcal/errsim/report_check.h"
#include "vstcal/errsim/simulation.h"
#include "vstcal/json/provenance.h"

namespace vstcal::app {

inline constexpr double kDefaultCheckZ = 3;  // a true rise within the allowance fails with probability ≤ 0.13 %

struct ErrSimCheckRequest {
  std::string accepted;  // the accepted report
  std::string report;    // the new report; empty: re-run the chain
  std::string chain;     // the chain to re-run; empty: the accepted report's "chain"
  unsigned threads = 0;
  RiseAllowance by_default{0.10, true};  // 10 % of the accepted value
  std::vector<RiseRule> rules;
  double z = kDefaultCheckZ;
  std::string junit;  // JUnit XML of the verdicts; empty: none
};

// `stdout_text`: one line per metric (accepted, new, rise, allowed, noise, verdict) and a count;
// `check_failed` when a metric failed; the JUnit file in `files`. InputError for bad reports,
// reports in different length units, an allowance or z that is not a positive finite number, an
// unknown metric name; DegenerateError as `err-sim run` for a re-run chain.
Outcome CheckErrSim(const ErrSimCheckRequest& request, const Provenance& provenance, const Progress& progress = {});

}  // namespace vstcal::app
