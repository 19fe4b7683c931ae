#include "vstcal/pages/html_page.h"

#include <cstdio>

#include "vstcal/formats/report/report_keys.h"
#include "vstcal/json/json_pointer.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/pages/gnuplot.h"

namespace vstcal {

std::string Escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string Name(const std::string& name) {
  std::string out;
  for (const char c : name) {
    out += Escape(std::string(1, c));
    if (c == '.' || c == '_') out += "<wbr>";
  }
  return out;
}

std::string Cell(const std::string& key, double v, int digits) {
  char shown[64];
  std::snprintf(shown, sizeof shown, "%.*f", digits, v);
  return "<td data-key=\"" + Escape(key) + "\" data-value=\"" + ShortestDecimal(v) + "\">" + shown + "</td>";
}
std::string Cell(const std::string& key, size_t n) {
  return "<td data-key=\"" + Escape(key) + "\" data-value=\"" + std::to_string(n) + "\">" + std::to_string(n) + "</td>";
}
std::string EmptyCells(int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += "<td class=\"none\">—</td>";
  return s;
}

std::string Figure(const std::string& mime, const std::string& base64, const std::string& alt, const std::string& caption) {
  return "<figure><img alt=\"" + Escape(alt) + "\" src=\"data:" + mime + ";base64," + base64 + "\"><figcaption>" +
         Escape(caption) + "</figcaption></figure>\n";
}

std::string Chart(const std::string& script, const std::string& alt, const std::string& caption) {
  return Figure("image/svg+xml", Base64(RunGnuplot(script)), alt, caption);
}

// Tables are set a little smaller than the text, with narrow cell padding: a row with a column per
// error source (err-sim's seven) then fits the 1000 px page, as the browser tests check.
std::string PageStart(const std::string& title) {
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
         "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; style-src 'unsafe-inline'\">\n"
         "<title>" + Escape(title) + "</title>\n<style>\n"
         "body{font-family:sans-serif;margin:1.5em;max-width:1000px;color:#222}"
         "table{border-collapse:collapse;margin:0.8em 0;font-size:90%}"
         "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}th{background:#f4f4f4}caption{text-align:left;"
         "font-weight:bold;padding:4px 0}td.none{color:#999}figure{margin:1em 0}img{max-width:100%;border:1px solid #ddd}"
         "figcaption{font-size:90%;color:#555}"
         ".small-multiples{display:flex;flex-wrap:wrap;gap:8px}.small-multiples>p{flex-basis:100%;margin:0}"
         "figure.view-residuals{margin:0;width:240px}figure.view-residuals svg{display:block}\n</style></head><body>\n";
}

std::string Base64(const unsigned char* data, size_t size) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (size_t i = 0; i < size; i += 3) {
    const unsigned a = data[i], b = i + 1 < size ? data[i + 1] : 0, c = i + 2 < size ? data[i + 2] : 0;
    const unsigned triple = (a << 16) | (b << 8) | c;
    out += kAlphabet[(triple >> 18) & 63];
    out += kAlphabet[(triple >> 12) & 63];
    out += i + 1 < size ? kAlphabet[(triple >> 6) & 63] : '=';
    out += i + 2 < size ? kAlphabet[triple & 63] : '=';
  }
  return out;
}

std::string StatsRow(const std::string& label, const std::string& key, const std::optional<ErrorStats>& s) {
  std::string row = "<tr><th>" + Escape(label) + "</th>";
  if (!s) return row + EmptyCells(6) + "</tr>\n";
  namespace k = reproj_key;
  row += Cell(key + JsonPointer({k::kN}), s->n) + Cell(key + JsonPointer({k::kMean}), s->mean) +
         Cell(key + JsonPointer({k::kRms}), s->rms) + Cell(key + JsonPointer({k::kMedian}), s->median) +
         Cell(key + JsonPointer({k::kP95}), s->p95) + Cell(key + JsonPointer({k::kMax}), s->max);
  return row + "</tr>\n";
}

std::string StatsTable(const std::string& caption, const std::string& rows) {
  return "<table><caption>" + Escape(caption) +
         "</caption><tr><th></th><th>n</th><th>mean</th><th>rms</th><th>median</th><th>p95</th><th>max</th></tr>\n" + rows +
         "</table>\n";
}

}  // namespace vstcal
