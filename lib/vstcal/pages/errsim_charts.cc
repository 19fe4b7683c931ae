#include "vstcal/pages/errsim_charts.h"

#include <algorithm>

#include "vstcal/formats/errsim/report_keys.h"
#include "vstcal/pages/gnuplot.h"

namespace vstcal {
namespace {

// A report number as gnuplot data: null or absent is NaN (gnuplot leaves it out).
std::string Datum(const OrderedJson& object, const char* key) {
  if (!object.is_object()) return "NaN";
  const auto it = object.find(key);
  return it != object.end() && it->is_number() ? ShortestDecimal(it->get<double>()) : "NaN";
}

}  // namespace

std::string QuantileBarsScript(const std::vector<QuantileBar>& bars, const std::string& ylabel) {
  std::string s = SvgChartHeader(900, 380);
  s += "$q << EOD\n";
  bool any = false;
  for (size_t i = 0; i < bars.size(); ++i) {
    const OrderedJson& st = *bars[i].stats;
    any = any || Datum(st, errsim_key::kMax) != "NaN";
    s += std::to_string(i) + " " + GnuplotQuoted(bars[i].label) + " " + Datum(st, errsim_key::kP50) + " " + Datum(st, errsim_key::kP95) + " " +
         Datum(st, errsim_key::kP99) + " " + Datum(st, errsim_key::kMean) + " " + Datum(st, errsim_key::kMax) + " " +
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

std::string BudgetScript(const OrderedJson& report, Total total) {
  const OrderedJson& budget = report.at(errsim_key::kBudget);
  if (budget.is_null()) return "";
  // The image misregistration is in px, the 3-D measures in the length unit.
  const bool image = Declaration(total).unit == OutputUnit::kPixel;
  const std::string measure = BudgetMeasureKey(total), rms = TotalKey(total);
  std::string s = SvgChartHeader(900, 380);
  s += "$b << EOD\n";
  bool any = false;
  for (const auto& source : budget.at(errsim_key::kRanking).at(measure)) {
    for (const auto& e : budget.at(errsim_key::kEntries)) {
      if (e.at(errsim_key::kSource) != source) continue;
      any = any || Datum(e.at(errsim_key::kAlone), rms.c_str()) != "NaN" || Datum(e.at(errsim_key::kHalved), rms.c_str()) != "NaN";
      s += GnuplotQuoted(source.get<std::string>()) + " " + Datum(e.at(errsim_key::kAlone), rms.c_str()) + " " +
           Datum(e.at(errsim_key::kHalved), rms.c_str()) + "\n";
    }
  }
  if (!any) return "";
  const std::string unit = image ? std::string("px") : report.at(errsim_key::kLengthUnit).get<std::string>();
  s += "EOD\nset style data histograms\nset style histogram clustered gap 1\nset style fill solid 0.85 border -1\n"
       "set ylabel " + GnuplotQuoted((image ? std::string("image misregistration") : measure) + " RMS (" + unit + ")") + "\nset yrange [0:*]\nset xtics rotate by -30 noenhanced\n";
  s += "plot $b using 2:xtic(1) lc rgb \"" + std::string(ChartColour(0)) + "\" title \"this source alone\", "
       "$b using 3 lc rgb \"" + ChartColour(4) + "\" title \"whole chain, this source halved\", " +
       Datum(report.at(errsim_key::kTotals), rms.c_str()) + " with lines lw 2 dt 2 lc rgb \"black\" title \"whole chain\"\n";
  return s;
}

std::string SweepCurvesScript(const OrderedJson& sweep, const std::string& source, Total total, const std::string& ylabel) {
  std::string data, plot;
  size_t lines = 0;
  bool any = false;
  for (const auto& p : sweep.at(errsim_key::kParameters)) {
    if (p.at(errsim_key::kSource) != source) continue;
    const auto& values = p.at(errsim_key::kValues);
    const auto& ys = p.at(TotalKey(total));
    const double lo = values.front().get<double>(), hi = values.back().get<double>();
    const std::string block = "$s" + std::to_string(lines);
    data += block + " << EOD\n";
    for (size_t i = 0; i < values.size(); ++i) {
      const double x = hi > lo ? 2 * (values[i].get<double>() - lo) / (hi - lo) - 1 : 0;
      any = any || ys[i].is_number();
      data += ShortestDecimal(x) + " " + (ys[i].is_number() ? ShortestDecimal(ys[i].get<double>()) : "NaN") + "\n";
    }
    data += "EOD\n";
    plot += std::string(lines ? ", " : "plot ") + block + " using 1:2 with linespoints pt 7 ps 0.4 lw 1.5 lc rgb \"" +
            ChartColour(lines) + "\" dt " + std::to_string(1 + lines / 6) + " title " + GnuplotQuoted(p.at(errsim_key::kName).get<std::string>());
    ++lines;
  }
  if (!any) return "";  // no parameter of the source, or no defined value: gnuplot refuses a plot of no point
  return SvgChartHeader(900, 360 + 18 * static_cast<int>((lines + 2) / 3)) + "set key noenhanced maxrows " +
         std::to_string((lines + 2) / 3) + "\n" + data + "set xlabel \"position in the swept range (-1: lo, 0: middle, +1: hi)\"\n" +
         "set ylabel " + GnuplotQuoted(ylabel) + "\nset xrange [-1:1]\nset yrange [0:*]\n" + plot + "\n";
}

}  // namespace vstcal

namespace vstcal {
namespace {

// `value` of the index object {value, interval: [lo, hi]} as "value lo hi", NaN where null.
std::string IndexColumns(const OrderedJson& index) {
  const auto& interval = index.at(errsim_key::kInterval);
  auto number = [](const OrderedJson& v) { return v.is_number() ? ShortestDecimal(v.get<double>()) : std::string("NaN"); };
  return number(index.at(errsim_key::kValue)) + " " + number(interval.at(0)) + " " + number(interval.at(1));
}

// Rotated output names on the x axis, thinned past 40 labels (as QuantileBarsScript).
std::string OutputTics(size_t n) {
  return "set xtics rotate by -60 noenhanced font \",9\"\n" + (n > 40 ? "set xtics 0, " + std::to_string(n / 20) + "\n" : "");
}

}  // namespace

std::string SobolIndicesScript(const OrderedJson& sobol_output, const OrderedJson& groups) {
  std::string data = "$i << EOD\n";
  bool any = false;
  for (const auto& group : groups) {
    const auto& indices = sobol_output.at(errsim_key::kIndices).at(group.get<std::string>());
    any = any || indices.at(errsim_key::kFirst).at(errsim_key::kValue).is_number() || indices.at(errsim_key::kTotal).at(errsim_key::kValue).is_number();
    data += GnuplotQuoted(group.get<std::string>()) + " " + IndexColumns(indices.at(errsim_key::kFirst)) + " " +
            IndexColumns(indices.at(errsim_key::kTotal)) + "\n";
  }
  if (!any) return "";
  return SvgChartHeader(900, 340) + data +
         "EOD\nset style data histograms\nset style histogram errorbars gap 1 lw 1\nset style fill solid 0.85 border -1\n"
         "set bars 0.4\nset ylabel \"Sobol index\"\nset xtics rotate by -30 noenhanced\nset xzeroaxis lt -1\n"
         "plot $i using 2:3:4:xtic(1) lc rgb \"" + std::string(ChartColour(0)) + "\" title \"first order S_i\" noenhanced, "
         "$i using 5:6:7 lc rgb \"" + ChartColour(1) + "\" title \"total S_Ti\" noenhanced\n";
}

std::string LinearScatterScript(const OrderedJson& linear, const std::vector<size_t>& indices, const std::string& unit) {
  const auto& outputs = linear.at(errsim_key::kOutputs);
  std::string data = "$p << EOD\n";
  double top = 0;
  for (size_t k : indices) {
    const auto& o = outputs.at(k);
    if (!o.at(errsim_key::kLinearSigma).is_number() || !o.at(errsim_key::kMonteCarloSigma).is_number()) continue;
    const double x = o.at(errsim_key::kLinearSigma).get<double>(), y = o.at(errsim_key::kMonteCarloSigma).get<double>();
    top = std::max({top, x, y});
    const bool disagrees = o.at(errsim_key::kMeanDisagrees).get<bool>() || o.at(errsim_key::kSigmaDisagrees).get<bool>();
    data += ShortestDecimal(x) + " " + ShortestDecimal(y) + " " + (disagrees ? "1" : "0") + "\n";
  }
  if (!(top > 0)) return "";
  const std::string range = "[0:" + ShortestDecimal(1.05 * top) + "]";
  return SvgChartHeader(560, 520) + data + "EOD\nset size ratio -1\nset xrange " + range + "\nset yrange " + range +
         "\nset xlabel " + GnuplotQuoted("first-order σ (" + unit + ")") + "\nset ylabel " +
         GnuplotQuoted("Monte Carlo σ (" + unit + ")") + " noenhanced\nset xlabel noenhanced\n"
         "plot x with lines dt 2 lc rgb \"black\" title \"y = x (linear exact)\", "
         "$p using 1:($3 == 0 ? $2 : NaN) with points pt 7 ps 0.8 lc rgb \"" + std::string(ChartColour(0)) +
         "\" title \"agree\", $p using 1:($3 == 1 ? $2 : NaN) with points pt 7 ps 0.9 lc rgb \"" + ChartColour(1) +
         "\" title \"differ beyond 3 standard errors\"\n";
}

std::string LinearRelativeDifferenceScript(const OrderedJson& linear, const std::vector<size_t>& indices) {
  const auto& outputs = linear.at(errsim_key::kOutputs);
  std::string data = "$d << EOD\n";
  bool any = false;
  for (size_t i = 0; i < indices.size(); ++i) {
    const auto& o = outputs.at(indices[i]);
    const auto& d = o.at(errsim_key::kSigmaRelativeDifference);
    const auto& se = o.at(errsim_key::kSigmaStandardError);
    const auto& mc = o.at(errsim_key::kMonteCarloSigma);
    const bool band = se.is_number() && mc.is_number() && mc.get<double>() > 0;
    any = any || d.is_number();
    data += std::to_string(i) + " " + GnuplotQuoted(o.at(errsim_key::kName).get<std::string>()) + " " +
            (d.is_number() ? ShortestDecimal(100 * d.get<double>()) : "NaN") + " " +
            (band ? ShortestDecimal(300 * se.get<double>() / mc.get<double>()) : "NaN") + "\n";
  }
  if (!any) return "";
  return SvgChartHeader(900, 420) + data + "EOD\nset ylabel \"(linear σ - MC σ) / MC σ (%)\" noenhanced\n" +
         "set xrange [-0.7:" + std::to_string(indices.size()) + "-0.3]\nset boxwidth 0.6\nset style fill solid 0.7 border -1\n" +
         "set xzeroaxis lt -1\n" + OutputTics(indices.size()) + "plot $d using 1:3:xtic(2) with boxes lc rgb \"" +
         ChartColour(0) + "\" title \"relative difference of σ\", $d using 1:3:4 with yerrorbars pt -1 lc rgb \"black\" "
         "title \"± 3 standard errors of the Monte Carlo σ\"\n";
}

}  // namespace vstcal
