#include "vstcal/pages/stereo_html.h"

#include <algorithm>
#include <cstdio>

#include "vstcal/formats/report/report_keys.h"
#include "vstcal/json/json_pointer.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/pages/charts.h"
#include "vstcal/pages/gnuplot.h"
#include "vstcal/pages/html_page.h"
#include "vstcal/pages/overlay.h"

namespace vstcal {
namespace {


std::string Fixed4(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.4f", v);
  return b;
}

std::string StereoRows(const std::string& key, const std::string& unit, const StereoStats& s) {
  namespace k = reproj_key;
  return StatsRow("|dx| " + unit, key + JsonPointer({k::kX}), s.x) + StatsRow("|dy| " + unit, key + JsonPointer({k::kY}), s.y) +
         StatsRow("|dz| " + unit, key + JsonPointer({k::kZ}), s.z) +
         StatsRow("linear " + unit, key + JsonPointer({k::kLinear}), s.linear) +
         StatsRow("lateral " + unit, key + JsonPointer({k::kLateral}), s.lateral) +
         StatsRow("|depth| " + unit, key + JsonPointer({k::kDepth}), s.depth) +
         StatsRow("angular deg", key + JsonPointer({k::kAngularDeg}), s.angular_deg);
}

// Test points inside and outside the measured volume, and each one's error.
std::string TestPointSection(const StereoReport& r, const std::string& unit) {
  std::string s = "<h2>Test points</h2>\n<p>Points never used in a calibration, triangulated like the others. Measured "
                  "volume (the convex hull of both files' calibration points): " + Escape(r.volume.status) + ".</p>\n";
  s += StatsTable("measured test points inside the volume", StereoRows(JsonPointer({reproj_key::kStereo, reproj_key::kTestPoints, reproj_key::kInside}), unit, r.test_inside));
  s += StatsTable("measured test points outside the volume", StereoRows(JsonPointer({reproj_key::kStereo, reproj_key::kTestPoints, reproj_key::kOutside}), unit, r.test_outside));
  std::string rows;
  for (size_t i = 0; i < r.test_points.size(); ++i) {
    const StereoTestPoint& t = r.test_points[i];
    // The error array: [dx, dy, dz, linear, …].
    const std::string key =
        JsonPointer({reproj_key::kStereo, reproj_key::kTestPoints, reproj_key::kPoints, std::to_string(i), reproj_key::kError}) + "/";
    rows += "<tr><th>" + Escape(t.name) + "</th><td>" +
            (t.inside_volume ? (*t.inside_volume ? "inside" : "outside") : "—") + "</td>";
    if (t.error.excluded != StereoExclusion::kNone) {
      rows += "<td colspan=\"4\" class=\"none\">excluded: " + std::string(StereoExclusionName(t.error.excluded)) + "</td></tr>\n";
      continue;
    }
    const Eigen::Vector3d d = t.error.error();
    rows += Cell(key + "0", d.x()) + Cell(key + "1", d.y()) + Cell(key + "2", d.z()) +
            Cell(key + "3", t.error.linear) + "</tr>\n";
  }
  return s + "<table><caption>each test point (" + Escape(unit) + ")</caption><tr><th>name</th><th>volume</th>"
             "<th>dx</th><th>dy</th><th>dz</th><th>linear</th></tr>\n" + rows + "</table>\n";
}

// Per view: each camera's reprojection RMS through the rig and the view's triangulated error.
std::string PerViewTable(const StereoReport& r, const std::string& unit) {
  const auto stat = [](const std::string& key, const std::optional<ErrorStats>& s, auto field) {
    return s ? Cell(key, (*s).*field) : EmptyCells(1);
  };
  std::string rows;
  for (size_t v = 0; v < r.views.size(); ++v) {
    const StereoViewReport& view = r.views[v];
    const std::string key = JsonPointer({reproj_key::kStereo, reproj_key::kViews, std::to_string(v)});
    rows += "<tr><th>" + Escape(view.name) + "</th><td>" + Escape(view.pose_status) + "</td>" +
            stat(key + JsonPointer({reproj_key::kReprojection, reproj_key::kLeft, reproj_key::kErrorPx, reproj_key::kRms}), view.left.error_px,
                 &ErrorStats::rms) +
            stat(key + JsonPointer({reproj_key::kReprojection, reproj_key::kRight, reproj_key::kErrorPx, reproj_key::kRms}), view.right.error_px,
                 &ErrorStats::rms) +
            (view.stats.linear ? Cell(key + JsonPointer({reproj_key::kStats, reproj_key::kLinear, reproj_key::kN}), view.stats.linear->n) : EmptyCells(1)) +
            stat(key + JsonPointer({reproj_key::kStats, reproj_key::kLinear, reproj_key::kRms}), view.stats.linear, &ErrorStats::rms) +
            stat(key + JsonPointer({reproj_key::kStats, reproj_key::kLinear, reproj_key::kMax}), view.stats.linear, &ErrorStats::max) + "</tr>\n";
  }
  return "<table><caption>per view: each camera's reprojection error through the rig and the triangulated error</caption>"
         "<tr><th>view</th><th>left pose</th><th>left RMS px</th><th>right RMS px</th><th>points triangulated</th>"
         "<th>linear RMS " + Escape(unit) + "</th><th>linear max " + Escape(unit) + "</th></tr>\n" + rows + "</table>\n";
}

// A camera's residual vectors through the rig over the common views (overlay.h).
std::string OverlayFigure(const StereoReport& r, bool left, const std::filesystem::path& dir) {
  const std::string& file = left ? r.left_file : r.right_file;
  std::vector<OverlayView> views;
  for (const StereoViewReport& v : r.views) {
    const StereoReprojection& cam = left ? v.left : v.right;
    views.push_back({v.name, cam.image, file + ": views[" + std::to_string(cam.file_view) + "].image: ", cam.points});
  }
  const StereoCameraGrid& grid = left ? r.left_grid : r.right_grid;
  const OverlayPicture overlay = DrawResidualOverlay(views, grid.grid.image_size, grid.overall_px, dir);
  const std::string eye = left ? "left" : "right";
  return Figure("image/png", Base64(overlay.png.data(), overlay.png.size()), "residual vectors " + eye,
                      "The " + eye + " camera's residual vectors " +
                          (left ? "against its own PnP pose" : "through the rig's relative pose") + ": " + overlay.caption + ".");
}

}  // namespace

std::string StereoDepthScript(const StereoReport& r) {
  std::vector<const StereoPointError*> points;
  for (const StereoViewReport& v : r.views) {
    for (const StereoPointError& e : v.points) {
      if (e.excluded == StereoExclusion::kNone) points.push_back(&e);
    }
  }
  if (points.empty()) return "";
  const std::string unit(LengthUnitName(r.length_unit));
  const size_t stride = std::max<size_t>(1, (points.size() + kMaxScatterPoints - 1) / kMaxScatterPoints);
  std::string s = SvgChartHeader(900, 420) + "$d << EOD\n";
  for (size_t i = 0; i < points.size(); i += stride) {
    const Eigen::Vector3d d = points[i]->error();
    s += ShortestDecimal(points[i]->truth.z()) + " " + ShortestDecimal(std::abs(d.x())) + " " +
         ShortestDecimal(std::abs(d.y())) + " " + ShortestDecimal(std::abs(d.z())) + "\n";
  }
  s += "EOD\nset xlabel " + GnuplotQuoted("depth z of the point in the left camera's frame (" + unit + ")") +
       "\nset ylabel " + GnuplotQuoted("triangulated error (" + unit + ")") + "\nset yrange [0:*]\nplot ";
  const char* axes[] = {"|dx|", "|dy|", "|dz|"};
  for (int a = 0; a < 3; ++a) {
    s += std::string(a ? ", " : "") + "$d using 1:" + std::to_string(a + 2) + " with points pt 7 ps 0.35 lc rgb \"" +
         ChartColour(static_cast<size_t>(a)) + "\" title \"" + axes[a] + "\"";
  }
  return s + "\n";
}

std::string StereoReportHtml(const StereoReport& r, const std::filesystem::path& left_dir, const std::filesystem::path& right_dir) {
  const std::string unit(LengthUnitName(r.length_unit));
  std::string s = PageStart("reproj-report: stereo rig " + r.rig_file);
  s += "<h1>Stereo rig " + Escape(r.rig_file) + "</h1>\n<p>" + Escape(r.left_file) + " and " + Escape(r.right_file) + ": " +
       std::to_string(r.views.size()) + " views seen by both cameras, baseline " + Fixed4(r.baseline) + " " +
       Escape(unit) + ". Each point both cameras saw is triangulated through the rig (the midpoint of the two rays) and "
       "compared with the known point in the left camera's frame (x right, y down, z forward); Holloway's terms are "
       "seen from the midpoint of the cameras. Definitions: docs/math/stereo.md#triangulated-error.</p>\n";
  s += StatsTable("every measured point", StereoRows(JsonPointer({reproj_key::kStereo, reproj_key::kOverall}), unit, r.overall));
  s += "<p>Excluded: " + std::to_string(r.n_left_only) + " seen by the left camera only, " +
       std::to_string(r.n_right_only) + " by the right only, " + std::to_string(r.n_no_pose) + " without a left pose, " +
       std::to_string(r.n_no_ray) + " without a ray, " + std::to_string(r.n_behind) + " behind; views seen by one camera: " +
       std::to_string(r.left_only_views.size()) + " left, " + std::to_string(r.right_only_views.size()) + " right.</p>\n";
  const std::string chart = StereoDepthScript(r);
  if (!chart.empty()) {
    s += Chart(chart, "triangulated error per axis against depth",
                     "|dx|, |dy|, |dz| of every measured point against its depth (seed 000 Figs. 9–10)");
  }
  for (const auto& [eye, cells] : {std::pair{"left", &r.left_grid}, std::pair{"right", &r.right_grid}}) {
    const bool left = eye == std::string("left");
    std::vector<std::optional<double>> means;
    for (const auto& cell : cells->error_px) means.push_back(cell ? std::optional<double>(cell->mean) : std::nullopt);
    s += Chart(HeatMapScript(cells->grid, means, "mean |reprojection error| (px)"), std::string("heat map ") + eye,
                     std::string("The ") + eye + " camera: mean reprojection error per image cell (" +
                         std::to_string(cells->grid.cols) + "×" + std::to_string(cells->grid.rows) +
                         "; blank: no point), " + (left ? "against its own PnP pose." : "through the rig's relative pose."));
    s += OverlayFigure(r, left, left ? left_dir : right_dir);
  }
  if (!r.test_points.empty()) s += TestPointSection(r, unit);
  s += PerViewTable(r, unit);
  return s + kPageEnd;
}

}  // namespace vstcal
