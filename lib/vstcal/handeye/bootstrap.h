// A parametric bootstrap of a hand-eye solution (docs/math/handeye.md#delta-bootstrap): recordings
// simulated at the estimate — the tracker's reports as the motion plus fresh report noise of the
// estimated σ's, each kept view's corners projected at its time through the interpolated pose plus
// fresh corner noise — each solved again, and the spread of the solutions taken. It is there for
// δ's σ: with few views the profile likelihood in δ is far from quadratic (a cusp where the views
// sit on the tracker's reports, a curvature that varies from recording to recording), and the
// first-order sandwich is off by up to 15 % where the bootstrap's spread is not.
#pragma once

#include <cstdint>
#include <span>

#include <Eigen/Core>

#include "vstcal/handeye/refine.h"

namespace vstcal {

struct HandEyeBootstrapOptions {
  int replicates = 100;  // simulated recordings, each solved once: the cost is replicates × one solve
  uint64_t seed = 1;     // replicate b draws from (seed, b) alone: the result does not depend on `threads`
  unsigned threads = 1;  // 0: every core
};

struct HandEyeBootstrap {
  int replicates = 0;  // asked for
  int solved = 0;      // of which solved (a replicate whose solve throws is left out and counted)
  uint64_t seed = 0;
  // The replicates' sample covariance of (X's left-perturbation tangent from the estimate, Z's, δ),
  // 13 × 13 in HandEyeCovarianceNames' order, and their mean (δ's: the bootstrap's estimate of δ̂'s
  // bias, s).
  Eigen::MatrixXd covariance;
  Eigen::VectorXd mean;
};

// `solution` is SolveHandEye's on the same inputs with the same `options` and `rig`; its rejected
// views are left out. The tracker's noise is solution.tracker_noise's σ's (none: the tracker
// exact and the corners' σ̂ = sigma_px). The replicates are solved with the bad-frame test off
// (the model has no bad frames). Throws InputError for fewer than 2 replicates.
HandEyeBootstrap BootstrapHandEye(const Camera& camera, std::span<const TrackedPose> log, std::span<const TimedView> views,
                                  const HandEyeSolution& solution, const HandEyeOptions& options,
                                  const HandEyeBootstrapOptions& bootstrap, const HandEyeRig* rig = nullptr);

}  // namespace vstcal
