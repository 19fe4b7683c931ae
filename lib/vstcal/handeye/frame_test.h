// The bad-frame test under the full noise model (docs/math/handeye.md#bad-frames): each frame's
// residuals are tested against the corners' noise AND the tracker's rotation and translation noise
// propagated to them, with the variance components estimated robustly from the frames themselves.
//
// Per frame f (noise_components.h), at a solution: the part of its residuals no pose error can
// produce, S⊥_f/c ~ χ²(2n_f − 6 − h⊥_f), and its pose discrepancy d_f ~ N(0, V_f),
// d_fᵀV_f⁻¹d_f ~ χ²(6 − h_d,f), V_f = c M⁻¹ + w_f diag(a I₃, b I₃). h⊥_f = tr(H⁻¹ A_f)/c and
// h_d,f = tr(H⁻¹ G_fᵀV_f⁻¹G_f) are the frame's leverages (the 13 shared parameters' share of its
// degrees of freedom; they sum to 13). The first statistic catches corners that no rigid pose
// explains (a mislabelled board), the second a pose the tracker's noise cannot explain (a glitch,
// a report from another time). Each is compared with its χ² quantile (Wilson–Hilferty, widened by
// the estimate's own uncertainty) at false alarm α/(2F): Bonferroni over both tests and all frames.
//
// θ = (c, a, b) is estimated by REML on the frames that pass (trimmed): a bad frame inflates a or b
// and would mask itself and others; the frames beyond their thresholds are left out of the
// estimate and θ estimated again, until the set is stable.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "vstcal/handeye/noise_components.h"

namespace vstcal {

struct FrameNoiseTest {
  bool ok = false;  // false: the noise could not be estimated (no maximum of the likelihood in reach)
  Eigen::Vector3d theta = Eigen::Vector3d::Zero();  // c, a, b from the frames that pass
  // Per frame: the larger of its two statistics over its threshold (> 1: inconsistent).
  std::vector<double> excess;
};

// `false_alarm`: the probability that a clean recording (every frame from the model) has any
// frame beyond its threshold.
FrameNoiseTest TestFramesAgainstNoise(std::span<const NoiseFrame> frames, double false_alarm);

}  // namespace vstcal
