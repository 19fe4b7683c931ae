#include "vstcal/handeye/report_phases.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

namespace vstcal {

bool ReportPhases::Locked() const { return concentration >= kLockedReportPhase; }

size_t ReportInterval(std::span<const TrackedPose> log, double tau) {
  const size_t k = static_cast<size_t>(std::upper_bound(log.begin(), log.end(), tau, [](double t, const TrackedPose& p) { return t < p.time; }) -
                                       log.begin());
  return std::min(std::max<size_t>(k, 1), log.size() - 1) - 1;
}

double InterpolationFraction(std::span<const TrackedPose> log, double tau) {
  const size_t k = ReportInterval(log, tau);
  return std::clamp((tau - log[k].time) / (log[k + 1].time - log[k].time), 0.0, 1.0);
}

ReportPhases ViewReportPhases(std::span<const TrackedPose> log, std::span<const double> times, double time_offset) {
  std::vector<double> sorted(times.begin(), times.end());
  std::sort(sorted.begin(), sorted.end());
  ReportPhases out;
  std::complex<double> sum = 0;
  double last = -INFINITY;
  for (const double t : sorted) {
    if (t - last <= 1e-6) continue;
    last = t;
    const double at = t + time_offset;
    if (log.size() < 2 || !(at >= log.front().time && at < log.back().time)) continue;
    sum += std::polar(1.0, 2 * M_PI * InterpolationFraction(log, at));
    ++out.instants;
  }
  if (out.instants == 0) return out;
  out.concentration = std::abs(sum) / static_cast<double>(out.instants);
  const double turn = std::arg(sum) / (2 * M_PI);
  out.mean = turn < 0 ? turn + 1 : turn;
  if (out.mean >= 1) out.mean = 0;
  return out;
}

}  // namespace vstcal
