#include "vstcal/handeye/refine.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <ceres/ceres.h>

#include "vstcal/core/error.h"
#include "vstcal/estimators/pose_refine.h"
#include "vstcal/scene/fit.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal {
namespace {

// One view's residuals, all its corners: the pose chain X⁻¹ · H(t + δ)⁻¹ · Z is differentiated
// once a view, not once a corner (4× faster at 54 corners a view). X and Z are left perturbations
// (ω, ρ) of fixed reference poses, so that the covariance at the solution, computed with the
// references moved there, is the convention's left-perturbation tangent
// (docs/conventions.md#poses-in-optimisation).
struct ViewCost {
  const Camera* camera;
  std::span<const TrackedPose> log;
  std::span<const Eigen::Vector3d> steps;
  const Rigid3d* x0;
  const Rigid3d* z0;
  const TimedView* view;

  template <typename T>
  bool operator()(T const* const* blocks, T* r) const {
    const T* x = blocks[0];
    const T* z = blocks[1];
    const Rigid3<T> X = PerturbLeft(x0->cast<T>(), Vec3<T>(x[0], x[1], x[2]), Vec3<T>(x[3], x[4], x[5]));
    const Rigid3<T> Z = PerturbLeft(z0->cast<T>(), Vec3<T>(z[0], z[1], z[2]), Vec3<T>(z[3], z[4], z[5]));
    const std::optional<Rigid3<T>> H = InterpolatePose(log, steps, T(view->time) + blocks[2][0]);
    if (!H) return false;
    const Rigid3<T> camera_from_board = X.inverse() * H->inverse() * Z;
    T params[kMaxLensParams];
    for (size_t i = 0; i < camera->params.size(); ++i) params[i] = T(camera->params[i]);
    for (size_t k = 0; k < view->observations.size(); ++k) {
      const Observation& o = view->observations[k];
      const Vec3<T> p = camera_from_board * o.point.cast<T>();
      T q[2];
      if (!ProjectWith(camera->model, params, p.data(), q)) return false;
      r[2 * k] = q[0] - T(o.pixel.x());
      r[2 * k + 1] = q[1] - T(o.pixel.y());
    }
    return true;
  }
};

void CheckLog(std::span<const TrackedPose> log) {
  if (log.size() < 2) throw InputError("poses: " + std::to_string(log.size()) + " reports; the tracker's log needs at least 2");
  for (size_t k = 1; k < log.size(); ++k) {
    if (!(log[k].time > log[k - 1].time)) {
      throw InputError("poses[" + std::to_string(k) + "].time: " + std::to_string(log[k].time) + " is not after the report before it (" +
                       std::to_string(log[k - 1].time) + "); sort the log by time and drop duplicates");
    }
  }
}

// Each view's PnP pose and the tracker's pose at its time + δ: the closed form's samples.
std::vector<HandEyeSample> Samples(std::span<const TrackedPose> log, std::span<const Eigen::Vector3d> steps,
                                   const std::vector<Rigid3d>& camera_from_board, std::span<const TimedView> views, double delta) {
  std::vector<HandEyeSample> out;
  for (size_t v = 0; v < views.size(); ++v) {
    if (const auto H = InterpolatePose(log, steps, views[v].time + delta)) out.push_back({*H, camera_from_board[v]});
  }
  return out;
}

// How well a closed form explains the samples: the spread of tracker_from_board over them (mm
// plus mm-equivalent of rotation at 1 m), for the coarse search of δ.
double Inconsistency(const HandEyeStart& s, std::span<const HandEyeSample> samples) {
  double sum = 0;
  for (const HandEyeSample& x : samples) {
    const Rigid3d z = x.tracker_from_hmd * s.hmd_from_camera * x.camera_from_board;
    sum += (z.t - s.tracker_from_board.t).squaredNorm() + 1e6 * RotvecFromRotation(z.R * s.tracker_from_board.R.transpose()).squaredNorm();
  }
  return sum / static_cast<double>(samples.size());
}


// One maximum-likelihood solve over `views` from the given start: fills X, Z, δ, the fit and the
// covariance of `out`, and returns each view's residuals at the solution.
std::vector<std::vector<Eigen::Vector2d>> Refine(const Camera& camera, std::span<const TrackedPose> log, std::span<const Eigen::Vector3d> steps,
                                                 const std::vector<const TimedView*>& views, const Rigid3d& x_start, const Rigid3d& z_start,
                                                 double delta_start, const HandEyeOptions& options, HandEyeSolution* out) {
  // X, Z as left perturbations of their starts, δ absolute.
  Rigid3d x0 = x_start, z0 = z_start;
  double x[6] = {0, 0, 0, 0, 0, 0}, z[6] = {0, 0, 0, 0, 0, 0}, delta = delta_start;
  ceres::Problem problem;
  std::vector<ceres::CostFunction*> costs;
  out->corners = 0;
  for (const TimedView* v : views) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<ViewCost, 13>(new ViewCost{&camera, log, steps, &x0, &z0, v});
    cost->AddParameterBlock(6);
    cost->AddParameterBlock(6);
    cost->AddParameterBlock(1);
    cost->SetNumResiduals(static_cast<int>(2 * v->observations.size()));
    problem.AddResidualBlock(cost, nullptr, {x, z, &delta});
    costs.push_back(cost);
    out->corners += v->observations.size();
  }
  out->views = views.size();
  ceres::Solver::Options solver;
  solver.max_num_iterations = options.max_iterations;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.num_threads = 1;
  solver.function_tolerance = 1e-12;
  solver.parameter_tolerance = 1e-12;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  out->iterations += static_cast<int>(summary.iterations.size());
  out->hmd_from_camera = PerturbLeft(x0, Eigen::Vector3d(x[0], x[1], x[2]), Eigen::Vector3d(x[3], x[4], x[5]));
  out->tracker_from_board = PerturbLeft(z0, Eigen::Vector3d(z[0], z[1], z[2]), Eigen::Vector3d(z[3], z[4], z[5]));
  out->time_offset = delta;

  // The covariance at the solution: references moved there, tangents zero, J of all residuals.
  x0 = out->hmd_from_camera;
  z0 = out->tracker_from_board;
  std::fill(std::begin(x), std::end(x), 0.0);
  std::fill(std::begin(z), std::end(z), 0.0);
  double cost = 0;
  ceres::CRSMatrix crs;
  problem.Evaluate(ceres::Problem::EvaluateOptions{}, &cost, nullptr, nullptr, &crs);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r) {
    for (int i = crs.rows[static_cast<size_t>(r)]; i < crs.rows[static_cast<size_t>(r) + 1]; ++i) {
      J(r, crs.cols[static_cast<size_t>(i)]) = crs.values[static_cast<size_t>(i)];
    }
  }
  const double residuals = static_cast<double>(crs.num_rows);
  out->rms_px = std::sqrt(2 * cost / residuals);
  out->sigma_px = residuals > kHandEyeParameters ? std::sqrt(2 * cost / (residuals - kHandEyeParameters)) : 0.0;
  out->covariance = out->sigma_px * out->sigma_px * (J.transpose() * J).inverse();

  std::vector<std::vector<Eigen::Vector2d>> per_view;
  const double* parameters[] = {x, z, &delta};
  for (size_t k = 0; k < views.size(); ++k) {
    std::vector<double> r(2 * views[k]->observations.size());
    costs[k]->Evaluate(parameters, r.data(), nullptr);
    std::vector<Eigen::Vector2d> pixels;
    for (size_t i = 0; i < views[k]->observations.size(); ++i) pixels.emplace_back(r[2 * i], r[2 * i + 1]);
    per_view.push_back(std::move(pixels));
  }
  return per_view;
}
}  // namespace

std::vector<Eigen::Vector3d> LogSteps(std::span<const TrackedPose> log) {
  std::vector<Eigen::Vector3d> steps;
  for (size_t k = 0; k + 1 < log.size(); ++k) {
    steps.push_back(RotvecFromRotation(log[k].tracker_from_hmd.R.transpose() * log[k + 1].tracker_from_hmd.R));
  }
  return steps;
}

HandEyeSolution SolveHandEye(const Camera& camera, std::span<const TrackedPose> log, std::span<const TimedView> views,
                             const HandEyeOptions& options) {
  CheckLog(log);
  const std::vector<Eigen::Vector3d> steps = LogSteps(log);
  for (const TimedView& v : views) {
    if (!(v.time >= log.front().time && v.time <= log.back().time)) {
      throw InputError("view \"" + v.name + "\": time " + std::to_string(v.time) + " s is outside the tracker's log (" +
                       std::to_string(log.front().time) + " … " + std::to_string(log.back().time) + " s); drop the view or record longer");
    }
  }
  // Each view's board pose from its corners alone.
  std::vector<Rigid3d> camera_from_board;
  for (const TimedView& v : views) {
    std::vector<Eigen::Vector3d> points;
    std::vector<Eigen::Vector2d> pixels;
    for (const Observation& o : v.observations) {
      points.push_back(o.point);
      pixels.push_back(o.pixel);
    }
    const PoseRefinement pose = SolvePnp(camera, points, pixels);
    if (pose.status != PoseStatus::kOk) {
      throw DegenerateError("view \"" + v.name + "\": the board's pose cannot be solved (" + std::string(PoseStatusText(pose.status)) +
                            "); drop the view");
    }
    camera_from_board.push_back(pose.body_from_world);
  }

  // δ's start: the closed form at each δ of a coarse grid, the most consistent kept.
  HandEyeSolution out;
  double best = std::numeric_limits<double>::infinity();
  const int steps_each_side = static_cast<int>(std::floor(options.max_time_offset / options.search_step));
  for (int k = -steps_each_side; k <= steps_each_side; ++k) {
    const double delta = k * options.search_step;
    const std::vector<HandEyeSample> samples = Samples(log, steps, camera_from_board, views, delta);
    if (samples.size() < kMinHandEyeSamples) continue;
    const HandEyeStart start = SolveHandEyeClosedForm(samples);
    const double score = Inconsistency(start, samples);
    if (score < best) {
      best = score;
      out.start = start;
      out.start_time_offset = delta;
    }
  }
  if (!std::isfinite(best)) out.start = SolveHandEyeClosedForm(Samples(log, steps, camera_from_board, views, 0.0));  // throws why

  // The refinement, then the test of every view against the others' noise: a view that the
  // solution cannot explain as well as the rest (a tracker glitch, a smeared or mislabelled board)
  // is dropped and the rest solved again from where they were, until every view is consistent.
  std::vector<const TimedView*> active;
  for (const TimedView& v : views) active.push_back(&v);
  std::vector<size_t> index(views.size());  // active[k] is views[index[k]]
  for (size_t k = 0; k < views.size(); ++k) index[k] = k;
  Rigid3d x_start = out.start.hmd_from_camera, z_start = out.start.tracker_from_board;
  double delta_start = out.start_time_offset;
  for (int round = 1;; ++round) {
    const std::vector<std::vector<Eigen::Vector2d>> residuals = Refine(camera, log, steps, active, x_start, z_start, delta_start, options, &out);
    if (!options.rejection.enabled || round > options.rejection.max_rounds) break;
    Correspondences c;
    Fit fit;
    for (size_t k = 0; k < active.size(); ++k) {
      c.views.push_back(View{active[k]->name, "", std::nullopt, active[k]->observations});
      fit.views.push_back(ViewFit{active[k]->name, {}, residuals[k]});
    }
    const RejectionTest test = TestResiduals(c, fit, kHandEyeParameters, 0, options.rejection);
    if (!test.worst_view) break;
    std::vector<double> rms = test.view_rms_px;
    std::nth_element(rms.begin(), rms.begin() + static_cast<long>(rms.size() / 2), rms.end());
    if (test.view_rms_px[*test.worst_view] < options.min_rms_ratio * rms[rms.size() / 2]) break;
    if (active.size() <= kMinHandEyeSamples) {
      out.warnings.push_back("view \"" + active[*test.worst_view]->name + "\" is inconsistent with the others (RMS " +
                             MessageNumber(test.view_rms_px[*test.worst_view]) + " px, threshold " +
                             MessageNumber(test.view_threshold_px[*test.worst_view]) + " px) but only " + std::to_string(active.size()) +
                             " views remain; kept. Record more views");
      break;
    }
    const size_t worst = *test.worst_view;
    Rejection r;
    r.kind = Rejection::Kind::kView;
    r.round = round;
    r.view = index[worst];
    r.view_name = active[worst]->name;
    r.rms_px = test.view_rms_px[worst];
    r.threshold_px = test.view_threshold_px[worst];
    r.because = "its corners are inconsistent with the other views' noise (σ̂ " + MessageNumber(test.sigma_px) +
                " px): a tracker glitch, a smeared or mislabelled board, or a pose log out of step at that time";
    out.rejected.push_back(std::move(r));
    active.erase(active.begin() + static_cast<long>(worst));
    index.erase(index.begin() + static_cast<long>(worst));
    x_start = out.hmd_from_camera;
    z_start = out.tracker_from_board;
    delta_start = out.time_offset;
  }
  out.names = HandEyeCovarianceNames();
  return out;
}

}  // namespace vstcal
