// The keys of vstcal/reproj-report@1 (docs/formats.md#reproj-report) that are read outside its
// writer (report_format.cc): the pages (pages/html.cc, stereo_html.cc, html_page.cc) give each
// table cell the JSON pointer of the value it shows (`data-key`, which the Chromium tests follow
// into the file), built from these.
#pragma once

namespace vstcal::reproj_key {

// A statistics object {n, mean, rms, median, p95, max}.
inline constexpr char kN[] = "n";
inline constexpr char kMean[] = "mean";
inline constexpr char kRms[] = "rms";
inline constexpr char kMedian[] = "median";
inline constexpr char kP95[] = "p95";
inline constexpr char kMax[] = "max";

// One camera's report: cameras[k] {parameters [{value, sigma}], overall, normalized
// {calibration_points, chi2_per_dof}, excluded {behind_camera}, views [{error_px}], test_points
// {inside, outside, points [{error_px, lateral, angular_deg}]}}; a measure's statistics {error_px,
// lateral, angular_deg}; differences [{prediction_shift_px}].
inline constexpr char kCameras[] = "cameras";
inline constexpr char kParameters[] = "parameters";
inline constexpr char kValue[] = "value";
inline constexpr char kSigma[] = "sigma";
inline constexpr char kOverall[] = "overall";
inline constexpr char kNormalized[] = "normalized";
inline constexpr char kCalibrationPoints[] = "calibration_points";
inline constexpr char kChi2PerDof[] = "chi2_per_dof";
inline constexpr char kExcluded[] = "excluded";
inline constexpr char kBehindCamera[] = "behind_camera";
inline constexpr char kViews[] = "views";
inline constexpr char kTestPoints[] = "test_points";
inline constexpr char kInside[] = "inside";
inline constexpr char kOutside[] = "outside";
inline constexpr char kPoints[] = "points";
inline constexpr char kErrorPx[] = "error_px";
inline constexpr char kLateral[] = "lateral";
inline constexpr char kAngularDeg[] = "angular_deg";
inline constexpr char kDifferences[] = "differences";
inline constexpr char kPredictionShiftPx[] = "prediction_shift_px";

// A stereo rig's report: stereo {overall, views [{stats, reprojection {left, right}}], test_points
// {inside, outside, points [{error: [dx, dy, dz, linear, …]}]}}; its statistics {x, y, z, linear,
// lateral, depth, angular_deg}.
inline constexpr char kStereo[] = "stereo";
inline constexpr char kStats[] = "stats";
inline constexpr char kReprojection[] = "reprojection";
inline constexpr char kLeft[] = "left";
inline constexpr char kRight[] = "right";
inline constexpr char kError[] = "error";
inline constexpr char kX[] = "x";
inline constexpr char kY[] = "y";
inline constexpr char kZ[] = "z";
inline constexpr char kLinear[] = "linear";
inline constexpr char kDepth[] = "depth";

}  // namespace vstcal::reproj_key
