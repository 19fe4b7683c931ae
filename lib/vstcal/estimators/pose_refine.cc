#include "vstcal/estimators/pose_refine.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <variant>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

// The normal equations JᵀJ, Jᵀr and the cost Σ|r|² at body_from_world, added to *out; false when
// a point is not in front of its camera.
struct Normal {
  Mat6 H = Mat6::Zero();
  Vec6 g = Vec6::Zero();
  double cost = 0;
  size_t n = 0;
};

template <typename Model>
bool Accumulate(const PoseObservations& set, const Rigid3d& body_from_world, Normal* out) {
  const double* params = set.camera->params.data();
  const Eigen::Matrix3d& Rc = set.camera_from_body.R;
  for (size_t i = 0; i < set.points_in_world.size(); ++i) {
    const Eigen::Vector3d p = body_from_world * set.points_in_world[i];
    const Eigen::Vector3d x = set.camera_from_body * p;
    Eigen::Vector2d px;
    Eigen::Matrix<double, 2, 3, Eigen::RowMajor> d_px_d_x;
    if (!Model::ProjectWithJacobians(params, x.data(), px.data(), nullptr, d_px_d_x.data())) return false;
    const Eigen::Vector2d r = px - set.pixels[i];
    // x = R_cb (Exp(ω) p + ρ) + t_cb: ∂x/∂ω = −R_cb [p]×, ∂x/∂ρ = R_cb.
    const Eigen::Matrix<double, 2, 3> A = d_px_d_x * Rc;
    Eigen::Matrix<double, 2, 6> J;
    J.leftCols<3>() = -A * Hat(p);
    J.rightCols<3>() = A;
    out->H.noalias() += J.transpose() * J;
    out->g.noalias() += J.transpose() * r;
    out->cost += r.squaredNorm();
  }
  out->n += set.points_in_world.size();
  return true;
}

bool Evaluate(std::span<const PoseObservations> sets, const Rigid3d& body_from_world, Normal* out) {
  *out = Normal{};
  for (const PoseObservations& set : sets) {
    VSTCAL_CHECK(set.camera != nullptr && set.pixels.size() == set.points_in_world.size(),
                 "a set needs a camera and one pixel per point");
    const bool ok = std::visit([&](const auto& m) { return Accumulate<std::decay_t<decltype(m)>>(set, body_from_world, out); },
                               set.camera->model);
    if (!ok) return false;
  }
  return true;
}

}  // namespace

PoseRefinement RefinePose(std::span<const PoseObservations> sets, const Rigid3d& start, const PoseRefineOptions& options) {
  PoseRefinement result;
  result.body_from_world = start;
  Normal current;
  if (!Evaluate(sets, start, &current)) {
    result.status = PoseStatus::kNoSolution;
    return result;
  }
  result.residuals = current.n;
  double lambda = 1e-3;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    result.iterations = iteration + 1;
    bool accepted = false;
    Vec6 step = Vec6::Zero();
    Normal trial;
    const Mat6 previous_H = current.H;
    double previous_cost = current.cost;
    // Marquardt's damping: the diagonal scaled by (1 + λ), so that ω (rad) and ρ (length) each
    // take their own scale.
    for (int attempt = 0; attempt < 12 && !accepted; ++attempt) {
      Mat6 A = current.H;
      A.diagonal() *= 1 + lambda;
      step = A.ldlt().solve(-current.g);
      const Rigid3d next = PerturbLeft(result.body_from_world, Eigen::Vector3d(step.head<3>()), Eigen::Vector3d(step.tail<3>()));
      if (step.allFinite() && Evaluate(sets, next, &trial) && trial.cost <= current.cost) {
        accepted = true;
        previous_cost = current.cost;
        result.body_from_world = next;
        current = trial;
        lambda = std::max(lambda * 0.1, 1e-12);
      } else {
        lambda *= 10;
      }
    }
    // No damping lowers the cost: the start was the minimum to rounding. Or the step moved the
    // pixels by less than the tolerance (to first order, Jδ), or lowered the cost by a negligible
    // fraction (along a flat valley Gauss–Newton converges only linearly).
    const double tolerance2 = options.pixel_tolerance * options.pixel_tolerance * static_cast<double>(std::max<size_t>(current.n, 1));
    if (!accepted || step.dot(previous_H * step) <= tolerance2 ||
        previous_cost - current.cost <= options.cost_tolerance * previous_cost) {
      result.status = PoseStatus::kOk;
      break;
    }
  }
  result.cost = current.cost;
  return result;
}

PoseRefinement RefineBranches(std::span<const PoseObservations> sets, const Rigid3d& start,
                              const std::optional<Rigid3d>& mirrored, const PoseRefineOptions& options) {
  PoseRefinement best = RefinePose(sets, start, options);
  if (mirrored) {
    const PoseRefinement other = RefinePose(sets, *mirrored, options);
    const int iterations = best.iterations + other.iterations;
    if (other.status == PoseStatus::kOk && (best.status != PoseStatus::kOk || other.cost < best.cost)) best = other;
    best.iterations = iterations;
  }
  return best;
}

PoseRefinement SolvePnp(const Camera& camera, std::span<const Eigen::Vector3d> points_in_world,
                        std::span<const Eigen::Vector2d> pixels, const PoseRefineOptions& options) {
  VSTCAL_CHECK(points_in_world.size() == pixels.size(), "one pixel per point");
  PoseRefinement out;
  if (points_in_world.size() < kMinPnpPoints) {
    out.status = PoseStatus::kTooFewPoints;
    return out;
  }
  if (ClassifyLayout(points_in_world) == PointLayout::kCollinear) {
    out.status = PoseStatus::kCollinear;
    return out;
  }
  const ClosedFormPose start = SolvePnpClosedForm(camera, points_in_world, pixels);
  if (start.status != PoseStatus::kOk) {
    out.status = start.status;
    return out;
  }
  const PoseObservations set{&camera, Rigid3d::Identity(), points_in_world, pixels};
  return RefineBranches({&set, 1}, start.camera_from_world, start.mirrored, options);
}

}  // namespace vstcal
