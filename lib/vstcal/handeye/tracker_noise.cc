#include "vstcal/handeye/tracker_noise.h"

#include <cmath>
#include <string>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>

#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/geometry/rotation_average.h"

namespace vstcal {
namespace {

// σ² per axis from zero-mean deviations with `dof` degrees of freedom each; the pooled σ and its
// 95 % interval from (3·dof)·s²/σ² ~ χ²(3·dof).
NoiseEstimate Estimate(const std::vector<Eigen::Vector3d>& deviations) {
  NoiseEstimate e;
  const double dof = static_cast<double>(deviations.size() - 1);
  Eigen::Vector3d ss = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& d : deviations) ss += d.cwiseProduct(d);
  e.per_axis = (ss / dof).cwiseSqrt();
  const double total = ss.sum(), k = 3 * dof;
  e.sigma = std::sqrt(total / k);
  const boost::math::chi_squared chi2(k);
  e.lower = std::sqrt(total / boost::math::quantile(boost::math::complement(chi2, 0.025)));
  e.upper = std::sqrt(total / boost::math::quantile(chi2, 0.025));
  return e;
}

}  // namespace

TrackerNoise EstimateTrackerNoise(std::span<const TrackedPose> log, double from, double to, double max_motion) {
  std::vector<TrackedPose> segment;
  for (const TrackedPose& p : log) {
    if (p.time >= from && p.time <= to) segment.push_back(p);
  }
  if (segment.size() < 10) {
    throw InputError("segment: " + std::to_string(segment.size()) + " reports between " + MessageNumber(from) + " and " + MessageNumber(to) +
                     " s; give a segment (from, to) of at least 10 reports in which the headset was held still");
  }
  TrackerNoise out;
  out.reports = segment.size();
  out.from = segment.front().time;
  out.to = segment.back().time;
  std::vector<Eigen::Matrix3d> rotations;
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  for (const TrackedPose& p : segment) {
    rotations.push_back(p.tracker_from_hmd.R);
    t += p.tracker_from_hmd.t;
  }
  out.mean.R = ChordalMeanRotation(rotations);
  out.mean.t = t / static_cast<double>(segment.size());
  std::vector<Eigen::Vector3d> omegas, rhos;
  for (const TrackedPose& p : segment) {
    const Eigen::Vector3d omega = RotvecFromRotation(p.tracker_from_hmd.R * out.mean.R.transpose());
    const Eigen::Vector3d rho = p.tracker_from_hmd.t - out.mean.t;
    if (omega.norm() > M_PI / 180 || rho.norm() > max_motion) {
      throw DegenerateError("the headset moved at " + MessageNumber(p.time) + " s (" + MessageNumber(omega.norm() * 180 / M_PI) + "°, " +
                            MessageNumber(rho.norm()) + " from the segment's mean pose); give a segment around a time it was held still");
    }
    omegas.push_back(omega);
    rhos.push_back(rho);
  }
  out.rotation = Estimate(omegas);
  out.translation = Estimate(rhos);
  return out;
}

}  // namespace vstcal
