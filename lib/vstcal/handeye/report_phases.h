// Where a recording's views fall between the tracker's reports, at the solved time offset
// (docs/math/handeye.md#report-phases). The time offset's σ depends on it: a camera locked to the
// tracker's clock puts every view at one place s of the report interval, where the first-order σ_δ
// is 8 % high (s = 0, on the reports) to 20 % low (s = ½) with 16 views; a camera on its own clock
// spreads them, and the first-order σ_δ is then within 4 % (0.02° … 0.05° a report; 13 % too large at 0.1°).
#pragma once

#include <cstddef>
#include <span>

#include "vstcal/handeye/refine.h"

namespace vstcal {

// At or above this concentration the views count as locked to the tracker's reports; 16 views at
// random places reach it in 2 % of recordings (Rayleigh: P(R ≥ r) ≈ exp(−n r²)).
inline constexpr double kLockedReportPhase = 0.5;
// Locked views this close to the middle of the interval, s in (0.3, 0.7), are where σ_δ was found
// too small — but not everywhere there: with 16 locked views at s = ½ (docs/math/handeye.md#report-phases)
// the first-order σ and the bootstrap's were within 10 % when the first-order σ spanned 0.05 or 0.48
// of a report interval, and up to 22 % too small when it spanned 0.15 or 0.29: the weight w(s(δ)),
// smallest midway, flattens the cost within half an interval of δ̂ and δ̂'s tails grow
// (docs/math/handeye.md#delta-shape). SolveHandEye warns inside that measured span, kDoubtfulSpan.
inline constexpr double kMidwayBand = 0.2;
inline constexpr double kDoubtfulSpan[2] = {0.1, 0.4};

// Locked near the middle, with the first-order σ_δ spanning kDoubtfulSpan of the mean report
// interval: where σ_δ may be up to ~20 % too small, by the first order and the bootstrap alike.
bool OffsetSigmaInDoubt(const ReportPhases& phases, double sigma_over_interval);

// The report interval [t_k, t_k+1] holding tracker time τ (InterpolatePose's; the first or last
// for τ outside the log), as k. `log` has at least 2 reports.
size_t ReportInterval(std::span<const TrackedPose> log, double tau);

// The interpolation's s ∈ [0, 1] at tracker time τ between the reports around it (clamped outside
// the log): the place a view's tracker time has between two reports.
double InterpolationFraction(std::span<const TrackedPose> log, double tau);

// s = (t + δ − t_k) / (t_{k+1} − t_k) for each time t, in the report interval [t_k, t_{k+1}) holding
// t + δ; times within 1 µs of each other count once, times outside the log not at all. `log` is
// strictly increasing in time (SolveHandEye's check).
ReportPhases ViewReportPhases(std::span<const TrackedPose> log, std::span<const double> times, double time_offset);

}  // namespace vstcal
