#include "vstcal/calib/refine.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

#include "vstcal/estimators/information.h"
#include "vstcal/estimators/linear_manifold.h"
#include "vstcal/estimators/reprojection_cost.h"
#include "vstcal/estimators/robust_loss.h"
#include "vstcal/core/error.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

// A residual below this is rounding, never an outlier (px).
constexpr double kRoundingResidualPx = 1e-9;

// Priors' pixel noise: the first round's (a typical corner noise, below most: the prior-held
// parameters stay near their values while the others converge), the relative change of σ̂ that
// ends the rounds, and their limit (two or three suffice: σ̂ barely depends on the priors' weight).
constexpr double kPriorNoiseStartPx = 0.3;
constexpr double kPriorNoiseTolerance = 0.01;
constexpr int kMaxPriorRounds = 6;

// χ²₂ quantile: P(χ²₂ > x) = e^{−x/2}.
double ChiSquare2Quantile(double tail_probability) { return -2.0 * std::log(tail_probability); }

// The priors' whitened residuals in pixels, noise_px · (θ_i − value)/σ_i: beside the reprojection
// residuals (px, a weight-1 point's noise noise_px) the sum of squares is then noise_px² times the
// negative log posterior (docs/math/uncertainty.md#priors). Over the whole intrinsics block.
class PriorCost final : public ceres::CostFunction {
 public:
  PriorCost(std::vector<ResolvedPrior> priors, int num_params, double noise_px)
      : priors_(std::move(priors)), noise_px_(noise_px) {
    set_num_residuals(static_cast<int>(priors_.size()));
    mutable_parameter_block_sizes()->push_back(num_params);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const int n = parameter_block_sizes()[0];
    for (size_t k = 0; k < priors_.size(); ++k) {
      const double scale = noise_px_ / priors_[k].sigma;
      residuals[k] = scale * (parameters[0][priors_[k].index] - priors_[k].value);
      if (jacobians && jacobians[0]) {
        double* row = jacobians[0] + k * static_cast<size_t>(n);
        std::fill(row, row + n, 0.0);
        row[priors_[k].index] = scale;
      }
    }
    return true;
  }

 private:
  std::vector<ResolvedPrior> priors_;
  double noise_px_;
};

// Everything the templated solve needs, independent of the model type.
struct Problem {
  const Correspondences* c;
  std::vector<double> intrinsics;  // θ, the model's whole layout
  FreeIntrinsics free;
  std::vector<Rigid3d> reference;  // pose per rig (volume: 1) or per view
  std::vector<std::array<double, 6>> delta;
};

template <typename Model>
void AddResiduals(ceres::Problem* problem, Problem* p, const RefineOptions& options) {
  const bool volume = p->c->rig == Rig::kVolume;
  for (size_t v = 0; v < p->c->views.size(); ++v) {
    const size_t pose = volume ? 0 : v;
    const std::vector<Observation>& obs = p->c->views[v].observations;
    double* delta = p->delta[pose].data();
    if (options.loss == RefineOptions::Loss::kNone) {
      problem->AddResidualBlock(new ReprojectionCost<Model>(obs, p->reference[pose]), nullptr, p->intrinsics.data(), delta);
      continue;
    }
    for (const Observation& o : obs) {
      problem->AddResidualBlock(new ReprojectionCost<Model>(std::span<const Observation>(&o, 1), p->reference[pose]),
                                MakeLoss(options).release(), p->intrinsics.data(), delta);
    }
  }
}

// Moves the optimum into the reference poses, so the tangent of each pose is again at δ = 0.
void Recentre(Problem* p) {
  for (size_t i = 0; i < p->reference.size(); ++i) {
    const auto& d = p->delta[i];
    p->reference[i] = PerturbLeft(p->reference[i], Eigen::Vector3d(d[0], d[1], d[2]), Eigen::Vector3d(d[3], d[4], d[5]));
    p->delta[i].fill(0.0);
  }
}

// The Ceres problem for the current reference poses (ownership of cost functions and manifolds
// stays with the problem) and its Schur ordering: every pose in the first elimination group, the
// intrinsics last, so the reduced system is the intrinsics' alone, whatever the number of views.
template <typename Model>
std::unique_ptr<ceres::Problem> BuildProblem(Problem* p, const RefineOptions& options, ceres::Solver::Options* solver) {
  auto problem = std::make_unique<ceres::Problem>();
  AddResiduals<Model>(problem.get(), p, options);
  if (p->free.size() == 0) {
    problem->SetParameterBlockConstant(p->intrinsics.data());
  } else {
    problem->SetManifold(p->intrinsics.data(), new LinearManifold(p->free.basis));
  }
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (auto& delta : p->delta) ordering->AddElementToGroup(delta.data(), 0);
  ordering->AddElementToGroup(p->intrinsics.data(), 1);
  solver->linear_solver_type = ceres::DENSE_SCHUR;
  solver->linear_solver_ordering = ordering;
  return problem;
}

template <typename Model>
Refinement RefineWith(const Correspondences& c, Problem* p, const RefineOptions& options) {
  Refinement out;
  out.camera.image_size = c.image_size;
  out.camera.model = Model{};
  out.free = p->free;
  out.held = HeldIntrinsics(Model{}, p->intrinsics, options);
  const std::vector<ResolvedPrior> priors = ResolvePriors(Model{}, p->free, options);
  out.priors = options.priors;

  const size_t n = NumObservations(c);
  const size_t free = static_cast<size_t>(p->free.size()) + 6 * p->reference.size();
  if (2 * n <= free) {
    out.status = RefineStatus::kTooFewPoints;
    out.message = "the refinement needs more residuals than free parameters, but " + std::to_string(n) + " points give " +
                  std::to_string(2 * n) + " for " + std::to_string(free) + " (" + std::to_string(p->free.size()) +
                  " intrinsics, 6 per pose); add points or estimate fewer terms (" VSTCAL_OPT("distortion") ")";
    return out;
  }

  // With priors, the posterior mode depends on the pixel noise (their residuals are scaled by it,
  // PriorCost), which the fit estimates: solve, estimate σ̂, solve again with it until σ̂ settles
  // (docs/math/uncertainty.md#priors). The first round's small noise holds the prior-held
  // parameters near their values while the rest converge.
  double noise_px = kPriorNoiseStartPx;
  out.iterations = 0;
  for (int round = 1;; ++round) {
    ceres::Solver::Options solver;
    std::unique_ptr<ceres::Problem> problem = BuildProblem<Model>(p, options, &solver);
    double prior_cost = 0;  // at the start: initial_rms_px is the reprojection residuals' alone
    if (!priors.empty()) {
      problem->AddResidualBlock(new PriorCost(priors, static_cast<int>(p->intrinsics.size()), noise_px), nullptr,
                                p->intrinsics.data());
      for (const ResolvedPrior& prior : priors) {
        prior_cost += 0.5 * std::pow(noise_px * (p->intrinsics[prior.index] - prior.value) / prior.sigma, 2);
      }
    }
    solver.max_num_iterations = options.max_iterations;
    // Stop when a step changes the cost by less than 1e-10 of itself: parameter changes are then a
    // few 1e-6 of their standard deviations, far below anything a covariance or a test can see.
    solver.function_tolerance = 1e-10;
    solver.parameter_tolerance = 1e-10;
    solver.gradient_tolerance = 1e-14;
    solver.num_threads = 1;  // deterministic
    // Powell's dogleg: from a closed-form start (DLT, Tsai, Zhang) it needs about half the
    // iterations of Levenberg–Marquardt to the same optimum (docs/performance.md).
    solver.trust_region_strategy_type = ceres::DOGLEG;
    solver.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, problem.get(), &summary);
    out.iterations += static_cast<int>(summary.iterations.size()) - 1;
    if (round == 1) out.initial_rms_px = std::sqrt(2 * std::max(0.0, summary.initial_cost - prior_cost) / static_cast<double>(n));
    if (summary.termination_type == ceres::FAILURE || !summary.IsSolutionUsable()) {
      out.status = RefineStatus::kFailed;
      out.message = "the refinement failed: " + summary.message +
                    "; check the initial camera (points behind it?) or the correspondences";
      return out;
    }
    out.status = summary.termination_type == ceres::CONVERGENCE ? RefineStatus::kConverged : RefineStatus::kNotConverged;

    Recentre(p);
    out.camera.params = p->intrinsics;
    out.poses = p->reference;
    out.fit = c.rig == Rig::kVolume ? ComputeVolumeFit(out.camera, p->reference[0], c)
                                    : ComputeViewsFit(out.camera, p->reference, c);

    // Outliers by the robust σ, then the noise estimate and its degrees of freedom
    // (docs/math/uncertainty.md#sigma), on weighted residuals √w r: a weight-1 point's scale.
    auto weighted = [&](size_t v, size_t k) { return std::sqrt(c.views[v].observations[k].weight) * out.fit.views[v].residuals_px[k]; };
    std::vector<double> norms;
    for (size_t v = 0; v < out.fit.views.size(); ++v) {
      for (size_t k = 0; k < out.fit.views[v].residuals_px.size(); ++k) {
        if (out.fit.views[v].residuals_px[k].allFinite()) norms.push_back(weighted(v, k).norm());
      }
    }
    if (2 * norms.size() <= free) {
      out.status = RefineStatus::kFailed;
      out.message = "only " + std::to_string(norms.size()) + " points project in front of the refined "
                    "camera, too few for " + std::to_string(free) + " free parameters; check the correspondences";
      return out;
    }
    std::vector<double> sorted = norms;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    out.robust_sigma_px = sorted[sorted.size() / 2] / std::sqrt(2 * std::log(2.0));
    const double threshold = ChiSquare2Quantile(options.outlier_false_alarm / static_cast<double>(norms.size()));
    // Noise-free data fit exactly (a median residual of 0): residuals of rounding size are no
    // outliers, and a zero σ would make every ‖r‖/σ infinite.
    const double sigma_for_outliers = std::max(out.robust_sigma_px, kRoundingResidualPx);
    out.outliers.clear();
    for (size_t v = 0; v < out.fit.views.size(); ++v) {
      const auto& residuals = out.fit.views[v].residuals_px;
      for (size_t k = 0; k < residuals.size(); ++k) {
        const double z2 = weighted(v, k).squaredNorm() / (sigma_for_outliers * sigma_for_outliers);
        if (residuals[k].allFinite() && z2 > threshold) out.outliers.push_back({v, k, residuals[k], std::sqrt(z2)});
      }
    }
    // A robust loss takes the outliers (almost) out of the fit and out of JᵀWJ, so σ̂ leaves them out
    // too: counted in, one 40 px corner among a few hundred triples σ̂ and the covariance with it.
    // Least squares keeps them in the fit, so σ̂ keeps them as well.
    out.sigma_inliers_only = options.loss != RefineOptions::Loss::kNone;
    double rss = 0;
    size_t n_sigma = 0;
    for (size_t v = 0, next = 0; v < out.fit.views.size(); ++v) {
      const auto& residuals = out.fit.views[v].residuals_px;
      for (size_t k = 0; k < residuals.size(); ++k) {
        const bool outlier = next < out.outliers.size() && out.outliers[next].view == v && out.outliers[next].point == k;
        next += outlier;
        if (!residuals[k].allFinite() || (outlier && out.sigma_inliers_only)) continue;
        rss += weighted(v, k).squaredNorm();
        ++n_sigma;
      }
    }
    // A prior-held parameter counts as spent in full: σ̂ is then at most #priors/dof too large.
    out.dof = 2 * static_cast<int>(n_sigma) - static_cast<int>(free);
    if (out.dof <= 0) {
      out.status = RefineStatus::kFailed;
      out.message = std::to_string(out.outliers.size()) + " of " + std::to_string(norms.size()) +
                    " points are outliers, too many to estimate the noise of the others; check the correspondences";
      return out;
    }
    out.sigma_px = std::sqrt(rss / out.dof);
    const double next_noise = std::max(out.sigma_px, kRoundingResidualPx);
    if (priors.empty() || out.status != RefineStatus::kConverged || std::abs(next_noise - noise_px) <= kPriorNoiseTolerance * next_noise ||
        round == kMaxPriorRounds) {
      break;
    }
    noise_px = next_noise;
  }

  // Covariance at the optimum, linearized at δ = 0 around the refined poses.
  CalibrationCovariance covariance = CovarianceAt(c, out.camera, out.poses, options, out.sigma_px);
  out.smallest_scaled_eigenvalue = covariance.smallest_scaled_eigenvalue;
  if (out.status == RefineStatus::kNotConverged) {
    // An unobservable parameter is the likely reason for wandering: say that rather than "iterate more".
    // A parameter the points barely determine is the likely reason for wandering: say which.
    out.message = "the refinement did not converge in " + std::to_string(options.max_iterations) + " iterations" +
                  (!covariance.observable         ? ": " + covariance.message
                   : !covariance.weakest.empty() ? ": " + covariance.weakest
                                                  : "; raise " VSTCAL_OPT("max_iterations") " or start from a better camera");
    return out;
  }
  if (covariance.observable) {
    out.covariance = std::move(covariance.covariance);
  } else {
    out.message = covariance.message;
  }
  return out;
}

}  // namespace

Refinement Refine(const Correspondences& c, const Camera& initial, const std::vector<Rigid3d>& initial_poses,
                  const RefineOptions& options) {
  const size_t expected_poses = c.rig == Rig::kVolume ? 1 : c.views.size();
  VSTCAL_CHECK(initial_poses.size() == expected_poses, "one initial pose per rig (volume) or per view");
  const AnyLensModel model = RefinedModel(initial.model, options);
  Problem p;
  p.c = &c;
  p.intrinsics = PromotedParams(initial, model);
  p.free = MakeFreeIntrinsics(model, options);
  p.reference = initial_poses;
  p.delta.assign(initial_poses.size(), std::array<double, 6>{});
  return std::visit([&](auto m) { return RefineWith<decltype(m)>(c, &p, options); }, model);
}

}  // namespace vstcal
