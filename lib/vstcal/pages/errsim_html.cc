#include "vstcal/pages/errsim_html.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "vstcal/core/error.h"
#include "vstcal/formats/errsim/report_keys.h"

#include "vstcal/pages/errsim_charts.h"
#include "vstcal/pages/errsim_page_parts.h"
#include "vstcal/pages/html_page.h"

namespace vstcal {
namespace {


// Cells of one statistics object (mean, rms, p50, p95, p99, max), dashes when it is null.
std::string StatsCells(const OrderedJson& report, const std::string& pointer) {
  std::string s;
  for (const char* field : {errsim_key::kMean, errsim_key::kRms, errsim_key::kP50, errsim_key::kP95, errsim_key::kP99, errsim_key::kMax}) {
    s += ValueCell(report, pointer + JsonPointer({field}));
  }
  return s;
}
constexpr const char* kStatsHeads = "<th>mean</th><th>rms</th><th>p50</th><th>p95</th><th>p99</th><th>max</th>";

std::string Summary(const OrderedJson& r) {
  const std::string unit = r.at(errsim_key::kLengthUnit).get<std::string>();
  std::string active;
  for (const auto& s : r.at(errsim_key::kSources).at(errsim_key::kActive)) {
    active += (active.empty() ? "" : ", ") + s.get<std::string>();
  }
  std::string s = "<p>" + std::to_string(r.at(errsim_key::kSamples).get<uint64_t>()) + " samples, seed " +
                  std::to_string(r.at(errsim_key::kSeed).get<uint64_t>()) + ", lengths in " + Escape(unit) + ", " +
                  std::to_string(r.at(errsim_key::kTestPoints).size()) + " test points. Active sources: " + Escape(active) +
                  ". Definitions: docs/math/vst-chain.md and docs/math/registration-error.md.</p>\n";
  std::string rows;
  const std::pair<std::string, std::string> totals[] = {{TotalKey(Total::kImage), "image misregistration RMS (px)"},
                                                        {TotalKey(Total::kMisregistration), "3-D misregistration RMS (" + unit + ")"},
                                                        {TotalKey(Total::kMisperception), "misperception RMS (" + unit + ")"},
                                                        {std::string(kSystematicMisperceptionKey), "systematic misperception RMS (" + unit + ")"},
                                                        {TotalKey(Total::kWrongOcclusion), "wrong occlusion rate"}};
  for (const auto& [key, label] : totals) rows += "<tr><th>" + Escape(label) + "</th>" + ValueCell(r, JsonPointer({errsim_key::kTotals, key})) + "</tr>\n";
  rows += "<tr><th>samples with some test point undefined</th>" + ValueCell(r, JsonPointer({errsim_key::kUndefinedSamples})) + "</tr>\n";
  return s + Table("whole chain", "<th></th><th>value</th>", rows);
}

std::string Distributions(const OrderedJson& r) {
  const OrderedJson& points = r.at(errsim_key::kTestPoints);
  const std::string unit = r.at(errsim_key::kLengthUnit).get<std::string>();
  std::vector<QuantileBar> image, misregistration, misperception;
  std::string image_rows, misregistration_rows, misperception_rows;
  for (size_t k = 0; k < points.size(); ++k) {
    const OrderedJson& p = points[k];
    const std::string name = p.at(errsim_key::kName).get<std::string>(), key = JsonPointer({errsim_key::kTestPoints, std::to_string(k)});
    auto at = [&](ErrorMeasure m, int eye = 0) { return &p.at(OrderedJson::json_pointer(std::string("/").append(MeasurePointer(m, eye)))); };
    for (int e = 0; e < kNumEyes; ++e) {
      const std::string eye(kEyeNames[e]);
      image.push_back({name + " " + eye, at(ErrorMeasure::kImagePixel, e), static_cast<size_t>(e)});
      const std::string pk = key + "/" + MeasurePointer(ErrorMeasure::kImagePixel, e);
      image_rows += "<tr><th>" + Escape(name) + "</th><th>" + eye + "</th>" + StatsCells(r, pk) + "</tr>\n";
    }
    misregistration.push_back({name, at(ErrorMeasure::kMisregistrationLinear), 2});
    misperception.push_back({name, at(ErrorMeasure::kMisperceptionLinear), 3});
    // The systematic part's terms are named as the sampled ones (report_format.cc).
    const MeasureDecl& misperception_linear = Declaration(ErrorMeasure::kMisperceptionLinear);
    const std::string systematic =
        key + JsonPointer({misperception_linear.group, errsim_key::kSystematic, misperception_linear.name});
    misregistration_rows += "<tr><th>" + Escape(name) + "</th>" + ValueCell(r, key + JsonPointer({errsim_key::kUndefined, errsim_key::kRate})) +
                            StatsCells(r, key + "/" + MeasurePointer(ErrorMeasure::kMisregistrationLinear)) + "</tr>\n";
    misperception_rows += "<tr><th>" + Escape(name) + "</th>" + ValueCell(r, systematic) +
                          StatsCells(r, key + "/" + MeasurePointer(ErrorMeasure::kMisperceptionLinear)) + "</tr>\n";
  }
  std::string s = "<section><h2>Error distributions</h2>\n";
  s += ChartOrNote(QuantileBarsScript(image, "image misregistration |overlay - video| (px)"), "image misregistration per test point and eye",
                   "Image misregistration of each test point in each eye (px): box from the median to p95, whisker to p99, "
                   "mean and maximum marked; left eye blue, right eye red.");
  s += ChartOrNote(QuantileBarsScript(misregistration, "3-D misregistration, linear (" + unit + ")"),
                   "3-D misregistration per test point",
                   "3-D misregistration (Holloway's linear error, " + unit + ") of each test point, the same quantiles.");
  s += ChartOrNote(QuantileBarsScript(misperception, "misperception, linear (" + unit + ")"), "misperception per test point",
                   "Misperception (linear, relative to the error-free chain's systematic one, " + unit +
                       ") of each test point, the same quantiles.");
  s += Table("image misregistration (px)", std::string("<th>test point</th><th>eye</th>") + kStatsHeads, image_rows);
  s += Table("3-D misregistration, linear (" + unit + ")", std::string("<th>test point</th><th>undefined rate</th>") + kStatsHeads,
             misregistration_rows);
  s += Table("misperception, linear (" + unit + "), beside the error-free chain's systematic one",
             std::string("<th>test point</th><th>systematic</th>") + kStatsHeads, misperception_rows);
  return s + "</section>\n";
}

// Where a budget row's distributions came from: "measured (rig.json)", "assumed" (a report written
// before the field existed shows nothing).
std::string OriginCell(const OrderedJson& row) {
  std::string text;
  if (row.contains(errsim_key::kOrigin)) {
    for (const auto& o : row.at(errsim_key::kOrigin)) {
      if (!text.empty()) text += " + ";
      text += o.at(errsim_key::kKind).get<std::string>() == errsim_key::kMeasured
                  ? "measured (<span title=\"" + Escape(o.at(errsim_key::kOriginFormat).get<std::string>()) + "\">" +
                        Escape(o.at(errsim_key::kFile).get<std::string>()) + "</span>)"
                  : std::string("assumed");
    }
  }
  return "<td class=\"origin\" style=\"text-align:left\">" + text + "</td>";
}

std::string Budget(const OrderedJson& r) {
  const OrderedJson& budget = r.at(errsim_key::kBudget);
  if (budget.is_null()) return "<section><h2>Error budget</h2>\n<p>Not computed: the run was asked for no budget.</p></section>\n";
  const std::string unit = r.at(errsim_key::kLengthUnit).get<std::string>();
  std::string s = "<section><h2>Error budget</h2>\n<p>Each source alone and the whole chain with that source halved (" +
                  std::to_string(budget.at(errsim_key::kSamples).get<uint64_t>()) +
                  " samples a scenario, common random numbers); ranked by its share of the whole chain's mean square — "
                  "first by what the user sees, the image misregistration (the default ranking), then by the 3-D "
                  "misregistration and by the misperception. "
                  "The shares and the row of interactions and means in common (what the sources' parts leave out) add "
                  "to 1 (docs/math/sensitivity.md#shares-of-the-whole).</p>\n";
  // Each ranked measure with another beside it: the image's RMS is in px, the others' in the length unit.
  struct Ranked {
    Total measure, beside;
  };
  auto unit_of = [&](Total t) { return Declaration(t).unit == OutputUnit::kPixel ? std::string("px") : unit; };
  auto title_of = [](Total t) { return t == Total::kImage ? std::string("image misregistration") : BudgetMeasureKey(t); };
  auto short_of = [](Total t) { return t == Total::kMisregistration ? std::string("3-D") : BudgetMeasureKey(t); };  // narrow column heads
  for (const Ranked& ranked : {Ranked{Total::kImage, Total::kMisregistration}, Ranked{Total::kMisregistration, Total::kImage},
                               Ranked{Total::kMisperception, Total::kImage}}) {
    const std::string measure = BudgetMeasureKey(ranked.measure), beside = BudgetMeasureKey(ranked.beside);
    if (!budget.at(errsim_key::kRanking).contains(measure)) continue;  // a report written before the image ranking
    const std::string rms = TotalKey(ranked.measure), beside_rms = TotalKey(ranked.beside);
    s += ChartOrNote(BudgetScript(r, ranked.measure), "error budget, " + title_of(ranked.measure),
                     "Error budget of the " + title_of(ranked.measure) + " (" + unit_of(ranked.measure) + "), sources ranked largest share first.");
    std::string rows;
    size_t rank = 0;
    for (const auto& source : budget.at(errsim_key::kRanking).at(measure)) {
      const OrderedJson& entries = budget.at(errsim_key::kEntries);
      for (size_t i = 0; i < entries.size(); ++i) {
        if (entries[i].at(errsim_key::kSource) != source) continue;
        const std::string key = JsonPointer({errsim_key::kBudget, errsim_key::kEntries, std::to_string(i)});
        rows += "<tr><th>" + std::to_string(++rank) + ". " + Escape(source.get<std::string>()) + "</th>" +
                ValueCell(r, key + JsonPointer({ShareKey(ranked.measure)})) + ValueCell(r, key + JsonPointer({errsim_key::kAlone, rms})) +
                ValueCell(r, key + JsonPointer({errsim_key::kHalved, rms})) + ValueCell(r, key + JsonPointer({ShareKey(ranked.beside)})) +
                ValueCell(r, key + JsonPointer({errsim_key::kHalved, beside_rms})) + "<td style=\"text-align:left\">" +
                Escape(entries[i].at(errsim_key::kCorrection).get<std::string>()) + "</td>" + OriginCell(entries[i]) + "</tr>\n";
        // The source's terms alone, largest share first (the tree source → term).
        const OrderedJson& terms = entries[i].at(errsim_key::kTerms);
        if (terms.size() < 2) continue;
        std::vector<size_t> order(terms.size());
        for (size_t t = 0; t < order.size(); ++t) order[t] = t;
        const std::string share = ShareKey(ranked.measure);
        auto value = [&](size_t t) { return terms[t].at(share).is_number() ? terms[t].at(share).get<double>() : -1.0; };
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return value(a) > value(b); });
        for (const size_t t : order) {
          const std::string term_key = key + JsonPointer({errsim_key::kTerms, std::to_string(t)});
          rows += "<tr><th style=\"padding-left:2em\">" + Name(terms[t].at(errsim_key::kTerm).get<std::string>()) + "</th>" +
                  ValueCell(r, term_key + JsonPointer({share})) + ValueCell(r, term_key + JsonPointer({errsim_key::kAlone, rms})) + EmptyCells(1) +
                  ValueCell(r, term_key + JsonPointer({ShareKey(ranked.beside)})) + EmptyCells(1) + "<td></td>" + OriginCell(terms[t]) +
                  "</tr>\n";
        }
      }
    }
    // What the sources' parts leave out, and the whole they are shares of: the share column adds to 1.
    const std::string whole = JsonPointer({errsim_key::kBudget, errsim_key::kWhole, measure});
    const bool none = budget.at(errsim_key::kWhole).at(measure).at(errsim_key::kNone).get<bool>();
    rows += "<tr><th>interactions and means in common</th>" + ValueCell(r, whole + JsonPointer({errsim_key::kRemainderShare})) + EmptyCells(2) +
            ValueCell(r, JsonPointer({errsim_key::kBudget, errsim_key::kWhole, beside, errsim_key::kRemainderShare})) + EmptyCells(1) +
            "<td style=\"text-align:left\">" + std::string(none ? "none: the whole chain's mean square is 0 to rounding" : "") +
            "</td><td></td></tr>\n";
    rows += "<tr><th>whole chain (RMS)</th>" + EmptyCells(1) + ValueCell(r, JsonPointer({errsim_key::kTotals, rms})) + EmptyCells(2) +
            ValueCell(r, JsonPointer({errsim_key::kTotals, beside_rms})) + EmptyCells(2) + "</tr>\n";
    s += Table("ranked by " + title_of(ranked.measure) +
                   (ranked.measure == Total::kImage ? " (what the user sees: the default ranking)" : ""),
               "<th>source</th><th>share of mean square</th><th>alone RMS (" + unit_of(ranked.measure) + ")</th><th>whole chain, halved (" +
                   unit_of(ranked.measure) + ")</th><th>share of " + short_of(ranked.beside) + " mean square</th><th>" +
                   short_of(ranked.beside) + " RMS halved (" + unit_of(ranked.beside) + ")</th><th>correction</th>"
                   "<th title=\"measured: from a calibration's file; assumed: typed into the chain\">distributions</th>",
               rows);
  }
  return s + "</section>\n";
}

}  // namespace

std::string ErrSimReportHtml(const OrderedJson& r) {
  std::string s = PageStart("err-sim: " + r.at(errsim_key::kChain).get<std::string>());
  s += "<h1>err-sim run: " + Escape(r.at(errsim_key::kChain).get<std::string>()) + "</h1>\n";
  s += Summary(r) + Distributions(r) + Budget(r);
  return s + kPageEnd;
}

std::string ErrSimSweepHtml(const OrderedJson& r) {
  const std::string unit = r.at(errsim_key::kLengthUnit).get<std::string>();
  std::string s = PageStart("err-sim sweep: " + r.at(errsim_key::kChain).get<std::string>());
  s += "<h1>err-sim sweep: " + Escape(r.at(errsim_key::kChain).get<std::string>()) + "</h1>\n<p>Each parameter swept on its own, "
       "every other at its mean; a slope is one output's d(output)/d(parameter) at the nominal point (every "
       "parameter at its mean), by automatic differentiation, and the steepest slope the largest of them in "
       "magnitude; the text summary's gain is another quantity, the RMS over test points of the error's "
       "derivative (docs/tools/err-sim.md).</p>\n";
  const OrderedJson& parameters = r.at(errsim_key::kParameters);
  std::vector<std::string> sources;
  for (const auto& p : parameters) {
    const std::string source = p.at(errsim_key::kSource).get<std::string>();
    if (std::find(sources.begin(), sources.end(), source) == sources.end()) sources.push_back(source);
  }
  for (const std::string& source : sources) {
    s += "<section><h2>" + Escape(source) + "</h2>\n";
    s += ChartOrNote(SweepCurvesScript(r, source, Total::kImage, "image misregistration RMS (px)"),
                     "image misregistration along the sweeps of " + source,
                     "Image misregistration RMS over the test points and eyes along each parameter's sweep.");
    s += ChartOrNote(SweepCurvesScript(r, source, Total::kMisregistration, "3-D misregistration RMS (" + unit + ")"),
                     "3-D misregistration along the sweeps of " + source,
                     "3-D misregistration RMS over the test points along each parameter's sweep.");
    std::string rows;
    for (size_t i = 0; i < parameters.size(); ++i) {
      const OrderedJson& p = parameters[i];
      if (p.at(errsim_key::kSource) != source) continue;
      const std::string key = JsonPointer({errsim_key::kParameters, std::to_string(i)}), last = std::to_string(p.at(errsim_key::kValues).size() - 1);
      const OrderedJson& slopes = p.at(errsim_key::kSlopePerUnit);
      size_t steepest = 0;
      for (size_t j = 1; j < slopes.size(); ++j) {
        if (slopes[j].is_number() && (!slopes[steepest].is_number() ||
                                      std::abs(slopes[j].get<double>()) > std::abs(slopes[steepest].get<double>()))) {
          steepest = j;
        }
      }
      rows += "<tr><th>" + Name(p.at(errsim_key::kName).get<std::string>()) + "</th><td>" + Escape(p.at(errsim_key::kUnit).get<std::string>()) +
              "</td>" + ValueCell(r, key + JsonPointer({errsim_key::kValues, "0"})) + ValueCell(r, key + JsonPointer({errsim_key::kValues, last})) +
              ValueCell(r, key + JsonPointer({TotalKey(Total::kImage), "0"})) + ValueCell(r, key + JsonPointer({TotalKey(Total::kImage), last})) +
              ValueCell(r, key + JsonPointer({TotalKey(Total::kMisregistration), "0"})) +
              ValueCell(r, key + JsonPointer({TotalKey(Total::kMisregistration), last})) +
              (slopes.empty() ? EmptyCells(1) : ValueCell(r, key + JsonPointer({errsim_key::kSlopePerUnit, std::to_string(steepest)}))) +
              "<td style=\"text-align:left\">" + (slopes.empty() ? "" : Name(r.at(errsim_key::kOutputs).at(steepest).get<std::string>())) +
              "</td></tr>\n";
    }
    s += Table("the sweeps of " + source,
               "<th>parameter</th><th>unit</th><th>lo</th><th>hi</th><th>image RMS at lo (px)</th><th>at hi</th>"
               "<th>3-D RMS at lo (" + unit + ")</th><th>at hi</th><th>steepest slope (output unit per unit)</th><th>of output</th>",
               rows);
    s += "</section>\n";
  }
  return s + kPageEnd;
}

std::string ErrSimHtml(const OrderedJson& output) {
  const std::string format = output.value(errsim_key::kFormat, "");
  if (format == kSweepFormat) return ErrSimSweepHtml(output);
  if (format == kSobolFormat) return ErrSimSobolHtml(output);
  if (format == kLinearFormat) return ErrSimLinearHtml(output);
  VSTCAL_CHECK(format == kReportFormat, "an HTML page is offered for run, merge, sweep, sobol and linear only");
  return ErrSimReportHtml(output);
}

}  // namespace vstcal
