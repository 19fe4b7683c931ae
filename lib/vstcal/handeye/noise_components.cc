#include "vstcal/handeye/noise_components.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat13 = Eigen::Matrix<double, 13, 13>;

// ℓ_R, its gradient and the expected information at θ (the header's formulas).
struct Evaluation {
  double value = 0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  bool ok = true;
};

Evaluation Evaluate(std::span<const NoiseFrame> frames, const Eigen::Vector3d& theta, bool with_derivatives) {
  const double c = theta[0], a = theta[1], b = theta[2];
  Evaluation e;
  Mat13 H = Mat13::Zero();
  std::array<Mat13, 3> dH = {Mat13::Zero(), Mat13::Zero(), Mat13::Zero()};
  for (const NoiseFrame& f : frames) {
    Mat6 V = c * f.M_inv;
    V.diagonal().head<3>().array() += f.w * a;
    V.diagonal().tail<3>().array() += f.w * b;
    const Eigen::LLT<Mat6> llt(V);
    if (llt.info() != Eigen::Success) {
      e.ok = false;
      return e;
    }
    const Mat6 Vi = llt.solve(Mat6::Identity());
    const Eigen::Matrix<double, 6, 1> Vd = Vi * f.d;
    const double log_det = 2 * llt.matrixLLT().diagonal().array().log().sum();
    e.value -= 0.5 * (f.s_perp / c + f.n_perp * std::log(c) + f.d.dot(Vd) + log_det);
    const Eigen::Matrix<double, 6, 13> ViG = Vi * f.G;
    H.noalias() += f.A / c + f.G.transpose() * ViG;
    if (!with_derivatives) continue;
    const Mat6 ViMVi = Vi * f.M_inv * Vi;
    e.gradient[0] -= 0.5 * (-f.s_perp / (c * c) + f.n_perp / c + (Vi * f.M_inv).trace() - Vd.dot(f.M_inv * Vd));
    e.gradient[1] -= 0.5 * f.w * (Vi.diagonal().head<3>().sum() - Vd.head<3>().squaredNorm());
    e.gradient[2] -= 0.5 * f.w * (Vi.diagonal().tail<3>().sum() - Vd.tail<3>().squaredNorm());
    const Mat6 ViM = Vi * f.M_inv;
    e.information(0, 0) += 0.5 * ((ViM * ViM).trace() + f.n_perp / (c * c));
    e.information(0, 1) += 0.5 * f.w * ViMVi.diagonal().head<3>().sum();
    e.information(0, 2) += 0.5 * f.w * ViMVi.diagonal().tail<3>().sum();
    e.information(1, 1) += 0.5 * f.w * f.w * Vi.topLeftCorner<3, 3>().squaredNorm();
    e.information(1, 2) += 0.5 * f.w * f.w * Vi.topRightCorner<3, 3>().squaredNorm();
    e.information(2, 2) += 0.5 * f.w * f.w * Vi.bottomRightCorner<3, 3>().squaredNorm();
    dH[0].noalias() -= f.A / (c * c) + ViG.transpose() * f.M_inv * ViG;
    dH[1].noalias() -= f.w * ViG.topRows<3>().transpose() * ViG.topRows<3>();
    dH[2].noalias() -= f.w * ViG.bottomRows<3>().transpose() * ViG.bottomRows<3>();
  }
  // REML: the information the estimate of g takes from the data is not the noise's.
  const Eigen::LLT<Mat13> h(H);
  if (h.info() != Eigen::Success) {
    e.ok = false;
    return e;
  }
  e.value -= h.matrixLLT().diagonal().array().log().sum();
  if (with_derivatives) {
    const Mat13 Hi = h.solve(Mat13::Identity());
    for (int k = 0; k < 3; ++k) e.gradient[k] -= 0.5 * (Hi * dH[static_cast<size_t>(k)]).trace();
    e.information.triangularView<Eigen::StrictlyLower>() = e.information.transpose();
  }
  return e;
}

}  // namespace

NoiseFrame ReduceNoiseFrame(const Eigen::MatrixXd& J_e, const Eigen::MatrixXd& J_g, const Eigen::VectorXd& r, double w) {
  VSTCAL_CHECK(J_e.cols() == 6 && J_g.cols() == 13 && J_e.rows() == r.size() && J_g.rows() == r.size() && r.size() > 6,
               "a noise frame needs Jacobians of 6 and 13 columns over more than 6 residuals");
  NoiseFrame f;
  const Mat6 M = J_e.transpose() * J_e;
  const Eigen::LDLT<Mat6> ldlt(M);
  f.M_inv = ldlt.solve(Mat6::Identity());
  const Eigen::Matrix<double, 6, 1> Jr = J_e.transpose() * r;
  const Eigen::Matrix<double, 6, 13> JJ = J_e.transpose() * J_g;
  f.d = f.M_inv * Jr;
  f.G = f.M_inv * JJ;
  f.A = J_g.transpose() * J_g - JJ.transpose() * f.G;
  f.s_perp = std::max(0.0, r.squaredNorm() - Jr.dot(f.d));
  f.n_perp = static_cast<double>(r.size()) - 6;
  f.w = w;
  return f;
}

Eigen::Vector3d MomentStart(std::span<const NoiseFrame> frames) {
  double s_perp = 0, n_perp = 0, a = 0, b = 0, w = 0;
  for (const NoiseFrame& f : frames) {
    s_perp += f.s_perp;
    n_perp += f.n_perp;
  }
  const double c = std::max(s_perp / n_perp, kMinCornerVariance);
  for (const NoiseFrame& f : frames) {
    a += f.d.head<3>().squaredNorm() - c * f.M_inv.topLeftCorner<3, 3>().trace();
    b += f.d.tail<3>().squaredNorm() - c * f.M_inv.bottomRightCorner<3, 3>().trace();
    w += 3 * f.w;
  }
  return {c, std::max(a / w, 0.0), std::max(b / w, 0.0)};
}

VarianceComponents EstimateVarianceComponents(std::span<const NoiseFrame> frames, const Eigen::Vector3d& start) {
  VSTCAL_CHECK(!frames.empty() && start[0] > 0 && start[1] >= 0 && start[2] >= 0, "variance components need frames and a start with c > 0, a, b ≥ 0");
  VarianceComponents out;
  Eigen::Vector3d theta = start;
  Evaluation e = Evaluate(frames, theta, true);
  if (!e.ok) return out;  // not converged: the caller holds the tracker exact
  double last_decrement = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 100; ++it) {
    out.iterations = it + 1;
    // Fisher scoring over the components not held at their bound (c at kMinCornerVariance, a or b at
    // 0) by a gradient pushing them below it (an active set); scaled so that c, a and b, of very different sizes,
    // are solved on an equal footing.
    std::array<bool, 3> free{};
    const Eigen::Vector3d bound(kMinCornerVariance, 0, 0);
    for (int k = 0; k < 3; ++k) free[static_cast<size_t>(k)] = theta[k] > bound[k] || e.gradient[k] > 0;
    Eigen::Vector3d scale = e.information.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
    Eigen::Matrix3d F = scale.asDiagonal() * e.information * scale.asDiagonal();
    Eigen::Vector3d g = scale.cwiseProduct(e.gradient);
    for (int k = 0; k < 3; ++k) {
      if (free[static_cast<size_t>(k)]) continue;
      F.row(k).setZero();
      F.col(k).setZero();
      F(k, k) = 1;
      g[k] = 0;
    }
    const Eigen::Vector3d step = scale.cwiseProduct(F.ldlt().solve(g));
    // Twice the rise a full step would bring: below 1e-8, the maximum to the precision of ℓ_R.
    const double decrement = g.dot(F.ldlt().solve(g));
    last_decrement = decrement;
    if (decrement < 1e-8) {
      out.converged = true;
      break;
    }
    // Step halving keeps ℓ_R rising (and c, a and b at or above their bounds).
    double t = 1;
    bool moved = false;
    for (int half = 0; half < 30; ++half, t /= 2) {
      Eigen::Vector3d next = theta + t * step;
      if (!(next[0] > 0)) continue;  // halved rather than clamped: the path of every recording before the floor
      next = next.cwiseMax(bound);
      const Evaluation n = Evaluate(frames, next, false);
      if (n.ok && n.value >= e.value - 1e-9) {
        theta = next;
        moved = true;
        break;
      }
    }
    if (!moved) {
      out.converged = true;  // no rise left: the maximum to numerical precision
      break;
    }
    e = Evaluate(frames, theta, true);
    if (!e.ok) return out;
  }
  // Out of iterations (a flat ridge: the translation's noise against the PnP depth's, with few
  // views) with a remaining step below a tenth of θ's standard errors (the decrement is the step's
  // squared length in them) is converged too: the rest is far inside every interval.
  if (!out.converged && last_decrement < 1e-2) out.converged = true;
  out.theta = theta;
  out.corner_variance_at_floor = theta[0] <= kMinCornerVariance;
  out.covariance = e.information.ldlt().solve(Eigen::Matrix3d::Identity());
  return out;
}

}  // namespace vstcal
