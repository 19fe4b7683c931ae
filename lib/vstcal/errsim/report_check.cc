#include "vstcal/errsim/report_check.h"

#include <cstdio>
#include <map>

#include "vstcal/core/error.h"
#include "vstcal/core/suggest.h"

namespace vstcal {
namespace {

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string Describe(const MetricCheck& c, const RiseAllowance& allowance, double z) {
  const RiseJudgement& j = c.judgement;
  std::string text = "accepted " + Number(c.accepted) + " ± " + Number(c.accepted_standard_error);
  if (!c.present) return text + ", missing from the new report";
  text += ", new " + Number(c.fresh) + " ± " + Number(c.fresh_standard_error) + ": rise " + Number(j.rise) +
          ", allowed " + Number(j.allowed);
  if (allowance.relative) text += " (" + Number(100 * allowance.amount) + " %)";
  return text + ", " + Number(z) + "σ noise " + Number(z * j.noise);
}

}  // namespace

const std::vector<CheckedMeasure>& CheckedMeasures() {
  static const std::vector<CheckedMeasure> checked = [] {
    std::vector<CheckedMeasure> list;
    for (const MeasureDecl& d : kMeasures) {
      if (!d.checked) continue;
      for (int eye = 0; eye < SlotsOf(d.scope); ++eye) list.push_back({d.measure, eye, SummaryName(d.measure, eye)});
    }
    return list;
  }();
  return checked;
}

std::vector<MetricCheck> CheckMetrics(std::span<const MonteCarloMetric> accepted, std::span<const MonteCarloMetric> fresh,
                                      const RiseAllowance& by_default, std::span<const RiseRule> rules, double z) {
  std::vector<std::string> names;
  std::vector<std::string_view> known;
  for (const CheckedMeasure& m : CheckedMeasures()) known.push_back(m.name);
  for (const MonteCarloMetric& m : accepted) names.push_back(m.name());
  for (const std::string& n : names) known.push_back(n);
  std::map<std::string, RiseAllowance> by_name;
  for (const RiseRule& rule : rules) {
    bool found = false;
    for (const std::string_view k : known) found = found || k == rule.name;
    if (!found) {
      std::string measures;
      for (const CheckedMeasure& m : CheckedMeasures()) measures.append(measures.empty() ? "" : ", ").append(m.name);
      const auto close = ClosestMatch(rule.name, known);
      throw InputError("\"" + rule.name + "\": no such metric in the accepted report, nor a measure; " +
                       (close ? "did you mean \"" + std::string(*close) + "\"? " : std::string()) + "give a measure (" +
                       measures + ") or \"<test point>.<measure>\"");
    }
    if (!by_name.emplace(rule.name, rule.allowance).second) {
      throw InputError("\"" + rule.name + "\": given twice; give one allowance per metric or measure");
    }
  }
  std::map<std::string, const MonteCarloMetric*> fresh_by_name;
  for (const MonteCarloMetric& m : fresh) fresh_by_name.emplace(m.name(), &m);

  std::vector<MetricCheck> out;
  for (const MonteCarloMetric& a : accepted) {
    MetricCheck c;
    c.name = a.name();
    c.accepted = a.value;
    c.accepted_standard_error = a.standard_error;
    RiseAllowance allowance = by_default;
    if (const auto it = by_name.find(a.measure); it != by_name.end()) allowance = it->second;
    if (const auto it = by_name.find(c.name); it != by_name.end()) allowance = it->second;
    const auto f = fresh_by_name.find(c.name);
    c.present = f != fresh_by_name.end();
    if (c.present) {
      c.fresh = f->second->value;
      c.fresh_standard_error = f->second->standard_error;
      c.judgement = JudgeRise(a.value, a.standard_error, c.fresh, c.fresh_standard_error, allowance.Of(a.value), z);
    } else {
      c.judgement.allowed = allowance.Of(a.value);
      c.judgement.verdict = CheckVerdict::kFail;
    }
    c.result = {c.name, c.judgement.verdict, Describe(c, allowance, z)};
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace vstcal
