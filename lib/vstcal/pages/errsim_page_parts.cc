#include "vstcal/pages/errsim_page_parts.h"

#include "vstcal/pages/html_page.h"

namespace vstcal {

std::string ValueCell(const OrderedJson& output, const std::string& pointer) {
  const OrderedJson::json_pointer at(pointer);
  if (!output.contains(at)) return EmptyCells(1);
  const OrderedJson& v = output.at(at);
  if (v.is_number_integer() && v.get<int64_t>() >= 0) return Cell(pointer, v.get<size_t>());  // counts
  return v.is_number() ? Cell(pointer, v.get<double>()) : EmptyCells(1);
}

std::string Table(const std::string& caption, const std::string& heads, const std::string& rows) {
  return "<table><caption>" + Escape(caption) + "</caption><tr>" + heads + "</tr>\n" + rows + "</table>\n";
}

std::string ChartOrNote(const std::string& script, const std::string& alt, const std::string& caption) {
  return script.empty() ? "<p class=\"none\">" + Escape(alt) + ": no defined value to draw.</p>\n"
                        : Chart(script, alt, caption);
}

}  // namespace vstcal
