// Pieces of err-sim's pages (errsim_html.h) shared by the run, sweep, sobol and linear pages: a
// cell showing the output value at a JSON pointer, a captioned table, a chart or the line saying why
// there is none.
#pragma once

#include <string>

#include "vstcal/json/json_writer.h"

namespace vstcal {

// The value of `output` at `pointer` as a table cell (Cell, carrying the pointer), a dash
// when it is null, absent or not a number; a non-negative integer is shown as a count.
std::string ValueCell(const OrderedJson& output, const std::string& pointer);

// <table> with `caption`, a header row of `heads` (<th> cells) and `rows`.
std::string Table(const std::string& caption, const std::string& heads, const std::string& rows);

// Chart of `script`, or, when the script is empty (nothing defined to draw), a line saying so.
std::string ChartOrNote(const std::string& script, const std::string& alt, const std::string& caption);

}  // namespace vstcal
