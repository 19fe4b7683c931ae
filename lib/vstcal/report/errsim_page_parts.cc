#include "vstcal/report/errsim_page_parts.h"

#include "vstcal/report/html_page.h"

namespace vstcal::errsim_page {

std::string ValueCell(const io::OrderedJson& output, const std::string& pointer) {
  const io::OrderedJson::json_pointer at(pointer);
  if (!output.contains(at)) return html::EmptyCells(1);
  const io::OrderedJson& v = output.at(at);
  if (v.is_number_integer() && v.get<int64_t>() >= 0) return html::Cell(pointer, v.get<size_t>());  // counts
  return v.is_number() ? html::Cell(pointer, v.get<double>()) : html::EmptyCells(1);
}

std::string Table(const std::string& caption, const std::string& heads, const std::string& rows) {
  return "<table><caption>" + html::Escape(caption) + "</caption><tr>" + heads + "</tr>\n" + rows + "</table>\n";
}

std::string ChartOrNote(const std::string& script, const std::string& alt, const std::string& caption) {
  return script.empty() ? "<p class=\"none\">" + html::Escape(alt) + ": no defined value to draw.</p>\n"
                        : html::Chart(script, alt, caption);
}

}  // namespace vstcal::errsim_page
