// The tracker's jitter from a static segment of its log (calib-handeye noise; issue 22 item 1;
// docs/math/handeye.md#noise): the headset held still, every report is the same pose plus noise.
#pragma once

#include <span>

#include <Eigen/Core>

#include "vstcal/handeye/refine.h"

namespace vstcal {

struct NoiseEstimate {
  double sigma = 0;          // per axis, the RMS of the three axes' deviations
  double lower = 0, upper = 0;  // its 95 % confidence interval (χ² with 3(n − 1) degrees of freedom)
  Eigen::Vector3d per_axis = Eigen::Vector3d::Zero();  // each axis' σ (tracker frame)
};

struct TrackerNoise {
  size_t reports = 0;
  double from = 0, to = 0;     // the segment's first and last report times (s)
  Rigid3d mean;                 // tracker_from_hmd of the held headset
  NoiseEstimate rotation;       // radians, left perturbation ω: R_k = Exp(ω_k) R̄
  NoiseEstimate translation;    // length unit
};

// Reports with from ≤ time ≤ to. Throws InputError for fewer than 10 reports in the segment, and
// DegenerateError when it is not static: a rotation beyond 1° or a translation beyond
// `max_motion` (length unit) from the mean — the headset moved.
TrackerNoise EstimateTrackerNoise(std::span<const TrackedPose> log, double from, double to, double max_motion);

}  // namespace vstcal
