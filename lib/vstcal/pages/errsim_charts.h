// err-sim's charts as gnuplot scripts (drawn by RunGnuplot, gnuplot.h): every number is read from
// the vstcal/err-sim-report@3 JSON (docs/formats.md#err-sim-report) and handed to gnuplot as an
// inline data block, so the pictures show exactly what the report file holds.
#pragma once

#include <string>
#include <vector>

#include "vstcal/errsim/outputs.h"
#include "vstcal/json/json_writer.h"

namespace vstcal {

// One distribution to draw: a statistics object of the report (mean, max, p50, p95, p99; null when
// no sample was defined), its label and its colour index (ChartColour).
struct QuantileBar {
  std::string label;
  const OrderedJson* stats;
  size_t colour;
};
// Each distribution as a box from the median to p95 with a whisker to p99, the mean (dot) and the
// maximum (cross); a distribution without a value is left blank. `ylabel` names the quantity.
// Empty when no distribution has a value (as every script below when it would draw nothing).
std::string QuantileBarsScript(const std::vector<QuantileBar>& bars, const std::string& ylabel);

// The error budget of the measure of `total` (one the budget ranks by: image, misregistration or
// misperception): the sources in the report's ranking for that measure, each with two bars, the
// RMS with that source alone and the RMS of the whole chain with that source halved, and the whole
// chain's RMS as a line. Empty without a budget.
std::string BudgetScript(const OrderedJson& report, Total total);

// A sweep report's (vstcal/err-sim-sweep@2) curves of the parameters of one `source`: `total`
// (its key: "misregistration_rms", "image_rms_px" …) against each parameter's position in its swept range,
// −1 at its lo end, +1 at its hi end (the parameters have different units), one line each.
// Empty when the sweep has no parameter of that source.
std::string SweepCurvesScript(const OrderedJson& sweep, const std::string& source, Total total, const std::string& ylabel);

}  // namespace vstcal

namespace vstcal {

// One output of a vstcal/err-sim-sobol@2 file (`outputs[k]`): for each source in `groups`, its
// first-order and total Sobol index as two bars, each with its bootstrap interval as an error bar.
// Empty when no index of the output is a number.
std::string SobolIndicesScript(const OrderedJson& sobol_output, const OrderedJson& groups);

// A vstcal/err-sim-linear@2 file's comparison for the outputs `indices` (one unit): each output a
// point at (first-order σ, Monte Carlo σ), red where the file says linear and Monte Carlo disagree,
// beside the line y = x where they would agree. `unit` labels the axes. Empty without a defined pair.
std::string LinearScatterScript(const OrderedJson& linear, const std::vector<size_t>& indices, const std::string& unit);

// The same outputs' relative difference (linear σ − MC σ) / MC σ in %, one bar each, with ±3 of the
// Monte Carlo σ's standard errors (relative) as the error bar: a bar whose error bar misses 0 is
// beyond what sampling noise explains. Empty without a defined difference.
std::string LinearRelativeDifferenceScript(const OrderedJson& linear, const std::vector<size_t>& indices);

}  // namespace vstcal
