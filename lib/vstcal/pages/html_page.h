// The pieces every vstcal HTML page is made of (reproj-report, err-sim): one self-contained file,
// styles inline, every picture a data: URI, a Content-Security-Policy that forbids any fetch. A
// number shown in a table cell carries the JSON pointer of the report value it shows and that value
// in the shortest round-trip decimal (data-key="/a/0/b" data-value="0.41842941"), so a test can
// read the rendered page back and compare it with the JSON.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "vstcal/report/statistics.h"

namespace vstcal {

// Text for element content and attribute values (& < > " escaped).
std::string Escape(const std::string& text);
// A dotted or snake_case name (a parameter, a source, an output: "camera_intrinsic.left.cx") as
// element content, escaped, with a line-break opportunity (<wbr>) after each '.' and '_': the name
// wraps there rather than pushing its table past the page.
std::string Name(const std::string& name);

// <td> showing `v` to 4 decimals (`digits`), carrying `key` (a JSON pointer) and the exact value.
std::string Cell(const std::string& key, double v, int digits = 4);
std::string Cell(const std::string& key, size_t n);
// `n` cells showing a dash (no value).
std::string EmptyCells(int n);

// One row of a statistics table, `label` then n, mean, rms, median, p95, max (`key` + "/n", …), or
// dashes for no value; and the table around such rows.
std::string StatsRow(const std::string& label, const std::string& key, const std::optional<ErrorStats>& s);
std::string StatsTable(const std::string& caption, const std::string& rows);

// A figure with an inline picture (`base64` of a `mime` image) and its caption.
std::string Figure(const std::string& mime, const std::string& base64, const std::string& alt, const std::string& caption);
// A gnuplot script (charts.h conventions) drawn to SVG by RunGnuplot and inlined as a figure.
std::string Chart(const std::string& script, const std::string& alt, const std::string& caption);

// From <!DOCTYPE html> to the opening <body>, with the policy and the shared style sheet; and the end.
std::string PageStart(const std::string& title);
inline constexpr const char* kPageEnd = "</body></html>\n";

// RFC 4648 base64 (with padding), for data: URIs.
std::string Base64(const unsigned char* data, size_t size);
inline std::string Base64(const std::string& text) {
  return Base64(reinterpret_cast<const unsigned char*>(text.data()), text.size());
}

}  // namespace vstcal
