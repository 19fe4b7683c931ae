#include "vstcal/calib/refine.h"

#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "vstcal/calib/reprojection_cost.h"
#include "vstcal/core/error.h"
#include "vstcal/core/suggest.h"

namespace vstcal {
namespace {

// A residual below this is rounding, never an outlier (px).
constexpr double kRoundingResidualPx = 1e-9;

// χ²₂ quantile: P(χ²₂ > x) = e^{−x/2}.
double ChiSquare2Quantile(double tail_probability) { return -2.0 * std::log(tail_probability); }

// The model to refine: promoted to radial-tangential when distortion terms are asked for.
AnyLensModel RefinedModel(const AnyLensModel& initial, const RefineOptions& options) {
  if (!options.free_distortion.empty() && LensModelNumParams(initial) == kNumIntrinsicParams) {
    return RadialTangentialModel{};
  }
  return initial;
}

std::vector<double> PromoteParams(const Camera& initial, const AnyLensModel& model) {
  std::vector<double> params(LensModelNumParams(model), 0.0);
  std::copy(initial.params.begin(), initial.params.end(), params.begin());
  return params;
}

std::string PoseName(const Correspondences& c, size_t pose) {
  return c.rig == Rig::kVolume ? "camera_from_world" : "views[" + std::to_string(pose) + "].camera_from_board";
}

std::unique_ptr<ceres::LossFunction> MakeLoss(const RefineOptions& options) {
  switch (options.loss) {
    case RefineOptions::Loss::kHuber: return std::make_unique<ceres::HuberLoss>(options.loss_scale_px);
    case RefineOptions::Loss::kCauchy: return std::make_unique<ceres::CauchyLoss>(options.loss_scale_px);
    default: return nullptr;
  }
}

// Everything the templated solve needs, independent of the model type.
struct Problem {
  const Correspondences* c;
  std::vector<double> intrinsics;
  std::vector<int> free_intrinsics;  // indices into intrinsics
  std::vector<Rigid3d> reference;    // pose per rig (volume: 1) or per view
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

// Builds the Ceres problem for the current reference poses (ownership of cost functions and
// manifolds stays with the problem).
template <typename Model>
std::unique_ptr<ceres::Problem> BuildProblem(Problem* p, const RefineOptions& options) {
  auto problem = std::make_unique<ceres::Problem>();
  AddResiduals<Model>(problem.get(), p, options);
  std::vector<int> fixed;
  for (int i = 0; i < Model::kNumParams; ++i) {
    if (std::find(p->free_intrinsics.begin(), p->free_intrinsics.end(), i) == p->free_intrinsics.end()) fixed.push_back(i);
  }
  if (fixed.size() == static_cast<size_t>(Model::kNumParams)) {
    problem->SetParameterBlockConstant(p->intrinsics.data());
  } else if (!fixed.empty()) {
    problem->SetManifold(p->intrinsics.data(), new ceres::SubsetManifold(Model::kNumParams, fixed));
  }
  return problem;
}

// σ̂² (JᵀJ)⁻¹ over the free parameters at δ = 0 (the poses recentred on the optimum), or an
// empty matrix when JᵀJ is singular. Columns: the free intrinsics, then 6 per pose. With a robust
// loss each point's rows are weighted by ρ′(‖r‖²) (the IRLS information).
template <typename Model>
Eigen::MatrixXd Covariance(const Problem& p, const RefineOptions& options, double sigma2, std::string* message) {
  const int free = static_cast<int>(p.free_intrinsics.size());
  const int n = free + 6 * static_cast<int>(p.reference.size());
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(n, n);
  const std::unique_ptr<ceres::LossFunction> loss = MakeLoss(options);
  const double zero[6] = {};
  const bool volume = p.c->rig == Rig::kVolume;
  for (size_t v = 0; v < p.c->views.size(); ++v) {
    const size_t pose = volume ? 0 : v;
    const std::vector<Observation>& obs = p.c->views[v].observations;
    const ReprojectionCost<Model> cost(obs, p.reference[pose]);
    std::vector<double> r(2 * obs.size()), Ji(2 * obs.size() * Model::kNumParams), Jp(2 * obs.size() * 6);
    const double* params[2] = {p.intrinsics.data(), zero};
    double* jacobians[2] = {Ji.data(), Jp.data()};
    if (!cost.Evaluate(params, r.data(), jacobians)) continue;  // cannot happen at a converged optimum
    // Each point's rows touch the free intrinsics and one pose: accumulate their small Gram
    // matrix and scatter it, instead of multiplying full-width rows.
    const int m = free + 6;
    Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::RowMajor, 2, 6 + Model::kNumParams> J(2, m);
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(m, m);
    for (size_t k = 0; k < obs.size(); ++k) {
      for (int row = 0; row < 2; ++row) {
        for (int f = 0; f < free; ++f) J(row, f) = Ji[(2 * k + row) * Model::kNumParams + p.free_intrinsics[f]];
        for (int c = 0; c < 6; ++c) J(row, free + c) = Jp[(2 * k + row) * 6 + c];
      }
      double weight = 1.0;
      if (loss) {
        double rho[3];
        loss->Evaluate(r[2 * k] * r[2 * k] + r[2 * k + 1] * r[2 * k + 1], rho);
        weight = rho[1];
      }
      for (int a = 0; a < m; ++a) {
        const double wa0 = weight * J(0, a), wa1 = weight * J(1, a);
        for (int b = a; b < m; ++b) gram(a, b) += wa0 * J(0, b) + wa1 * J(1, b);
      }
    }
    gram = gram.selfadjointView<Eigen::Upper>();
    const int pose_column = free + 6 * static_cast<int>(pose);
    information.topLeftCorner(free, free) += gram.topLeftCorner(free, free);
    information.block(0, pose_column, free, 6) += gram.topRightCorner(free, 6);
    information.block(pose_column, 0, 6, free) += gram.bottomLeftCorner(6, free);
    information.block(pose_column, pose_column, 6, 6) += gram.bottomRightCorner(6, 6);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(information);
  const double largest = eig.eigenvalues().maxCoeff();
  if (!(eig.eigenvalues().minCoeff() > 1e-13 * largest)) {
    *message = "the information matrix is singular: some free parameter is not observable from these points "
               "(e.g. skew or a distortion term without coverage); estimate fewer terms (--distortion, --skew) or "
               "add views";
    return {};
  }
  const Eigen::VectorXd inverse = eig.eigenvalues().cwiseInverse();
  const Eigen::MatrixXd covariance = sigma2 * eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
  // V D Vᵀ is symmetric only to rounding; the file promises a symmetric matrix, bit for bit.
  return 0.5 * (covariance + covariance.transpose());
}

template <typename Model>
Refinement RefineWith(const Correspondences& c, Problem* p, const RefineOptions& options) {
  Refinement out;
  out.camera.image_size = c.image_size;
  out.camera.model = Model{};

  const size_t n = NumObservations(c);
  const size_t free = p->free_intrinsics.size() + 6 * p->reference.size();
  if (2 * n <= free) {
    out.status = RefineStatus::kTooFewPoints;
    out.message = "the refinement needs more residuals than free parameters, but " + std::to_string(n) + " points give " +
                  std::to_string(2 * n) + " for " + std::to_string(free) + " (" + std::to_string(p->free_intrinsics.size()) +
                  " intrinsics, 6 per pose); add points or estimate fewer terms (--distortion)";
    return out;
  }

  std::unique_ptr<ceres::Problem> problem = BuildProblem<Model>(p, options);
  ceres::Solver::Options solver;
  solver.linear_solver_type = c.rig == Rig::kVolume ? ceres::DENSE_NORMAL_CHOLESKY : ceres::DENSE_SCHUR;
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
  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  out.initial_rms_px = std::sqrt(2 * summary.initial_cost / static_cast<double>(n));
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
  const std::vector<Rigid3d> per_view =
      c.rig == Rig::kVolume ? std::vector<Rigid3d>(c.views.size(), p->reference[0]) : p->reference;
  out.fit = c.rig == Rig::kVolume ? ComputeVolumeFit(out.camera, p->reference[0], c)
                                  : ComputeViewsFit(out.camera, per_view, c);

  // Outliers by the robust σ, then the noise estimate and its degrees of freedom
  // (docs/math/uncertainty.md#sigma).
  std::vector<double> norms;
  for (const ViewFit& v : out.fit.views) {
    for (const Eigen::Vector2d& r : v.residuals_px) {
      if (r.allFinite()) norms.push_back(r.norm());
    }
  }
  if (2 * static_cast<int>(norms.size()) <= static_cast<int>(free)) {
    out.status = RefineStatus::kFailed;
    out.message = "only " + std::to_string(norms.size()) + " points project in front of the refined "
                  "camera, too few for " + std::to_string(free) + " free parameters; check the correspondences";
    return out;
  }
  std::vector<double> sorted = norms;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  out.robust_sigma_px = sorted[sorted.size() / 2] / std::sqrt(2 * std::log(2.0));
  const double threshold = ChiSquare2Quantile(options.outlier_false_alarm / static_cast<double>(norms.size()));
  // Noise-free data fit exactly (a median residual of 0): residuals of rounding size are no
  // outliers, and a zero σ would make every ‖r‖/σ infinite.
  const double sigma_for_outliers = std::max(out.robust_sigma_px, kRoundingResidualPx);
  for (size_t v = 0; v < out.fit.views.size(); ++v) {
    const auto& residuals = out.fit.views[v].residuals_px;
    for (size_t k = 0; k < residuals.size(); ++k) {
      const double z2 = residuals[k].squaredNorm() / (sigma_for_outliers * sigma_for_outliers);
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
      rss += residuals[k].squaredNorm();
      ++n_sigma;
    }
  }
  out.dof = 2 * static_cast<int>(n_sigma) - static_cast<int>(free);
  if (out.dof <= 0) {
    out.status = RefineStatus::kFailed;
    out.message = std::to_string(out.outliers.size()) + " of " + std::to_string(norms.size()) +
                  " points are outliers, too many to estimate the noise of the others; check the correspondences";
    return out;
  }
  out.sigma_px = std::sqrt(rss / out.dof);

  // Covariance at the optimum, linearized at δ = 0 around the refined poses.
  std::string singular;
  out.covariance.matrix = Covariance<Model>(*p, options, out.sigma_px * out.sigma_px, &singular);
  if (out.status == RefineStatus::kNotConverged) {
    // An unobservable parameter is the likely reason for wandering: say that rather than "iterate more".
    out.message = "the refinement did not converge in " + std::to_string(options.max_iterations) + " iterations" +
                  (singular.empty() ? "; raise --max-iterations or start from a better camera" : ": " + singular);
    out.covariance.matrix.resize(0, 0);
    return out;
  }
  if (out.covariance.matrix.size() == 0) {
    out.message = singular;
  } else {
    const auto names = LensModelParamNames(out.camera.model);
    for (int i : p->free_intrinsics) out.covariance.parameters.emplace_back(names[i]);
    for (size_t i = 0; i < p->reference.size(); ++i) {
      for (const char* axis : {"rx", "ry", "rz", "tx", "ty", "tz"}) {
        out.covariance.parameters.push_back(PoseName(c, i) + "." + axis);
      }
    }
  }
  return out;
}

}  // namespace

std::vector<std::string> FreeIntrinsicNames(const AnyLensModel& model, const RefineOptions& options) {
  const auto names = LensModelParamNames(model);
  std::vector<std::string> free;
  auto add = [&](std::string_view name) { free.emplace_back(name); };
  if (options.free_focal) add("fx"), add("fy");
  if (options.free_principal_point) add("cx"), add("cy");
  if (options.free_skew) add("s");
  for (size_t i = kNumIntrinsicParams; i < names.size(); ++i) {
    if (std::find(options.free_distortion.begin(), options.free_distortion.end(), names[i]) !=
        options.free_distortion.end()) {
      add(names[i]);
    }
  }
  return free;
}

Refinement Refine(const Correspondences& c, const Camera& initial, const std::vector<Rigid3d>& initial_poses,
                  const RefineOptions& options) {
  const size_t expected_poses = c.rig == Rig::kVolume ? 1 : c.views.size();
  VSTCAL_CHECK(initial_poses.size() == expected_poses, "one initial pose per rig (volume) or per view");
  const AnyLensModel model = RefinedModel(initial.model, options);
  const auto names = LensModelParamNames(model);
  for (const std::string& term : options.free_distortion) {
    const auto it = std::find(names.begin() + kNumIntrinsicParams, names.end(), term);
    if (it == names.end()) {
      const std::vector<std::string_view> terms(names.begin() + kNumIntrinsicParams, names.end());
      throw InputError("--distortion: unknown term \"" + term + "\" for the " + std::string(LensModelName(model)) +
                       " model; " + SuggestKey(term, terms) + ", or none for no distortion");
    }
  }
  Problem p;
  p.c = &c;
  p.intrinsics = PromoteParams(initial, model);
  for (const std::string& name : FreeIntrinsicNames(model, options)) {
    p.free_intrinsics.push_back(static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin()));
  }
  p.reference = initial_poses;
  p.delta.assign(initial_poses.size(), std::array<double, 6>{});
  return std::visit([&](auto m) { return RefineWith<decltype(m)>(c, &p, options); }, model);
}

}  // namespace vstcal
