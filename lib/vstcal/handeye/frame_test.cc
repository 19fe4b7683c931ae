#include "vstcal/handeye/frame_test.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "vstcal/core/error.h"
#include "vstcal/sensitivity/normal_quantile.h"

namespace vstcal {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat13 = Eigen::Matrix<double, 13, 13>;

// χ²_k's quantile at normal quantile z by Wilson–Hilferty, its cube-root normal widened by τ²/9
// for a scale estimated with relative variance τ² (as estimators/view_rejection.cc does).
double ChiSquareThreshold(double k, double z, double tau2) {
  const double a = 2 / (9 * k);
  const double root = 1 - a + z * std::sqrt(a + tau2 / 9);
  return k * root * root * root;
}

// Each frame's excess at θ, the leverages from the information H over every frame.
bool Excess(std::span<const NoiseFrame> frames, const Eigen::Vector3d& theta, double z, double tau2_perp, double tau2_pose,
            std::vector<double>* excess) {
  const double c = theta[0];
  std::vector<Mat6> Vi(frames.size());
  Mat13 H = Mat13::Zero();
  for (size_t f = 0; f < frames.size(); ++f) {
    Mat6 V = c * frames[f].M_inv;
    V.diagonal().head<3>().array() += frames[f].w * theta[1];
    V.diagonal().tail<3>().array() += frames[f].w * theta[2];
    const Eigen::LLT<Mat6> llt(V);
    if (llt.info() != Eigen::Success) return false;
    Vi[f] = llt.solve(Mat6::Identity());
    H.noalias() += frames[f].A / c + frames[f].G.transpose() * Vi[f] * frames[f].G;
  }
  const Eigen::LLT<Mat13> h(H);
  if (h.info() != Eigen::Success) return false;
  const Mat13 Hi = h.solve(Mat13::Identity());
  excess->resize(frames.size());
  for (size_t f = 0; f < frames.size(); ++f) {
    const NoiseFrame& fr = frames[f];
    const double h_perp = (Hi * fr.A).trace() / c;
    const double h_pose = (Hi * fr.G.transpose() * Vi[f] * fr.G).trace();
    const double k_perp = std::max(1.0, fr.n_perp - h_perp), k_pose = std::max(1.0, 6 - h_pose);
    const double perp = fr.s_perp / c / ChiSquareThreshold(k_perp, z, tau2_perp);
    const double pose = fr.d.dot(Vi[f] * fr.d) / ChiSquareThreshold(k_pose, z, tau2_pose);
    (*excess)[f] = std::max(perp, pose);
  }
  return true;
}

}  // namespace

FrameNoiseTest TestFramesAgainstNoise(std::span<const NoiseFrame> frames, double false_alarm) {
  VSTCAL_CHECK(!frames.empty() && false_alarm > 0 && false_alarm < 1, "a frame test needs frames and a false-alarm rate in (0, 1)");
  FrameNoiseTest out;
  const auto F = static_cast<double>(frames.size());
  const double z = NormalQuantile(1 - false_alarm / (2 * F));
  // The scales' relative variances: c from Σ(2n − 6) dof, a and b from 3 dof a frame each.
  double n_perp = 0;
  for (const NoiseFrame& f : frames) n_perp += f.n_perp;
  const double tau2_perp = 2 / n_perp, tau2_pose = 2 / (3 * F);
  std::vector<NoiseFrame> kept(frames.begin(), frames.end());
  Eigen::Vector3d theta = MomentStart(kept);
  std::vector<bool> passing(frames.size(), true);
  for (int round = 0; round < 8; ++round) {
    const VarianceComponents components = EstimateVarianceComponents(kept, theta);
    if (!components.converged) return out;
    theta = components.theta;
    if (!Excess(frames, theta, z, tau2_perp, tau2_pose, &out.excess)) return out;
    // The frames that pass estimate θ again — at least half of them, the most consistent, so
    // that a recording with many bad frames still has a scale.
    std::vector<double> sorted = out.excess;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    const double cut = std::max(1.0, sorted[sorted.size() / 2]);
    std::vector<bool> next(frames.size());
    for (size_t f = 0; f < frames.size(); ++f) next[f] = out.excess[f] <= cut;
    if (next == passing) break;
    passing = std::move(next);
    kept.clear();
    for (size_t f = 0; f < frames.size(); ++f) {
      if (passing[f]) kept.push_back(frames[f]);
    }
  }
  out.ok = true;
  out.theta = theta;
  return out;
}

}  // namespace vstcal
