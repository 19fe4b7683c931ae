#include "vstcal/app/calib_compare.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <vector>

#include "vstcal/calib/compare.h"
#include "vstcal/core/check.h"
#include "vstcal/core/error.h"
#include "vstcal/files/junit_xml.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/scene/measured_volume.h"
#include "vstcal/core/option_name.h"

namespace vstcal::app {
namespace {

[[gnu::format(printf, 2, 3)]] void Append(std::string* out, const char* format, ...) {
  va_list args;
  va_start(args, format);
  char buf[512];
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  *out += buf;
}

void CheckThreshold(const std::optional<double>& value, const char* flag, const char* unit) {
  if (value && !(std::isfinite(*value) && *value > 0)) {
    throw InputError(std::string(flag) + ": " + MessageNumber(*value) + " is not a positive number; give a bound > 0 in " +
                     unit);
  }
}

void RequireCovariance(const CalibratedCamera& camera, const std::string& file, const char* flag) {
  if (!camera.covariance || camera.covariance->empty()) {
    throw InputError(file + ": covariance: none; " + flag + " needs both cameras' covariances (write them with "
                            "calib-dlt " VSTCAL_OPT("refine") " or calib-tsai), or bound the pixels with " VSTCAL_OPT("max_px"));
  }
}

// The regions' table and the verdict, and the check it makes.
CheckResult AppendCrossValidation(std::string* s, const CrossValidation& v) {
  Append(s, "cross-validation, intrinsics only, %d×%d regions (m² is χ²₂ when both calibrations are right; p = exp(−m²/2)):\n", v.cols,
         v.rows);
  Append(s, "%-8s %-18s %10s %8s %8s\n", "region", "pixel", "|Δ| px", "m σ", "p");
  for (const RegionAgreement& r : v.regions) {
    char where[32], pixel[40];
    std::snprintf(where, sizeof where, "%d,%d", r.col + 1, r.row + 1);
    std::snprintf(pixel, sizeof pixel, "(%.1f, %.1f)", r.pixel.x(), r.pixel.y());
    if (r.p_value) {
      Append(s, "%-8s %-18s %10.4f %8.2f %8.2g\n", where, pixel, *r.distance_px, *r.sigma, *r.p_value);
    } else {
      Append(s, "%-8s %-18s %10s\n", where, pixel, r.distance_px ? "(no σ)" : "(no ray)");
    }
  }
  CheckResult check{"cross-validation", v.agree ? CheckVerdict::kPass : CheckVerdict::kFail, ""};
  if (!v.p_value) {
    check.verdict = CheckVerdict::kFail;
    check.message = "no region has a defined uncertainty";
    return check;
  }
  char text[200];
  std::snprintf(text, sizeof text, "all %zu regions jointly: χ² %.3g with %d degrees of freedom, p %.2g %s %.2g", v.tested, v.chi2, v.dof,
                *v.p_value, v.agree ? "≥" : "<", v.alpha);
  check.message = std::string(v.agree ? "one camera within their uncertainty: "
                                      : "they disagree beyond their uncertainty (a lens model that does not fit, a camera that "
                                        "changed, or σ's that are too small): ") + text;
  return check;
}

CheckResult Bound(std::string name, std::optional<double> value, double limit, const char* unit, const std::string& what) {
  CheckResult r{std::move(name), CheckVerdict::kPass, ""};
  if (!value) {
    r.verdict = CheckVerdict::kFail;
    r.message = what + ": undefined, limit " + MessageNumber(limit) + " " + unit;
    return r;
  }
  r.verdict = *value > limit ? CheckVerdict::kFail : CheckVerdict::kPass;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4f", *value);
  r.message = what + ": " + buf + " " + unit + (*value > limit ? " > " : " ≤ ") + "limit " + MessageNumber(limit) + " " + unit;
  return r;
}

std::vector<CheckResult> Checks(const CompareRequest& request, const CameraComparison& c,
                                const std::optional<std::vector<PointDisagreement>>& at_points) {
  std::vector<CheckResult> checks;
  const std::string grid = "max over " + std::to_string(c.n_points) + " grid points";
  if (request.max_px) {
    checks.push_back(Bound("grid px", c.max_px, *request.max_px, "px", grid));
    for (const PointDisagreement& d : at_points ? *at_points : std::vector<PointDisagreement>{}) {
      checks.push_back(Bound("test point " + d.name + " px", d.pixel_distance, *request.max_px, "px",
                             d.pixel_distance ? "disagreement" : "disagreement (behind a camera)"));
    }
  }
  if (request.max_sigma) {
    char where[96];
    std::snprintf(where, sizeof where, " (at pixel %.1f, %.1f)", c.max_sigma_pixel.x(), c.max_sigma_pixel.y());
    CheckResult r = Bound("grid sigma", c.max_sigma, *request.max_sigma, "σ", grid);
    if (c.max_sigma) r.message += where;
    checks.push_back(std::move(r));
    for (const PointDisagreement& d : at_points ? *at_points : std::vector<PointDisagreement>{}) {
      checks.push_back(Bound("test point " + d.name + " sigma", d.sigma, *request.max_sigma, "σ", "disagreement"));
    }
  }
  return checks;
}

}  // namespace

Outcome Compare(const CompareRequest& request) {
  CheckThreshold(request.max_px, VSTCAL_OPT("max_px"), "px");
  CheckThreshold(request.max_sigma, VSTCAL_OPT("max_sigma"), "σ (e.g. 3)");
  if (!request.junit.empty() && !request.max_px && !request.max_sigma && !request.cross_validate) {
    throw InputError(VSTCAL_OPT("junit") ": no check to report; give " VSTCAL_OPT("max_px") ", " VSTCAL_OPT("max_sigma") " or " VSTCAL_OPT("cross_validate") " too");
  }
  const CalibratedCamera a = ReadCamera(request.reference), b = ReadCamera(request.other);
  for (const auto& [flag, wanted] : {std::pair{VSTCAL_OPT("max_sigma"), request.max_sigma.has_value()}, {VSTCAL_OPT("cross_validate"), request.cross_validate}}) {
    if (!wanted) continue;
    RequireCovariance(a, request.reference, flag);
    RequireCovariance(b, request.other, flag);
  }
  const CameraComparison c = [&] {
    try {
      return CompareCameras(a, b, request.depth);
    } catch (const InputError& e) {
      throw InputError(request.other + " vs " + request.reference + ": " + e.what());  // name the files
    }
  }();
  // Every input is read and checked before anything is printed: a refused --test-points file
  // leaves no half comparison on stdout.
  std::optional<std::vector<PointDisagreement>> at_points;
  if (!request.test_points.empty()) {
    const Correspondences corners = ReadCorrespondences(request.test_points);
    if (corners.test_points.empty()) {
      throw InputError(request.test_points + ": test_points: none; give a file with test points");
    }
    try {
      at_points = CompareAtTestPoints(a, b, corners);
    } catch (const InputError& e) {
      throw InputError(request.other + " vs " + request.reference + ": " + e.what());
    }
  }
  Outcome out;
  std::string& s = out.stdout_text;
  const Eigen::Matrix3d Ka = a.camera.K(), Kb = b.camera.K();
  const char* names[5] = {"fx", "fy", "cx", "cy", "skew"};
  const int rows[5] = {0, 1, 0, 1, 0}, cols[5] = {0, 1, 2, 2, 1};
  Append(&s, "%-6s %16s %16s %12s\n", "", "reference", "other", "difference");
  for (int i = 0; i < 5; ++i) {
    Append(&s, "%-6s %16.6f %16.6f %12.6f\n", names[i], Ka(rows[i], cols[i]), Kb(rows[i], cols[i]),
           c.K_difference(rows[i], cols[i]));
  }
  const std::string unit(LengthUnitName(a.length_unit));
  if (c.rotation_deg) Append(&s, "rotation difference      %.6f deg\n", *c.rotation_deg);
  if (c.centre_distance) Append(&s, "camera centre distance   %.6f %s\n", *c.centre_distance, unit.c_str());
  Append(&s, "pixel disagreement at depth %.1f %s: RMS %.4f px, max %.4f px over %zu grid points\n", c.depth,
         unit.c_str(), c.rms_px, c.max_px, c.n_points);
  if (at_points) {
    Append(&s, "%-14s %-8s %s\n", "test point", "volume", "disagreement px");
    for (const PointDisagreement& d : *at_points) {
      const char* where = VolumeSideName(d.inside_volume);
      if (d.pixel_distance) {
        Append(&s, "%-14s %-8s %.4f\n", d.name.c_str(), where, *d.pixel_distance);
      } else {
        Append(&s, "%-14s %-8s (behind a camera)\n", d.name.c_str(), where);
      }
    }
  }
  std::vector<CheckResult> checks = Checks(request, c, at_points);
  if (request.cross_validate) checks.push_back(AppendCrossValidation(&s, CrossValidate(a, b)));
  size_t failed = 0;
  for (const CheckResult& r : checks) {
    s += "check " + r.name + ": " + std::string(CheckVerdictName(r.verdict)) + ": " + r.message + "\n";
    failed += r.verdict == CheckVerdict::kFail;
  }
  if (!checks.empty()) {
    s += "checks: " + std::to_string(checks.size()) + ", failed " + std::to_string(failed) +
         (failed ? " (exit code 4)\n" : "\n");
  }
  out.check_failed = failed > 0;
  if (!request.junit.empty()) out.files.emplace_back(request.junit, JUnitXml("calib-compare", checks));
  return out;
}

}  // namespace vstcal::app
