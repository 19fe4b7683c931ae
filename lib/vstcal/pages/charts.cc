#include "vstcal/pages/charts.h"

#include <algorithm>
#include <cmath>

#include "vstcal/scene/measured_volume.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/pages/gnuplot.h"

namespace vstcal {
namespace {

std::string Number(double v) { return ShortestDecimal(v); }

std::string CameraTitle(const ReprojReport& r, size_t k) {
  const CameraReport& c = r.cameras[k];
  return GnuplotQuoted(std::to_string(k) + ": " + c.file + (c.method.empty() ? "" : " (" + c.method + ")"));
}

}  // namespace

std::string HistogramScript(const ReprojReport& r) {
  double top = 0;
  for (const CameraReport& c : r.cameras) {
    if (c.overall.error_px) top = std::max(top, c.overall.error_px->max);
  }
  if (!(top > 0)) top = 1;
  constexpr int kBins = 40;
  const double width = top / kBins;
  std::string s = SvgChartHeader(900, 360);
  std::string plot = "plot ";
  for (size_t k = 0; k < r.cameras.size(); ++k) {
    std::vector<size_t> counts(kBins, 0);
    for (const ViewReport& v : r.cameras[k].views) {
      for (const PointError& e : v.points) {
        if (e.excluded == Exclusion::kNone) ++counts[std::min<size_t>(kBins - 1, static_cast<size_t>(e.error_px / width))];
      }
    }
    s += "$h" + std::to_string(k) + " << EOD\n";
    for (int b = 0; b < kBins; ++b) s += Number(b * width) + " " + std::to_string(counts[b]) + "\n";
    s += Number(kBins * width) + " " + std::to_string(counts[kBins - 1]) + "\nEOD\n";
    plot += std::string(k ? ", " : "") + "$h" + std::to_string(k) + " using 1:2 with steps lw 2 lc rgb \"" + ChartColour(k) +
            "\" title " + CameraTitle(r, k);
  }
  s += "set xlabel \"|residual| (px)\"\nset ylabel \"points\"\nset xrange [0:" + Number(top) + "]\nset yrange [0:*]\n";
  return s + plot + "\n";
}

std::string PerViewScript(const ReprojReport& r) {
  std::string s = SvgChartHeader(900, 360);
  s += "$v << EOD\n";
  const size_t n_views = r.correspondences.views.size();
  for (size_t v = 0; v < n_views; ++v) {
    s += GnuplotQuoted(r.correspondences.views[v].name);
    for (const CameraReport& c : r.cameras) s += " " + (c.views[v].error_px ? Number(c.views[v].error_px->rms) : "NaN");
    s += "\n";
  }
  s += "EOD\nset style data histograms\nset style histogram clustered gap 1\nset style fill solid 0.85 border -1\n"
       "set ylabel \"RMS |residual| (px)\"\nset yrange [0:*]\nset xtics rotate by -45 noenhanced\n";
  if (n_views > 40) s += "set xtics 0, " + std::to_string(n_views / 20) + "\n";
  std::string plot = "plot ";
  for (size_t k = 0; k < r.cameras.size(); ++k) {
    plot += std::string(k ? ", " : "") + "$v using " + std::to_string(k + 2) + (k ? "" : ":xtic(1)") + " lc rgb \"" +
            ChartColour(k) + "\" title " + CameraTitle(r, k);
  }
  return s + plot + "\n";
}

std::string DepthScript(const ReprojReport& r) {
  std::string s = SvgChartHeader(900, 560);
  const std::string unit(LengthUnitName(r.correspondences.length_unit));
  for (size_t k = 0; k < r.cameras.size(); ++k) {
    std::vector<const PointError*> points;
    for (const ViewReport& v : r.cameras[k].views) {
      for (const PointError& e : v.points) {
        if (e.excluded == Exclusion::kNone) points.push_back(&e);
      }
    }
    const size_t stride = std::max<size_t>(1, (points.size() + kMaxScatterPoints - 1) / kMaxScatterPoints);
    s += "$d" + std::to_string(k) + " << EOD\n";
    for (size_t i = 0; i < points.size(); i += stride) {
      s += Number(points[i]->depth) + " " + Number(points[i]->error_px) + " " + Number(points[i]->lateral) + "\n";
    }
    s += "EOD\n";
  }
  s += "set multiplot layout 2,1\nset key noenhanced\n";
  for (const int column : {2, 3}) {
    s += column == 2 ? "set ylabel \"|residual| (px)\"\nunset xlabel\n"
                     : "set ylabel " + GnuplotQuoted("lateral error (" + unit + ")") + "\nset xlabel " +
                           GnuplotQuoted("distance from the camera (" + unit + ")") + "\n";
    std::string plot = "plot ";
    for (size_t k = 0; k < r.cameras.size(); ++k) {
      plot += std::string(k ? ", " : "") + "$d" + std::to_string(k) + " using 1:" + std::to_string(column) +
              " with points pt 7 ps 0.35 lc rgb \"" + ChartColour(k) + "\" title " + CameraTitle(r, k);
    }
    s += plot + "\n";
  }
  return s + "unset multiplot\n";
}

std::string HeatMapScript(const ImageGrid& g, const std::vector<std::optional<double>>& cells, const std::string& label) {
  const ImageSize& size = g.image_size;
  const int width = 700, height = std::clamp(static_cast<int>(700.0 * size.height / size.width) + 60, 200, 900);
  std::string s = SvgChartHeader(width, height);
  // Cell centres in pixel coordinates; an empty cell is NaN (drawn blank).
  s += "$g << EOD\n";
  for (int row = 0; row < g.rows; ++row) {
    for (int col = 0; col < g.cols; ++col) {
      const std::optional<double>& cell = cells[static_cast<size_t>(row) * g.cols + col];
      const Eigen::Vector2d centre = g.CellCentre(col, row);
      s += Number(centre.x()) + " " + Number(centre.y()) + " " + (cell ? Number(*cell) : "NaN") + "\n";
    }
    s += "\n";
  }
  s += "EOD\nset xrange [-0.5:" + Number(size.width - 0.5) + "]\nset yrange [" + Number(size.height - 0.5) +
       ":-0.5]\nset size ratio -1\nset xlabel \"u (px)\"\nset ylabel \"v (px)\"\n"
       "set cblabel " + GnuplotQuoted(label) + "\nset palette defined (0 \"#ffffcc\", 1 \"#fd8d3c\", 2 \"#800026\")\n"
       "unset grid\nset cbrange [0:*]\n";
  s += "plot $g using 1:2:3 with image pixels notitle\n";
  return s;
}

std::string TestPointsScript(const ReprojReport& r) {
  // Column 4: 1 inside the measured volume, 2 outside, 0 when the calibration points span none.
  const std::string kSideColour = "($4 == 1 ? 0x1f77b4 : $4 == 2 ? 0xd62728 : 0x7f7f7f)";
  std::string data;
  size_t rows = 0;
  for (size_t k = 0; k < r.cameras.size(); ++k) {
    for (const TestPointReport& t : r.cameras[k].test_points) {
      if (t.error.excluded != Exclusion::kNone) continue;
      const char* where = VolumeSideName(t.inside_volume);
      data += GnuplotQuoted(std::to_string(k) + ":" + t.name + " (" + where + ")") + " " + Number(t.error.error_px) + " " +
              Number(t.error.lateral) + " " + (!t.inside_volume ? "0" : *t.inside_volume ? "1" : "2") + "\n";
      ++rows;
    }
  }
  if (rows == 0) return {};
  const std::string unit(LengthUnitName(r.correspondences.length_unit));
  std::string s = SvgChartHeader(900, 420);
  s += "$t << EOD\n" + data + "EOD\n";
  s += "set style fill solid 0.85 border -1\nset boxwidth 0.7\nset xtics rotate by -45 noenhanced\nset yrange [0:*]\n"
       "set multiplot layout 1,2\nset key off\n"
       "set title \"|residual| (px): blue inside the volume, red outside, grey without a hull\"\n"
       "plot $t using 0:2:" + kSideColour + ":xtic(1) with boxes lc rgb variable\n"
       "set title " + GnuplotQuoted("lateral error (" + unit + ")") + "\n"
       "plot $t using 0:3:" + kSideColour + ":xtic(1) with boxes lc rgb variable\nunset multiplot\n";
  return s;
}

}  // namespace vstcal
