#include "vstcal/app/err_sim_check.h"

#include <cmath>
#include <cstdio>

#include "vstcal/app/err_sim.h"
#include "vstcal/core/error.h"
#include "vstcal/files/junit_xml.h"
#include "vstcal/formats/errsim/report_reader.h"
#include "vstcal/core/option_name.h"

namespace vstcal::app {
namespace {

void CheckPositive(double value, const std::string& what, const std::string& fix) {
  if (!(std::isfinite(value) && value > 0)) throw InputError(what + ": " + MessageNumber(value) + " is not a positive number; " + fix);
}

std::string Cell(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%12.6g", v);
  return buf;
}

}  // namespace

Outcome CheckErrSim(const ErrSimCheckRequest& request, const Provenance& provenance, const Progress& progress) {
  const std::string fix = "give an amount (0.5) or a percentage of the accepted value (10%)";
  CheckPositive(request.by_default.amount, VSTCAL_OPT("max_rise"), fix);
  for (const RiseRule& rule : request.rules) CheckPositive(rule.allowance.amount, VSTCAL_OPT("max_rise") " " + rule.name, fix);
  CheckPositive(request.z, VSTCAL_OPT("z"), "give the number of standard errors a rise may exceed its allowance by (e.g. 3)");
  if (!request.report.empty() && !request.chain.empty()) {
    throw InputError(VSTCAL_OPT("chain") ": names a chain to re-run, but " VSTCAL_OPT("report") " gives the new report; drop one of the two");
  }
  const ReportForCheck accepted = ReadReportForCheck(JsonDocument::Load(request.accepted));
  std::string fresh_name = request.report;
  const ReportForCheck fresh = [&] {
    if (!request.report.empty()) return ReadReportForCheck(JsonDocument::Load(request.report));
    RunRequest run;
    run.chain.chain = request.chain.empty() ? accepted.chain : request.chain;
    run.chain.only = accepted.only;
    run.chain.without = accepted.without;
    run.chain.samples = accepted.samples;
    run.chain.seed = accepted.seed;
    run.chain.threads = request.threads;
    run.budget = false;  // the budget's totals carry no standard error: nothing of it is checked
    fresh_name = "the run of " + run.chain.chain;
    const ErrSimDocument document = RunErrSim(run, provenance, progress);
    return ReadReportForCheck(JsonDocument::Parse(document.Text(), fresh_name));
  }();
  if (fresh.length_unit != accepted.length_unit) {
    throw InputError(fresh_name + ": length_unit: \"" + fresh.length_unit + "\", the accepted report's is \"" +
                     accepted.length_unit + "\"; compare reports of chains in one unit");
  }
  std::vector<MetricCheck> checks;
  try {
    checks = CheckMetrics(accepted.metrics, fresh.metrics, request.by_default, request.rules, request.z);
  } catch (const InputError& e) {
    throw InputError(std::string(VSTCAL_OPT("max_rise") ": ") + e.what());
  }

  Outcome out;
  std::string& s = out.stdout_text;
  s += "err-sim check: " + request.accepted + " (accepted, digest " + accepted.chain_digest + ") against " + fresh_name +
       " (digest " + fresh.chain_digest + (fresh.chain_digest == accepted.chain_digest ? ", the same chain" : ", the chain changed") +
       ")\n";
  char header[200];
  std::snprintf(header, sizeof header, "  %-40s %12s %12s %12s %12s %13s  %s\n", "metric (mean)", "accepted", "new", "rise",
                "allowed", "z·noise", "verdict");
  s += header;
  size_t counts[3] = {0, 0, 0};
  std::vector<CheckResult> results;
  for (const MetricCheck& c : checks) {
    char name[64];
    std::snprintf(name, sizeof name, "%-40s", c.name.c_str());
    s += "  " + std::string(name) + " " + Cell(c.accepted) + " ";
    if (c.present) {
      s += Cell(c.fresh) + " " + Cell(c.judgement.rise) + " " + Cell(c.judgement.allowed) + " " + Cell(request.z * c.judgement.noise);
    } else {
      s += "     missing" + std::string(39, ' ');
    }
    s += "  " + std::string(CheckVerdictName(c.judgement.verdict)) + "\n";
    ++counts[static_cast<int>(c.judgement.verdict)];
    results.push_back(c.result);
  }
  s += "err-sim check: " + std::to_string(checks.size()) + " metrics: " + std::to_string(counts[0]) + " pass, " +
       std::to_string(counts[1]) + " within noise, " + std::to_string(counts[2]) + " fail" +
       (counts[2] ? " (exit code 4)\n" : "\n");
  out.check_failed = counts[2] > 0;
  if (!request.junit.empty()) out.files.emplace_back(request.junit, JUnitXml("err-sim check", results));
  return out;
}

}  // namespace vstcal::app
