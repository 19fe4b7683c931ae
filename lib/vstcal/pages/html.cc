#include "vstcal/pages/html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "vstcal/formats/report/report_keys.h"
#include "vstcal/json/json_pointer.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/pages/charts.h"
#include "vstcal/pages/html_page.h"
#include "vstcal/pages/overlay.h"
#include "vstcal/pages/view_residuals.h"

namespace vstcal {
namespace {

constexpr size_t kMaxPictureCameras = 4;  // overlays and heat maps of the first cameras only


// A cell in significant digits: parameters span 1e-6 (p1) to 1e3 (fx).
std::string SignificantCell(const std::string& key, double v, int digits) {
  char shown[64];
  std::snprintf(shown, sizeof shown, "%.*g", digits, v);
  return "<td data-key=\"" + Escape(key) + "\" data-value=\"" + ShortestDecimal(v) + "\">" + shown + "</td>";
}

// Each lens parameter with its 1σ and 3σ interval from the camera file's covariance (Bouguet's
// and mrcal's listing), or "—" where the file gives no σ.
std::string ParametersTable(const CameraReport& c, const std::string& key) {
  std::string rows;
  for (size_t i = 0; i < c.parameters.size(); ++i) {
    const ParameterEstimate& p = c.parameters[i];
    const std::string pk = key + JsonPointer({reproj_key::kParameters, std::to_string(i)});
    rows += "<tr><th>" + Escape(p.name) + "</th>" + SignificantCell(pk + JsonPointer({reproj_key::kValue}), p.value, 9);
    if (p.sigma) {
      char interval[96];
      std::snprintf(interval, sizeof interval, "[%.8g, %.8g]", p.value - 3 * *p.sigma, p.value + 3 * *p.sigma);
      rows += SignificantCell(pk + JsonPointer({reproj_key::kSigma}), *p.sigma, 4) + "<td>" + interval + "</td>";
    } else {
      rows += "<td>—</td><td>—</td>";
    }
    rows += "</tr>\n";
  }
  return "<table><caption>lens parameters (1-sigma from the camera's covariance)</caption><tr><th></th><th>estimate</th>"
         "<th>1-sigma</th><th>3-sigma interval</th></tr>\n" + rows + "</table>\n";
}

std::string CameraSection(const ReprojReport& r, size_t k) {
  const CameraReport& c = r.cameras[k];
  const std::string key = JsonPointer({reproj_key::kCameras, std::to_string(k)});
  const std::string unit(LengthUnitName(r.correspondences.length_unit));
  std::string s = "<section><h2>Camera " + std::to_string(k) + ": " + Escape(c.file) +
                  (c.method.empty() ? "" : " (" + Escape(c.method) + ")") + "</h2>\n";
  s += StatsTable("calibration points", StatsRow("|residual| px", key + JsonPointer({reproj_key::kOverall, reproj_key::kErrorPx}), c.overall.error_px) +
                                            StatsRow("lateral " + unit, key + JsonPointer({reproj_key::kOverall, reproj_key::kLateral}), c.overall.lateral) +
                                            StatsRow("angular deg", key + JsonPointer({reproj_key::kOverall, reproj_key::kAngularDeg}), c.overall.angular_deg) +
                                            StatsRow("normalized z", key + JsonPointer({reproj_key::kNormalized, reproj_key::kCalibrationPoints}), c.normalized));
  s += "<p>Normalized residuals: ";
  if (c.chi2_per_dof) {
    s += "chi² per degree of freedom <span data-key=\"" + key + JsonPointer({reproj_key::kNormalized, reproj_key::kChi2PerDof}) + "\" data-value=\"" +
         ShortestDecimal(*c.chi2_per_dof) + "\">" + [&] {
           char b[32];
           std::snprintf(b, sizeof b, "%.3f", *c.chi2_per_dof);
           return std::string(b);
         }() + "</span> (1 = as large as the camera's covariance says).";
  } else {
    s += Escape(c.normalization) + ".";
  }
  s += " Excluded: <span data-key=\"" + key + JsonPointer({reproj_key::kExcluded, reproj_key::kBehindCamera}) + "\" data-value=\"" + std::to_string(c.n_behind_camera) +
       "\">" + std::to_string(c.n_behind_camera) + "</span> behind the camera, " + std::to_string(c.n_no_pose) +
       " without a pose, " + std::to_string(c.n_no_ray) + " without a ray.</p>\n";
  s += ParametersTable(c, key);
  // Worst first: the view a user should look at (or drop) heads the table.
  std::string views;
  for (const size_t v : WorstViewsFirst(c)) {
    views += StatsRow(c.views[v].name, key + JsonPointer({reproj_key::kViews, std::to_string(v), reproj_key::kErrorPx}), c.views[v].error_px);
  }
  s += StatsTable("|residual| px per view, the largest RMS first", views);
  if (!c.test_points.empty()) {
    s += StatsTable("test points, |residual| px and lateral " + unit,
                    StatsRow("inside, px", key + JsonPointer({reproj_key::kTestPoints, reproj_key::kInside, reproj_key::kErrorPx}), c.test_inside.error_px) +
                        StatsRow("outside, px", key + JsonPointer({reproj_key::kTestPoints, reproj_key::kOutside, reproj_key::kErrorPx}), c.test_outside.error_px) +
                        StatsRow("inside, " + unit, key + JsonPointer({reproj_key::kTestPoints, reproj_key::kInside, reproj_key::kLateral}), c.test_inside.lateral) +
                        StatsRow("outside, " + unit, key + JsonPointer({reproj_key::kTestPoints, reproj_key::kOutside, reproj_key::kLateral}), c.test_outside.lateral));
    std::string rows;
    for (size_t i = 0; i < c.test_points.size(); ++i) {
      const TestPointReport& t = c.test_points[i];
      const std::string tk = key + JsonPointer({reproj_key::kTestPoints, reproj_key::kPoints, std::to_string(i)});
      rows += "<tr><th>" + Escape(t.name) + "</th><td>" +
              (!t.inside_volume ? "—" : *t.inside_volume ? "inside" : "outside") + "</td>";
      rows += t.error.excluded == Exclusion::kNone
                  ? Cell(tk + JsonPointer({reproj_key::kErrorPx}), t.error.error_px) +
                        Cell(tk + JsonPointer({reproj_key::kLateral}), t.error.lateral) +
                        Cell(tk + JsonPointer({reproj_key::kAngularDeg}), t.error.angular_deg())
                  : "<td colspan=\"3\">" + std::string(ExclusionName(t.error.excluded)) + "</td>";
      rows += "</tr>\n";
    }
    s += "<table><caption>each test point</caption><tr><th></th><th>volume</th><th>|residual| px</th><th>lateral " + unit +
         "</th><th>angular deg</th></tr>\n" + rows + "</table>\n";
  }
  return s + "</section>\n";
}

}  // namespace

std::string ReprojReportHtml(const ReprojReport& r, const std::filesystem::path& dir) {
  const Correspondences& c = r.correspondences;
  std::string s = PageStart("reproj-report: " + r.correspondences_file);
  s += "<h1>Reprojection report: " + Escape(r.correspondences_file) + "</h1>\n";
  s += "<p>" + std::to_string(NumObservations(c)) + " points in " + std::to_string(c.views.size()) + " views (" +
       (c.rig == Rig::kVolume ? "volume" : "planar views") + "), " + std::to_string(c.test_points.size()) +
       " test points, image " + std::to_string(c.image_size.width) + "×" + std::to_string(c.image_size.height) +
       " px, lengths in " + std::string(LengthUnitName(c.length_unit)) + ". Measured volume: " + Escape(r.volume.status) +
       ". Definitions: docs/math/report-statistics.md.</p>\n";
  if (!r.differences.empty()) {
    std::string rows;
    for (size_t m = 0; m < r.differences.size(); ++m) {
      const CameraDifference& d = r.differences[m];
      rows += StatsRow("camera " + std::to_string(d.camera) + " vs " + std::to_string(d.reference) +
                           ": prediction shift px",
                       JsonPointer({reproj_key::kDifferences, std::to_string(m), reproj_key::kPredictionShiftPx}), d.prediction_shift_px);
    }
    s += "<section><h2>Cameras side by side</h2>\n" + StatsTable("how far the cameras' predictions lie apart", rows) +
         "</section>\n";
  }
  s += "<section><h2>Charts</h2>\n";
  s += Chart(HistogramScript(r), "histogram of residuals", "Histogram of |residual| over the calibration points, every camera.");
  s += Chart(PerViewScript(r), "per-view RMS", "RMS |residual| per view.");
  s += Chart(DepthScript(r), "error against depth",
             "|residual| and lateral error at each point's distance from the camera (at most 20000 points a camera).");
  if (const std::string script = TestPointsScript(r); !script.empty()) {
    s += Chart(script, "test points inside and outside the volume", "Test points inside vs outside the calibration points' convex hull.");
  }
  for (size_t k = 0; k < std::min(r.cameras.size(), kMaxPictureCameras); ++k) {
    const CameraReport& cam = r.cameras[k];
    std::vector<std::optional<double>> means;
    for (const auto& cell : cam.grid) means.push_back(cell ? std::optional<double>(cell->mean) : std::nullopt);
    s += Chart(HeatMapScript(r.grid, means, "mean |residual| (px)"), "heat map camera " + std::to_string(k),
               "Camera " + std::to_string(k) + ": mean |residual| per image cell (" + std::to_string(r.grid.cols) + "×" +
                   std::to_string(r.grid.rows) + "; blank: no point).");
    if (!cam.uncertainty_px.empty()) {
      char depth[32];
      std::snprintf(depth, sizeof depth, "%.6g", cam.uncertainty_depth);
      s += Chart(HeatMapScript(r.grid, cam.uncertainty_px, "1-sigma projection uncertainty (px)"),
                 "projection uncertainty camera " + std::to_string(k),
                 "Camera " + std::to_string(k) + ": projection uncertainty from its covariance, the major semi-axis of the " +
                     "1-sigma ellipse at each cell's centre and depth " + depth + " " +
                     std::string(LengthUnitName(r.correspondences.length_unit)) +
                     " (the points' median), tied to the calibration object (as mrcal's show-projection-uncertainty).");
    }
    const OverlayPicture overlay = DrawResidualOverlay(r, k, dir);
    s += Figure("image/png", Base64(overlay.png.data(), overlay.png.size()), "residual vectors camera " + std::to_string(k),
                "Camera " + std::to_string(k) + ": residual vectors, " + overlay.caption + ".");
    s += ViewResidualPlots(r, k);
  }
  s += "</section>\n";
  for (size_t k = 0; k < r.cameras.size(); ++k) s += CameraSection(r, k);
  return s + kPageEnd;
}

}  // namespace vstcal
