// Where a recording's views fall between the tracker's reports, at the solved time offset
// (docs/math/handeye.md#report-phases). A camera locked to the tracker's clock puts every view at one
// place s of the report interval; a camera on its own clock spreads them. The time offset's cost
// once depended on it (σ_δ 8 % high on the reports to 20 % low midway); the instrumented δ does not
// (docs/math/handeye.md#delta-instrumented), and the phases are reported for the record.
#pragma once

#include <cstddef>
#include <span>

#include "vstcal/handeye/refine.h"

namespace vstcal {

// At or above this concentration the views count as locked to the tracker's reports; 16 views at
// random places reach it in 2 % of recordings (Rayleigh: P(R ≥ r) ≈ exp(−n r²)).
inline constexpr double kLockedReportPhase = 0.5;

// The report interval [t_k, t_k+1] holding tracker time τ (InterpolatePose's; the first or last
// for τ outside the log), as k. `log` has at least 2 reports.
size_t ReportInterval(std::span<const TrackedPose> log, double tau);

// The interpolation's s ∈ [0, 1] at tracker time τ between the reports around it (clamped outside
// the log): the place a view's tracker time has between two reports.
double InterpolationFraction(std::span<const TrackedPose> log, double tau);

// w(s) = (1 − s)² + s²: the variance of the pose interpolated at fraction s between two reports
// over one report's (1 at a report, ½ midway; docs/math/handeye.md#delta-likelihood). T may be a
// Jet, so that δ's derivative flows through s.
template <typename T>
T InterpolationWeight(const T& s) {
  return (T(1) - s) * (T(1) - s) + s * s;
}

// s = (t + δ − t_k) / (t_{k+1} − t_k) for each time t, in the report interval [t_k, t_{k+1}) holding
// t + δ; times within 1 µs of each other count once, times outside the log not at all. `log` is
// strictly increasing in time (SolveHandEye's check).
ReportPhases ViewReportPhases(std::span<const TrackedPose> log, std::span<const double> times, double time_offset);

}  // namespace vstcal
