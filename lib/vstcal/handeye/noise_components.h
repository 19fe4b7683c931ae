// The tracker's noise estimated jointly with X, Z and δ (docs/math/handeye.md#tracker-noise): the
// variance components of a linear mixed model, by restricted maximum likelihood (REML).
//
// Per frame f (the views taken at one instant: one camera's, or a rig's two), at the solution:
// the corner residuals r_f (2n_f, px), their Jacobian J_e (2n_f × 6) with respect to the error
// e_f = (ω, ρ) of the tracker's pose at that instant (R = Exp(ω) R_true, t = t_true + ρ, tracker
// frame) and J_g (2n_f × 13) with respect to X, Z, δ. The linearised model is
//
//   r_f = J_g Δg + J_e e_f + ε_f,   ε_f ~ N(0, c I),   e_f ~ N(0, w_f diag(a I₃, b I₃)),
//
// c = σ_px², a = σ_r² (rad²), b = σ_t² (length unit²), w_f = (1 − s)² + s² for a pose interpolated
// at s between two reports whose errors are independent. Splitting r_f into the part J_e cannot
// produce (2n_f − 6 dof, variance c alone) and the frame's pose discrepancy
// d_f = M⁻¹ J_eᵀ r_f, M = J_eᵀ J_e, of covariance V_f = c M⁻¹ + w_f diag(a I₃, b I₃), the REML
// log-likelihood is
//
//   ℓ_R = −½ Σ_f [S⊥_f / c + (2n_f − 6) log c + d_fᵀ V_f⁻¹ d_f + log det V_f] − ½ log det H,
//   H = Σ_f [A_f / c + G_fᵀ V_f⁻¹ G_f]   (the information on g; A_f = J_gᵀ(I − J_e M⁻¹ J_eᵀ)J_g,
//                                         G_f = M⁻¹ J_eᵀ J_g),
//
// maximised by Fisher scoring over θ = (c, a, b) with a, b ≥ 0; θ's covariance is the inverse of
// the expected information.
#pragma once

#include <span>

#include <Eigen/Core>

namespace vstcal {

// One frame reduced to what the likelihood needs (ReduceNoiseFrame).
struct NoiseFrame {
  Eigen::Matrix<double, 6, 6> M_inv;   // (J_eᵀ J_e)⁻¹
  Eigen::Matrix<double, 6, 1> d;       // M⁻¹ J_eᵀ r
  Eigen::Matrix<double, 6, 13> G;      // M⁻¹ J_eᵀ J_g
  Eigen::Matrix<double, 13, 13> A;     // J_gᵀ J_g − J_gᵀ J_e M⁻¹ J_eᵀ J_g
  double s_perp = 0;                   // |r|² − r_ᵀ J_e M⁻¹ J_eᵀ r
  double n_perp = 0;                   // 2n − 6
  double w = 1;                        // (1 − s)² + s²
};

// nullopt-free: J_e must have full column rank (a view of ≥ 4 corners in general position).
NoiseFrame ReduceNoiseFrame(const Eigen::MatrixXd& J_e, const Eigen::MatrixXd& J_g, const Eigen::VectorXd& r, double w);

// The corners' variance is held at or above (0.001 px)²: noise-free corners (a synthetic recording)
// would otherwise send c to the remainder of the linearisation and the interpolation, ~1e-7 px²,
// where V_f and H lose their precision and the scoring stops short — the tracker then taken as exact
// and δ 5-15 of its σ's from the truth. Corners detected in clean renders are ~0.01 px (the demo's:
// 0.0095 px), ten times the floor, so no real recording comes near it.
inline constexpr double kMinCornerVariance = 1e-6;

struct VarianceComponents {
  Eigen::Vector3d theta = Eigen::Vector3d::Zero();           // c (px²), a (rad²), b (unit²)
  bool corner_variance_at_floor = false;                     // c held at kMinCornerVariance
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();      // of θ
  int iterations = 0;
  bool converged = false;
};

// The start of the estimate: c from the part of the residuals no pose error explains, a and b by
// moments (E[d dᵀ] = c M⁻¹ + w D).
Eigen::Vector3d MomentStart(std::span<const NoiseFrame> frames);

// REML over the frames, from `start` (c > 0; a, b ≥ 0).
VarianceComponents EstimateVarianceComponents(std::span<const NoiseFrame> frames, const Eigen::Vector3d& start);

}  // namespace vstcal
