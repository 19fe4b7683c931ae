// err-sim's pages. The run page (html_page.h: self-contained, opens offline): the error distributions per
// test point and eye as quantile bars, the error budget as ranked bars with the halved-source
// column, and the tables behind them. It is drawn from the report as written
// (vstcal/err-sim-report@3, formats/errsim/report_format.h), never recomputed: each number shown
// carries the JSON pointer it comes from, e.g. data-key="/test_points/0/image/left/pixel_px/p95".
#pragma once

#include <cstddef>
#include <string>

#include "vstcal/json/json_writer.h"

namespace vstcal {

// The page of an err-sim output, by its "format": a run report (ErrSimReportHtml), a sweep
// (ErrSimSweepHtml), Sobol indices (ErrSimSobolHtml) or a linear comparison (ErrSimLinearHtml).
// VSTCAL_CHECK for another format (the tool offers --html for these only).
std::string ErrSimHtml(const OrderedJson& output);

// `report` is a complete err-sim run report (err-sim run or merge); the charts are drawn by gnuplot.
// Throws what RunGnuplot throws.
std::string ErrSimReportHtml(const OrderedJson& report);

// `sweep` is a vstcal/err-sim-sweep@2 output: per source, the curves of the image and the 3-D
// misregistration along each parameter's swept range; per parameter, its range, the measures at both
// ends and its steepest slope (autodiff, at the nominal point) over the outputs, with that output's name.
std::string ErrSimSweepHtml(const OrderedJson& sweep);

// `sobol` is a vstcal/err-sim-sobol@2 output: the first-order and total index of each source with
// its bootstrap interval, charted for each test point's image error per eye and linear
// misregistration and misperception (the first kMaxSobolCharts of them: a chart is ~25 kB), in
// tables for every output. errsim_sensitivity_html.cc.
std::string ErrSimSobolHtml(const OrderedJson& sobol);
inline constexpr size_t kMaxSobolCharts = 40;

// `linear` is a vstcal/err-sim-linear@2 output: first-order σ against Monte Carlo σ per output (a
// scatter with y = x for the pixel and for the length outputs), their relative difference with the
// Monte Carlo σ's ±3 standard errors, and the table of means, σs and σ per source.
std::string ErrSimLinearHtml(const OrderedJson& linear);

}  // namespace vstcal
