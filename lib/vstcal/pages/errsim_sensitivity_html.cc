// The pages of err-sim sobol and err-sim linear (errsim_html.h), drawn from their outputs as written.
#include <algorithm>
#include <string>
#include <vector>

#include "vstcal/errsim/outputs.h"
#include "vstcal/formats/errsim/report_keys.h"
#include "vstcal/pages/errsim_charts.h"
#include "vstcal/pages/errsim_html.h"
#include "vstcal/pages/errsim_page_parts.h"
#include "vstcal/pages/html_page.h"

namespace vstcal {
namespace {


// The outputs a Sobol page charts, as err-sim's summary lists them: each test point's headline
// measures (kMeasures: its image error per eye, its linear misregistration and misperception).
bool Charted(const std::string& name) {
  for (const MeasureDecl& d : kMeasures) {
    if (!d.headline) continue;
    for (int e = 0; e < SlotsOf(d.scope); ++e) {
      if (name.ends_with(std::string(".").append(MeasureName(d.measure, e)))) return true;
    }
  }
  return false;
}

// Whether a linear file's output (a component of kVectorOutputs below its test point) is in px.
bool InPixels(const std::string& name) {
  for (const VectorOutputDecl& d : kVectorOutputs) {
    if (d.unit != OutputUnit::kPixel) continue;
    for (int e = 0; e < SlotsOf(d.scope); ++e) {
      for (int c = 0; c < d.size; ++c) {
        if (name.ends_with(std::string(".").append(VectorOutputName(d.output, e, c)))) return true;
      }
    }
  }
  return false;
}

std::string Filters(const OrderedJson& r) {
  std::string s;
  for (const char* key : {errsim_key::kOnly, errsim_key::kWithout}) {
    if (!r.contains(key) || !r.at(key).is_array() || r.at(key).empty()) continue;
    std::string list;
    for (const auto& v : r.at(key)) list += (list.empty() ? "" : ", ") + v.get<std::string>();
    s += std::string(" --") + key + " " + Escape(list) + ".";
  }
  return s;
}

}  // namespace

std::string ErrSimSobolHtml(const OrderedJson& r) {
  const OrderedJson& groups = r.at(errsim_key::kGroups);
  const OrderedJson& outputs = r.at(errsim_key::kOutputs);
  std::string s = PageStart("err-sim sobol: " + r.at(errsim_key::kChain).get<std::string>());
  s += "<h1>err-sim sobol: " + Escape(r.at(errsim_key::kChain).get<std::string>()) + "</h1>\n<p>Sobol indices of each source (" +
       Escape(r.at(errsim_key::kSampling).get<std::string>()) + " sampling): the first-order index S<sub>i</sub> is the share of an "
       "output's variance that source causes alone, the total index S<sub>Ti</sub> its share including its interactions "
       "with the others (docs/tools/err-sim.md). Error bars and intervals: bootstrap over the samples." +
       Filters(r) + "</p>\n";
  s += Table("run", "<th></th><th>value</th>",
             "<tr><th>samples N</th>" + ValueCell(r, JsonPointer({errsim_key::kSamples})) + "</tr>\n<tr><th>seed</th>" + ValueCell(r, JsonPointer({errsim_key::kSeed})) +
                 "</tr>\n<tr><th>chain evaluations</th>" + ValueCell(r, JsonPointer({errsim_key::kEvaluations})) + "</tr>\n");

  std::vector<size_t> charted;
  for (size_t k = 0; k < outputs.size(); ++k) {
    if (Charted(outputs[k].at(errsim_key::kName).get<std::string>())) charted.push_back(k);
  }
  s += "<section><h2>Indices with their bootstrap intervals</h2>\n";
  const size_t drawn = std::min(charted.size(), kMaxSobolCharts);
  if (drawn < charted.size()) {
    s += "<p>Charts of the first " + std::to_string(drawn) + " of the " + std::to_string(charted.size()) +
         " outputs listed below; the tables hold every one.</p>\n";
  }
  for (size_t i = 0; i < drawn; ++i) {
    const std::string name = outputs[charted[i]].at(errsim_key::kName).get<std::string>();
    s += ChartOrNote(SobolIndicesScript(outputs[charted[i]], groups), "Sobol indices of " + name,
                     "Sobol indices of " + name + " per source: first order (blue) and total (red), error bars the "
                     "bootstrap intervals.");
  }
  std::string interval_rows;
  for (size_t k : charted) {
    const std::string name = outputs[k].at(errsim_key::kName).get<std::string>();
    for (const auto& group : groups) {
      const std::string key = JsonPointer({errsim_key::kOutputs, std::to_string(k), errsim_key::kIndices, group.get<std::string>()});
      interval_rows += "<tr><th>" + Name(name) + "</th><th>" + Name(group.get<std::string>()) + "</th>";
      for (const char* order : {errsim_key::kFirst, errsim_key::kTotal}) {
        interval_rows += ValueCell(r, key + JsonPointer({order, errsim_key::kValue})) +
                         ValueCell(r, key + JsonPointer({order, errsim_key::kInterval, "0"})) +
                         ValueCell(r, key + JsonPointer({order, errsim_key::kInterval, "1"}));
      }
      interval_rows += "</tr>\n";
    }
  }
  s += Table("the charted outputs' indices and bootstrap intervals",
             "<th>output</th><th>source</th><th>first order</th><th>lo</th><th>hi</th><th>total</th><th>lo</th><th>hi</th>",
             interval_rows);
  s += "</section>\n<section><h2>Every output</h2>\n";
  // One table per order: a column per source in each, so that seven sources fit the page.
  std::string source_heads;
  for (const auto& group : groups) source_heads += "<th>" + Name(group.get<std::string>()) + "</th>";
  std::string first_rows, total_rows;
  for (size_t k = 0; k < outputs.size(); ++k) {
    const std::string key = JsonPointer({errsim_key::kOutputs, std::to_string(k)});
    const std::string name = "<tr><th>" + Name(outputs[k].at(errsim_key::kName).get<std::string>()) + "</th>";
    first_rows += name + ValueCell(r, key + JsonPointer({errsim_key::kMean})) + ValueCell(r, key + JsonPointer({errsim_key::kVariance}));
    total_rows += name;
    for (const auto& group : groups) {
      const std::string index = key + JsonPointer({errsim_key::kIndices, group.get<std::string>()});
      first_rows += ValueCell(r, index + JsonPointer({errsim_key::kFirst, errsim_key::kValue}));
      total_rows += ValueCell(r, index + JsonPointer({errsim_key::kTotal, errsim_key::kValue}));
    }
    first_rows += "</tr>\n";
    total_rows += "</tr>\n";
  }
  s += Table("first-order indices S_i of every output, per source", "<th>output</th><th>mean</th><th>variance</th>" + source_heads,
             first_rows);
  s += Table("total indices S_Ti of every output, per source", "<th>output</th>" + source_heads, total_rows) + "</section>\n";
  return s + kPageEnd;
}

std::string ErrSimLinearHtml(const OrderedJson& r) {
  const OrderedJson& outputs = r.at(errsim_key::kOutputs);
  const std::string unit = r.at(errsim_key::kLengthUnit).get<std::string>();
  std::string s = PageStart("err-sim linear: " + r.at(errsim_key::kChain).get<std::string>());
  s += "<h1>err-sim linear: " + Escape(r.at(errsim_key::kChain).get<std::string>()) + "</h1>\n<p>First-order propagation "
       "(σ² = J Σ<sub>θ</sub> J<sup>T</sup>, J by " + Escape(r.at(errsim_key::kDerivatives).get<std::string>()) +
       ") against Monte Carlo on the same chain, per vector output (pixel errors per eye; misregistration and "
       "misperception in the hmd frame, " + Escape(unit) + "). Where they differ beyond 3 standard errors of the "
       "Monte Carlo estimate, the error is not linear in the sources there." + Filters(r) + "</p>\n";
  s += Table("run", "<th></th><th>value</th>",
             "<tr><th>Monte Carlo samples</th>" + ValueCell(r, JsonPointer({errsim_key::kSamples})) + "</tr>\n<tr><th>seed</th>" +
                 ValueCell(r, JsonPointer({errsim_key::kSeed})) + "</tr>\n<tr><th>undefined samples</th>" + ValueCell(r, JsonPointer({errsim_key::kUndefinedSamples})) +
                 "</tr>\n<tr><th>outputs that differ</th>" + ValueCell(r, JsonPointer({errsim_key::kDisagreements})) + "</tr>\n");
  std::vector<size_t> pixels, lengths, all;
  for (size_t k = 0; k < outputs.size(); ++k) {
    (InPixels(outputs[k].at(errsim_key::kName).get<std::string>()) ? pixels : lengths).push_back(k);
    all.push_back(k);
  }
  s += "<section><h2>Linear against Monte Carlo</h2>\n";
  s += ChartOrNote(LinearScatterScript(r, pixels, "px"), "σ of the pixel errors, linear against Monte Carlo",
                   "Each pixel error component (du, dv per eye and test point): first-order σ against Monte Carlo σ (px).");
  s += ChartOrNote(LinearScatterScript(r, lengths, unit), "σ of the 3-D errors, linear against Monte Carlo",
                   "Each misregistration and misperception component: first-order σ against Monte Carlo σ (" + unit + ").");
  s += ChartOrNote(LinearRelativeDifferenceScript(r, all), "relative difference of σ per output",
                   "(linear σ − Monte Carlo σ) / Monte Carlo σ of each output, with ±3 standard errors of the Monte "
                   "Carlo σ: linear σ / MC σ is 1 + this.");
  // The comparison and the σ from each source as two tables, each of which fits the page.
  const OrderedJson& groups = outputs.empty() ? OrderedJson::object() : outputs[0].at(errsim_key::kLinearSigmaBySource);
  std::string source_heads = "<th>output</th>";
  for (const auto& [group, value] : groups.items()) source_heads += "<th>" + Name(group) + "</th>";
  std::string rows, source_rows;
  for (size_t k = 0; k < outputs.size(); ++k) {
    const OrderedJson& o = outputs[k];
    const std::string key = JsonPointer({errsim_key::kOutputs, std::to_string(k)});
    const std::string name = "<tr><th>" + Name(o.at(errsim_key::kName).get<std::string>()) + "</th>";
    rows += name;
    for (const char* field : {errsim_key::kLinearMean, errsim_key::kMonteCarloMean, errsim_key::kMeanStandardError,
                              errsim_key::kLinearSigma, errsim_key::kMonteCarloSigma, errsim_key::kSigmaStandardError,
                              errsim_key::kSigmaRelativeDifference}) {
      rows += ValueCell(r, key + JsonPointer({field}));
    }
    const bool mean = o.at(errsim_key::kMeanDisagrees).get<bool>(), sigma = o.at(errsim_key::kSigmaDisagrees).get<bool>();
    rows += std::string("<td>") + (mean && sigma ? "mean, σ" : mean ? "mean" : sigma ? "σ" : "") + "</td></tr>\n";
    source_rows += name;
    for (const auto& [group, value] : groups.items()) source_rows += ValueCell(r, key + JsonPointer({errsim_key::kLinearSigmaBySource, group}));
    source_rows += "</tr>\n";
  }
  const std::string units = "pixel outputs in px, the others in " + unit;
  s += Table("per output (" + units + ")",
             "<th>output</th><th>linear mean</th><th>MC mean</th><th>its s.e.</th><th>linear σ</th><th>MC σ</th>"
             "<th>its s.e.</th><th>(lin − MC) / MC</th><th>differs</th>",
             rows);
  s += Table("linear σ from each source alone, per output (" + units + ")", source_heads, source_rows) + "</section>\n";
  return s + kPageEnd;
}

}  // namespace vstcal
