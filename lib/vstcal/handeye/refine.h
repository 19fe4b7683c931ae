// Maximum-likelihood hand-eye calibration with the time offset between the two clocks (issue 22;
// docs/math/handeye.md#refinement): over the board corners' reprojection, with the tracker's
// poses interpolated on SE(3) at each image's time plus the offset,
//
//   minimise over X = hmd_from_camera, Z = tracker_from_board, δ
//     Σ_views Σ_corners |project(camera_from_board_i · P) − u|²,
//     camera_from_board_i = X⁻¹ · H(t_i + δ)⁻¹ · Z,
//
// H(τ) the tracker's pose at its own clock's time τ; a view taken at camera time t_i is the
// tracker's t_i + δ. The camera's intrinsics are fixed (calibrated before). The start comes from
// the closed form (closed_form.h) on each view's PnP pose at the best δ of a coarse search.
#pragma once

#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/camera/camera.h"
#include "vstcal/estimators/view_rejection.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/handeye/closed_form.h"
#include "vstcal/handeye/covariance_names.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal {

// One report of the tracker: its clock's time (s) and the body's pose.
struct TrackedPose {
  double time = 0;
  Rigid3d tracker_from_hmd;
};

// One image of the board: the camera clock's time (s) and its corners (board point → pixel).
struct TimedView {
  std::string name;
  double time = 0;
  std::vector<Observation> observations;
};

// The pose at tracker time τ between the reports around it: rotation along the geodesic
// (R_k Exp(s log(R_kᵀ R_k+1))), translation linearly, s = (τ − t_k)/(t_k+1 − t_k). Templated so that
// δ's derivative flows through s. nullopt outside [first, last] report.
// log_steps[k] = log(R_kᵀ R_k+1), one per interval (LogSteps).
std::vector<Eigen::Vector3d> LogSteps(std::span<const TrackedPose> log);

// A quadratic in time fitted by least squares, per component, to the reports log[first, first +
// count): rows (1, t, t²) with t = time − t0, six columns — the rotation as log(R_m R_atᵀ), the
// translation. The tracker's noise's smoothing (SmoothedVelocity takes its slope) and the
// bootstrap's motion (its value) both fit it.
Eigen::MatrixXd FitReportsQuadratic(std::span<const TrackedPose> log, size_t first, size_t count, const Rigid3d& at, double t0);

namespace detail {
inline double ScalarPart(double x) { return x; }
template <typename J>
double ScalarPart(const J& jet) {
  return jet.a;
}
}  // namespace detail

template <typename T>
std::optional<Rigid3<T>> InterpolatePose(std::span<const TrackedPose> log, std::span<const Eigen::Vector3d> log_steps, const T& tau) {
  const double time = detail::ScalarPart(tau);
  if (log.size() < 2 || !(time >= log.front().time && time <= log.back().time)) return std::nullopt;
  // The interval [t_k, t_k+1] holding τ (the last one for τ = t_last).
  size_t k = static_cast<size_t>(std::upper_bound(log.begin(), log.end(), time, [](double t, const TrackedPose& p) { return t < p.time; }) -
                                 log.begin());
  k = std::min(k, log.size() - 1) - 1;
  const T s = (tau - T(log[k].time)) / T(log[k + 1].time - log[k].time);
  const Mat3<T> Rk = log[k].tracker_from_hmd.R.template cast<T>();
  const Vec3<T> step = log_steps[k].template cast<T>() * s;
  Rigid3<T> out;
  out.R = Rk * RotationFromRotvec(step);
  out.t = log[k].tracker_from_hmd.t.template cast<T>() * (T(1) - s) + log[k + 1].tracker_from_hmd.t.template cast<T>() * s;
  return out;
}

// A second camera rigidly beside the first, as a stereo rig holds it (stereo@1's right_from_left,
// held: docs/math/handeye.md#rig): its own views of the board, each at its own time. A corner it
// sees is projected through right_from_left · X⁻¹ · H(t + δ)⁻¹ · Z, so its views constrain the
// same X, Z and δ as the first camera's; X stays the first (left) camera's hmd_from_camera.
struct HandEyeRig {
  Camera right;
  Rigid3d right_from_left;
  std::vector<TimedView> views;
};

struct HandEyeOptions {
  double max_time_offset = 0.2;  // s: the coarse search for δ's start spans ±this
  double search_step = 0.005;    // s
  int max_iterations = 100;
  // Bad frames: after each solve a view inconsistent with the others' noise is dropped and the rest
  // solved again (docs/math/handeye.md#bad-frames); on by default, views only (a frame's corners
  // share its one tracker pose, so a bad pose spoils the frame, not a corner).
  ViewRejectionOptions rejection{.enabled = true};
  // ... and only when its RMS is at least this many times the median view's. Significance alone
  // is not enough: with corners good to 0.01 px, what is left is the interpolation between the
  // tracker's reports, larger where the headset moved faster, and every view would in turn look
  // inconsistent. A bad frame is off by pixels, not by a few hundredths.
  double min_rms_ratio = 2;
  // The tracker's noise (docs/math/handeye.md#tracker-noise): each report is the true pose with
  // R = Exp(ω) R_true, t = t_true + ρ, ω ~ N(0, σ_r² I₃), ρ ~ N(0, σ_t² I₃), independent from
  // report to report. true: σ_r, σ_t (and the corners' σ) are estimated jointly by restricted
  // maximum likelihood and every frame weighed by them, after the bad-frame test; false: the
  // tracker's poses are taken as exact (their noise then only inflates σ̂).
  bool estimate_tracker_noise = true;
  // With the tracker's noise: δ's estimating equation with the smoothed velocity as its slope
  // (docs/math/handeye.md#delta-instrumented) rather than the two reports' around each view. false:
  // δ minimises the cost with the weight following it, as up to stop 39 (1.4 … 1.8 × δ's scatter;
  // kept to reproduce the docs' tables).
  bool instrumented_offset = true;
};

// A σ estimated from the data, with its standard error and 95 % interval (same unit).
struct EstimatedSigma {
  double sigma = 0, sigma_sigma = 0, lower = 0, upper = 0;
};

// The tracker's noise as the joint solve estimated it (HandEyeOptions::estimate_tracker_noise).
struct JointTrackerNoise {
  EstimatedSigma rotation;     // rad, per axis (the left perturbation ω of each report)
  EstimatedSigma translation;  // length unit, per axis
  EstimatedSigma corner_px;    // the corners' σ, px per coordinate
  size_t frames = 0;           // instants (a rig's two views of one instant are one frame)
  int rounds = 0;              // re-weighted solves
};

// X's 6, Z's 6 and δ.
inline constexpr size_t kHandEyeParameters = 13;

// Where the kept views fall between the tracker's reports at the solved δ (report_phases.h,
// docs/math/handeye.md#report-phases): s in [0, 1) of each instant's report interval.
struct ReportPhases {
  double concentration = 0;  // |mean of exp(2πi s)|: 1 when every view sits at one place, ~1/√n when spread
  double mean = 0;           // the circular mean of s, in [0, 1): where they sit when concentrated
  size_t instants = 0;       // the views' distinct times (a rig's pair is one)
  bool Locked() const;       // concentration ≥ kLockedReportPhase
};

struct HandEyeSolution {
  Rigid3d hmd_from_camera, tracker_from_board;
  double time_offset = 0;  // δ, s: the tracker's clock reads t + δ at the camera's t
  // Covariance of (X's left-perturbation tangent ω, ρ; Z's ω, ρ; δ), 13 × 13, σ̂²(JᵀJ)⁻¹ with σ̂ from
  // the residuals; `names` gives the order.
  Eigen::MatrixXd covariance;
  std::vector<std::string> names;
  double sigma_px = 0;  // σ̂ = √(Σ r² / (2N − 13))
  double rms_px = 0;
  size_t views = 0, corners = 0;
  int iterations = 0;
  HandEyeStart start;  // the closed form the refinement started from
  double start_time_offset = 0;
  std::vector<Rejection> rejected;    // views dropped as bad frames, in the order dropped
  std::vector<std::string> warnings;  // e.g. an inconsistent view kept because too few remain
  // With a rig: right_from_left as held, and how many of `views` and `corners` are the right
  // camera's (those two counts are both cameras'). Rejections index the left views, then the right.
  std::optional<Rigid3d> right_from_left;
  size_t right_views = 0, right_corners = 0;
  // With estimate_tracker_noise: the noise's σ's. X and Z then minimise Σ_f r_fᵀ C_f⁻¹ r_f,
  // C_f = c I + w(s_f) K_f (each frame's corners with the tracker's error at its instant profiled
  // out), and δ solves the instrumented equation Σ_f ν̄_fᵀJₑᵀC_f⁻¹r_f = 0 with ν̄ the smoothed
  // velocity (docs/math/handeye.md#delta-instrumented); their covariance is Ī⁻¹, Ī the information
  // with δ's column the smoothed velocity's, not σ̂²(JᵀJ)⁻¹. (HandEyeOptions::instrumented_offset
  // false: δ minimises the cost with w following it, and the covariance is that cost's sandwich
  // Ī⁻¹ + N (Ī⁻¹e_δ)(Ī⁻¹e_δ)ᵀ, docs/math/handeye.md#delta-likelihood.)
  // `covariance` and `names` then end with
  // tracker_noise.rotation (rad) and tracker_noise.translation (length unit), the σ's themselves,
  // uncorrelated with X, Z and δ to first order (a Gaussian's mean and variance parameters are
  // orthogonal in its information). sigma_px stays the residuals' σ̂ (the fit); the corners' σ
  // estimated beside the tracker's is tracker_noise->corner_px.
  std::optional<JointTrackerNoise> tracker_noise;
  // With the tracker's noise: N Ī⁻¹_δδ, what the noisy slope between two reports adds to δ's
  // first-order variance over the true velocity's information alone when δ minimises the cost (its
  // variance is then Ī⁻¹_δδ (1 + this)); about 6σ²/(wΔt²|ν|²), the slope's noise over the velocity
  // squared. The instrumented δ's variance is Ī⁻¹_δδ: this is what it saves. 0 without.
  double slope_excess = 0;
  ReportPhases report_phases;
};

// `iterations` counts every solve's (one per rejection round). Throws InputError for a log that is
// not strictly increasing in time or has fewer than 2 reports, a view outside the log's span, and
// DegenerateError (closed_form.h) for too few views or motion about one axis. `views` are the
// (left) camera's; with `rig` its right camera's views join the solve (the start is the left
// camera's alone: its PnP poses and the closed form).
HandEyeSolution SolveHandEye(const Camera& camera, std::span<const TrackedPose> log, std::span<const TimedView> views,
                             const HandEyeOptions& options = {}, const HandEyeRig* rig = nullptr);

}  // namespace vstcal
