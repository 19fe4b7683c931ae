#include "vstcal/estimators/view_rejection.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "vstcal/core/error.h"
#include "vstcal/sensitivity/normal_quantile.h"

namespace vstcal {

RejectionTest TestResiduals(const Correspondences& c, const Fit& fit, size_t num_params, size_t pose_params_per_view,
                            const ViewRejectionOptions& options) {
  VSTCAL_CHECK(fit.views.size() == c.views.size(), "the fit covers the correspondences' views");
  const size_t V = c.views.size();
  size_t N = 0;
  for (const View& v : c.views) N += v.observations.size();
  // Each view's share of the degrees of freedom: its 2n coordinates less its own pose and its share
  // of the parameters all views have in common (docs/math/uncertainty.md#view-rejection).
  const double shared = static_cast<double>(num_params) - static_cast<double>(pose_params_per_view * V);
  std::vector<double> squares(V, 0.0), dof(V, 0.0);
  RejectionTest t;
  t.view_rms_px.resize(V);
  t.view_threshold_px.resize(V);
  for (size_t v = 0; v < V; ++v) {
    const auto& obs = c.views[v].observations;
    for (size_t i = 0; i < obs.size(); ++i) squares[v] += obs[i].weight * fit.views[v].residuals_px[i].squaredNorm();
    const double n = static_cast<double>(obs.size());
    dof[v] = std::max(1.0, 2 * n - static_cast<double>(pose_params_per_view) - shared * n / static_cast<double>(N));
    t.view_rms_px[v] = std::sqrt(squares[v] / std::max(1.0, n));
  }
  // σ̂² = median of S_v/k_v over the median of χ²_k/k, (1 − 2/(9k))³ (Wilson–Hilferty), k the
  // median view's dof.
  std::vector<double> per_dof(V);
  for (size_t v = 0; v < V; ++v) per_dof[v] = squares[v] / dof[v];
  std::vector<size_t> order(V);
  for (size_t v = 0; v < V; ++v) order[v] = v;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return per_dof[a] < per_dof[b]; });
  const size_t lo = order[(V - 1) / 2], hi = order[V / 2];
  const double median = 0.5 * (per_dof[lo] + per_dof[hi]);
  const double k = 0.5 * (dof[lo] + dof[hi]);
  const double shrink = std::pow(1 - 2 / (9 * k), 3);
  t.sigma_px = std::sqrt(median / shrink);

  if (V >= kMinViewsToTest) {
    // σ̂² is itself uncertain: a median of V views' S_v/k_v has relative variance τ² ≈ (π/2)·2/(kV)
    // (the median's efficiency 2/π), which widens Wilson–Hilferty's cube-root normal by τ²/9.
    const double tau2 = std::numbers::pi / (k * static_cast<double>(V));
    const double z = NormalQuantile(1 - options.view_false_alarm / static_cast<double>(V));
    double worst = 1;
    for (size_t v = 0; v < V; ++v) {
      const double n = static_cast<double>(c.views[v].observations.size());
      const double a = 2 / (9 * dof[v]);
      const double root = 1 - a + z * std::sqrt(a + tau2 / 9);
      const double q = dof[v] * root * root * root;
      t.view_threshold_px[v] = t.sigma_px * std::sqrt(q / n);
      const double excess = squares[v] / (t.sigma_px * t.sigma_px * q);
      if (excess > worst) worst = excess, t.worst_view = v;
    }
  }
  if (t.worst_view) return t;
  // Corners: w|r|²/σ̂² ~ (k_v / 2n_v)·χ²₂ (the fit's leverage shrinks each residual), whose tail
  // beyond x is exp(−x/2): the threshold at false-alarm α/N is −2 ln(α/N).
  const double chi2 = -2 * std::log(options.corner_false_alarm / static_cast<double>(N));
  for (size_t v = 0; v < V; ++v) {
    const auto& obs = c.views[v].observations;
    const double leverage = dof[v] / (2.0 * static_cast<double>(obs.size()));
    const double threshold = t.sigma_px * std::sqrt(leverage * chi2);
    for (size_t i = 0; i < obs.size(); ++i) {
      const double r = std::sqrt(obs[i].weight) * fit.views[v].residuals_px[i].norm();
      if (r > threshold) t.corners.push_back({v, i, r, threshold});
    }
  }
  return t;
}

}  // namespace vstcal
