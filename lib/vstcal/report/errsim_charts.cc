#include "vstcal/report/errsim_charts.h"

#include "vstcal/report/gnuplot.h"

namespace vstcal {
namespace {

// A report number as gnuplot data: null or absent is NaN (gnuplot leaves it out).
std::string Datum(const io::OrderedJson& object, const char* key) {
  if (!object.is_object()) return "NaN";
  const auto it = object.find(key);
  return it != object.end() && it->is_number() ? io::ShortestDecimal(it->get<double>()) : "NaN";
}

}  // namespace

std::string QuantileBarsScript(const std::vector<QuantileBar>& bars, const std::string& ylabel) {
  std::string s = SvgChartHeader(900, 380);
  s += "$q << EOD\n";
  bool any = false;
  for (size_t i = 0; i < bars.size(); ++i) {
    const io::OrderedJson& st = *bars[i].stats;
    any = any || Datum(st, "max") != "NaN";
    s += std::to_string(i) + " " + GnuplotQuoted(bars[i].label) + " " + Datum(st, "p50") + " " + Datum(st, "p95") + " " +
         Datum(st, "p99") + " " + Datum(st, "mean") + " " + Datum(st, "max") + " " +
         std::to_string(std::stoul(ChartColour(bars[i].colour) + 1, nullptr, 16)) + "\n";  // "#rrggbb" as 0xrrggbb
  }
  if (!any) return "";  // gnuplot refuses a plot of no point
  s += "EOD\nset ylabel " + GnuplotQuoted(ylabel) + "\nset yrange [0:*]\nset xrange [-0.7:" + std::to_string(bars.size()) +
       "-0.3]\nset xtics rotate by -45 noenhanced\nset boxwidth 0.5\nset style fill solid 0.6 border -1\n";
  if (bars.size() > 40) s += "set xtics 0, " + std::to_string(bars.size() / 20) + "\n";
  s += "plot $q using 1:3:3:5:4:8:xtic(2) with candlesticks whiskerbars 0.5 lc rgb variable "
       "title \"median to p95, whisker to p99\", "
       "$q using 1:6 with points pt 7 ps 0.6 lc rgb \"black\" title \"mean\", "
       "$q using 1:7 with points pt 2 ps 0.8 lc rgb \"#555555\" title \"max\"\n";
  return s;
}

std::string BudgetScript(const io::OrderedJson& report, const std::string& measure) {
  const io::OrderedJson& budget = report.at("budget");
  if (budget.is_null()) return "";
  const std::string rms = measure + "_rms";
  std::string s = SvgChartHeader(900, 380);
  s += "$b << EOD\n";
  bool any = false;
  for (const auto& source : budget.at("ranking").at(measure)) {
    for (const auto& e : budget.at("entries")) {
      if (e.at("source") != source) continue;
      any = any || Datum(e.at("alone"), rms.c_str()) != "NaN" || Datum(e.at("halved"), rms.c_str()) != "NaN";
      s += GnuplotQuoted(source.get<std::string>()) + " " + Datum(e.at("alone"), rms.c_str()) + " " +
           Datum(e.at("halved"), rms.c_str()) + "\n";
    }
  }
  if (!any) return "";
  const std::string unit = report.at("length_unit").get<std::string>();
  s += "EOD\nset style data histograms\nset style histogram clustered gap 1\nset style fill solid 0.85 border -1\n"
       "set ylabel " + GnuplotQuoted(measure + " RMS (" + unit + ")") + "\nset yrange [0:*]\nset xtics rotate by -30 noenhanced\n";
  s += "plot $b using 2:xtic(1) lc rgb \"" + std::string(ChartColour(0)) + "\" title \"this source alone\", "
       "$b using 3 lc rgb \"" + ChartColour(4) + "\" title \"whole chain, this source halved\", " +
       Datum(report.at("totals"), rms.c_str()) + " with lines lw 2 dt 2 lc rgb \"black\" title \"whole chain\"\n";
  return s;
}

std::string SweepCurvesScript(const io::OrderedJson& sweep, const std::string& source, const std::string& measure,
                              const std::string& ylabel) {
  std::string data, plot;
  size_t lines = 0;
  bool any = false;
  for (const auto& p : sweep.at("parameters")) {
    if (p.at("source") != source) continue;
    const auto& values = p.at("values");
    const auto& ys = p.at(measure);
    const double lo = values.front().get<double>(), hi = values.back().get<double>();
    const std::string block = "$s" + std::to_string(lines);
    data += block + " << EOD\n";
    for (size_t i = 0; i < values.size(); ++i) {
      const double x = hi > lo ? 2 * (values[i].get<double>() - lo) / (hi - lo) - 1 : 0;
      any = any || ys[i].is_number();
      data += io::ShortestDecimal(x) + " " + (ys[i].is_number() ? io::ShortestDecimal(ys[i].get<double>()) : "NaN") + "\n";
    }
    data += "EOD\n";
    plot += std::string(lines ? ", " : "plot ") + block + " using 1:2 with linespoints pt 7 ps 0.4 lw 1.5 lc rgb \"" +
            ChartColour(lines) + "\" dt " + std::to_string(1 + lines / 6) + " title " + GnuplotQuoted(p.at("name").get<std::string>());
    ++lines;
  }
  if (!any) return "";  // no parameter of the source, or no defined value: gnuplot refuses a plot of no point
  return SvgChartHeader(900, 360 + 18 * static_cast<int>((lines + 2) / 3)) + "set key noenhanced maxrows " +
         std::to_string((lines + 2) / 3) + "\n" + data + "set xlabel \"position in the swept range (-1: lo, 0: middle, +1: hi)\"\n" +
         "set ylabel " + GnuplotQuoted(ylabel) + "\nset xrange [-1:1]\nset yrange [0:*]\n" + plot + "\n";
}

}  // namespace vstcal
