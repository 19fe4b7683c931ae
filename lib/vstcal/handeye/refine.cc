#include "vstcal/handeye/refine.h"
#include "vstcal/handeye/report_phases.h"

#include "vstcal/handeye/frame_test.h"
#include "vstcal/handeye/noise_components.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <type_traits>
#include <variant>

#include <Eigen/Dense>
#include <ceres/ceres.h>

#include "vstcal/core/error.h"
#include "vstcal/estimators/pose_refine.h"
#include "vstcal/scene/fit.h"
#include "vstcal/geometry/linalg.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal {
namespace {

// Views whose times differ by no more than this (s) are one instant: the same tracker pose.
constexpr double kSameInstant = 1e-6;

// A view in the solve: its camera and, for a rig's right camera, right_from_left (else null).
struct SolveView {
  const TimedView* view;
  const Camera* camera;
  const Rigid3d* right_from_left;
  size_t index;  // in the left views, then the right (Rejection::view)
};

// The views of one instant: they share the tracker's pose H(t + δ) and, with it, its error (a
// rig's two views of one time; otherwise each view is a frame of its own).
struct Frame {
  double time = 0;
  std::vector<SolveView> views;
  size_t Residuals() const {
    size_t n = 0;
    for (const SolveView& v : views) n += 2 * v.view->observations.size();
    return n;
  }
};

// What every cost shares: the tracker's log and the reference poses of X and Z.
struct Chain {
  std::span<const TrackedPose> log;
  std::span<const Eigen::Vector3d> steps;
  Rigid3d x0, z0;
};

// A corner's pixel and its Jacobian ∂pixel/∂p_cam (2 × 3, row-major) through the one projection.
bool ProjectWithPointJacobian(const Camera& camera, const double* p_cam, double* px, double* d_px_d_p) {
  return std::visit([&](const auto& model) { return std::decay_t<decltype(model)>::ProjectWithJacobians(camera.params.data(), p_cam, px, nullptr, d_px_d_p); },
                    camera.model);
}

// A frame's corner residuals (px) at the left perturbations x, z of the references, δ, and the
// tracker pose's error e = (ω, ρ): H → (Exp(ω) R_H, t_H + ρ) (null: none). The pose chain
// X⁻¹ · H(t + δ)⁻¹ · Z is differentiated once a frame, not once a corner (4× faster at 54 corners a
// view). X and Z are left perturbations (ω, ρ) of fixed reference poses, so that the covariance at
// the solution, computed with the references moved there, is the convention's left-perturbation
// tangent (docs/conventions.md#poses-in-optimisation).
template <typename T>
bool FrameResiduals(const Chain& chain, const Frame& frame, const T* x, const T* z, const T& delta, const T* e, T* r) {
  const Rigid3<T> X = PerturbLeft(chain.x0.cast<T>(), Vec3<T>(x[0], x[1], x[2]), Vec3<T>(x[3], x[4], x[5]));
  const Rigid3<T> Z = PerturbLeft(chain.z0.cast<T>(), Vec3<T>(z[0], z[1], z[2]), Vec3<T>(z[3], z[4], z[5]));
  std::optional<Rigid3<T>> H = InterpolatePose(chain.log, chain.steps, T(frame.time) + delta);
  if (!H) return false;
  if (e) *H = Rigid3<T>{RotationFromSmallRotvec(Vec3<T>(e[0], e[1], e[2])) * H->R, H->t + Vec3<T>(e[3], e[4], e[5])};
  const Rigid3<T> left_from_board = X.inverse() * H->inverse() * Z;
  for (const SolveView& v : frame.views) {
    const Rigid3<T> camera_from_board = v.right_from_left ? v.right_from_left->cast<T>() * left_from_board : left_from_board;
    if constexpr (std::is_same_v<T, double>) {
      for (const Observation& o : v.view->observations) {
        const Eigen::Vector3d p = camera_from_board * o.point;
        double q[2];
        if (!ProjectWith(v.camera->model, v.camera->params.data(), p.data(), q)) return false;
        *r++ = q[0] - o.pixel.x();
        *r++ = q[1] - o.pixel.y();
      }
    } else {
      // The chain rule at the point: the point's Jets (the pose's derivatives, R·P + t with P a
      // constant) times the projection's 2 × 3 Jacobian in double — rather than projecting with
      // Jets of every parameter (a third of the Jet operations; the same values and derivatives).
      const Mat3<T>& R = camera_from_board.R;
      const Vec3<T>& t = camera_from_board.t;
      for (const Observation& o : v.view->observations) {
        const Eigen::Vector3d& P = o.point;
        T p[3];
        for (int i = 0; i < 3; ++i) p[i] = R(i, 0) * P.x() + R(i, 1) * P.y() + R(i, 2) * P.z() + t[i];
        const double p_value[3] = {p[0].a, p[1].a, p[2].a};
        double q[2], d_q_d_p[6];
        if (!ProjectWithPointJacobian(*v.camera, p_value, q, d_q_d_p)) return false;
        for (int k = 0; k < 2; ++k, ++r) {
          r->a = q[k] - o.pixel[k];
          r->v = d_q_d_p[3 * k] * p[0].v + d_q_d_p[3 * k + 1] * p[1].v + d_q_d_p[3 * k + 2] * p[2].v;
        }
      }
    }
  }
  return true;
}

// InterpolationWeight at tracker time τ, s the fraction of τ in its interval: with T a Jet, δ's
// derivative flows through s.
template <typename T>
T InterpolationWeightAt(std::span<const TrackedPose> log, const T& tau) {
  const size_t k = ReportInterval(log, detail::ScalarPart(tau));
  const T s = (tau - T(log[k].time)) / T(log[k + 1].time - log[k].time);
  return InterpolationWeight(s);
}

// The headset's true velocity over report interval k — (spatial angular, rad/s; linear, unit/s), the
// tangent of the tracker-error perturbation e — from a quadratic fit of the ten reports around the
// interval (k − 4 … k + 5, shifted inside the log), its slope at the interval's midpoint: for a
// quadratic, the secant of the fitted poses at t_k and t_k+1, what the interpolation of the true
// reports would give. Its variance, σ²/Σ(t − t_mid)² = σ²/(82.5 Δt²), is 1/165 of the two reports'
// slope's (2σ²/Δt²), at the price of taking the motion smooth over ten reports. Fewer than three
// reports: their secant.
Eigen::Matrix<double, 6, 1> SmoothedVelocity(std::span<const TrackedPose> log, size_t k) {
  constexpr size_t kReports = 10;
  const size_t count = std::min(kReports, log.size());
  const size_t first = std::min(k >= 4 ? k - 4 : 0, log.size() - count);
  const Rigid3d& at = log[k].tracker_from_hmd;
  const double mid = 0.5 * (log[k].time + log[k + 1].time);
  Eigen::Matrix<double, 6, 1> v;
  if (count < 3) {
    const Rigid3d& next = log[k + 1].tracker_from_hmd;
    const double dt = log[k + 1].time - log[k].time;
    v << RotvecFromRotation(next.R * at.R.transpose()) / dt, (next.t - at.t) / dt;
    return v;
  }
  v = FitReportsQuadratic(log, first, count, at, mid).row(1).transpose();
  return v;
}

// The whitening of a frame's residuals r by the tracker's noise (docs/math/handeye.md#delta-likelihood):
// C(δ) = c I + w(s(δ)) K, K = Jₑ D Jₑᵀ, D = diag(σ_r² I₃, σ_t² I₃), with D^½ Jₑᵀ Jₑ D^½ = U Λ Uᵀ and
// L = Jₑ D^½ U (orthogonal columns, |L_i|² = λ_i), ℓ = Lᵀ r:
//
//   r̃ = [ (r − L diag(w/(c + wλ)) ℓ)/√c ;  √w ℓ_i/(c + wλ_i) ],   |r̃|² = rᵀ C(δ)⁻¹ r,
//
// the corners' likelihood with the tracker's error at that instant profiled out. w is recomputed
// from δ inside the cost, so δ's derivative sees it (holding w fixed pulls δ towards views midway
// between reports); L and λ are held from the last linearisation. D = 0 gives [r/√c ; 0] exactly.
struct Whitening {
  Eigen::MatrixXd L;  // 2n × 6
  Eigen::Matrix<double, 6, 1> lambda = Eigen::Matrix<double, 6, 1>::Zero();
  double c = 1, inv_sqrt_c = 1;
};

Whitening MakeWhitening(const Eigen::MatrixXd& J_e, const Eigen::Vector3d& theta) {
  Eigen::Matrix<double, 6, 1> d;
  d << Eigen::Vector3d::Constant(std::sqrt(theta[1])), Eigen::Vector3d::Constant(std::sqrt(theta[2]));
  const Eigen::MatrixXd JD = J_e * d.asDiagonal();
  // geometry/linalg.cc's dynamic eigen-solver gives the fixed 6 × 6 one's values and vectors bit for
  // bit (5,000 random whitenings, docs/performance.md stop 36); V stays a fixed 6 × 6 because JD
  // times a dynamic V takes Eigen's other product kernel and rounds L differently.
  const SymmetricEigen eigen = DecomposeSymmetric((JD.transpose() * JD).eval());
  const Eigen::Matrix<double, 6, 6> V = eigen.vectors;
  Whitening w;
  w.L = JD * V;
  w.lambda = eigen.values.cwiseMax(0.0);
  w.c = theta[0];
  w.inv_sqrt_c = 1 / std::sqrt(theta[0]);
  return w;
}

// Whitens a frame's residuals r (2n, then 6 more slots) at weight w: the struct's formula.
template <typename T>
void Whiten(const Whitening& W, const T& w, T* r) {
  const Eigen::Index n = W.L.rows();
  T g[6];
  for (int j = 0; j < 6; ++j) {
    using std::sqrt;
    T l = T(0);
    for (Eigen::Index k = 0; k < n; ++k) l += W.L(k, j) * r[k];
    const T den = T(W.c) + w * W.lambda[j];
    g[j] = w / den * l;
    r[n + j] = sqrt(w) * l / den;
  }
  for (Eigen::Index k = 0; k < n; ++k) {
    T v = r[k];
    for (int j = 0; j < 6; ++j) v -= W.L(k, j) * g[j];
    r[k] = v * W.inv_sqrt_c;
  }
}

// δ instrumented (docs/math/handeye.md#delta-instrumented): the tracker's pose at t + δ taken as
// the polyline's at t + δ₀ moved along the smoothed velocity ν̄ by δ − δ₀, and the weight held at
// w(s(δ₀)). δ's score is then Σ_f ν̄_fᵀJₑᵀC_f⁻¹r_f: the slope in it is the smoothed one, not the two
// reports', so neither the noisy slope's excess nor w's curvature enters; δ₀ follows δ̂ to a fixed point.
struct Instrument {
  double delta0 = 0, w0 = 1;
  Eigen::Matrix<double, 6, 1> velocity = Eigen::Matrix<double, 6, 1>::Zero();
};

struct FrameCost {
  const Chain* chain;
  const Frame* frame;
  const Whitening* whitening;  // null: the tracker's poses exact, residuals in px
  const Instrument* instrument = nullptr;  // with whitening: δ instrumented

  template <typename T>
  bool operator()(T const* const* blocks, T* r) const {
    if (instrument) {
      T e[6];
      for (int i = 0; i < 6; ++i) e[i] = T(instrument->velocity[i]) * (blocks[2][0] - T(instrument->delta0));
      if (!FrameResiduals<T>(*chain, *frame, blocks[0], blocks[1], T(instrument->delta0), e, r)) return false;
      Whiten<T>(*whitening, T(instrument->w0), r);
      return true;
    }
    if (!FrameResiduals<T>(*chain, *frame, blocks[0], blocks[1], blocks[2][0], nullptr, r)) return false;
    if (!whitening) return true;
    Whiten<T>(*whitening, InterpolationWeightAt<T>(chain->log, T(frame->time) + blocks[2][0]), r);
    return true;
  }
};

// The frame's residuals with the tracker pose's error as a fourth block: its Jacobians Jₑ (and J_g).
struct PoseErrorCost {
  const Chain* chain;
  const Frame* frame;

  template <typename T>
  bool operator()(T const* const* blocks, T* r) const {
    return FrameResiduals<T>(*chain, *frame, blocks[0], blocks[1], blocks[2][0], blocks[3], r);
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


// A frame's corner residuals (px) and their Jacobians at the solution (references there, tangents
// zero): J_g with respect to (x, z, δ), 2n × 13, and J_e with respect to the tracker pose's error,
// 2n × 6 — the linearisation the tracker's noise model and the whitening hold.
struct Linearisation {
  Eigen::VectorXd r;
  Eigen::MatrixXd J_g, J_e;
};

Linearisation Linearise(const Chain& chain, const Frame& frame, double delta) {
  const double zero6[6] = {0, 0, 0, 0, 0, 0};
  ceres::DynamicAutoDiffCostFunction<PoseErrorCost, 19> cost(new PoseErrorCost{&chain, &frame});
  for (int size : {6, 6, 1, 6}) cost.AddParameterBlock(size);
  const auto n = static_cast<Eigen::Index>(frame.Residuals());
  cost.SetNumResiduals(static_cast<int>(n));
  Linearisation out;
  out.r.resize(n);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jx(n, 6), jz(n, 6), jd(n, 1), je(n, 6);
  const double* parameters[] = {zero6, zero6, &delta, zero6};
  double* jacobians[] = {jx.data(), jz.data(), jd.data(), je.data()};
  VSTCAL_CHECK(cost.Evaluate(parameters, out.r.data(), jacobians), "a frame's residuals at the solution cannot be evaluated");
  out.J_g.resize(n, 13);
  out.J_g << jx, jz, jd;
  out.J_e = je;
  return out;
}

// One maximum-likelihood solve over `frames` from the given start: fills X, Z, δ, the fit and the
// covariance of `out`, and returns each view's residuals (px) at the solution. With `whitening`
// (one per frame) the frames are weighed by the tracker's noise and the covariance is (J̃ᵀJ̃)⁻¹ of
// the whitened residuals; without, the tracker is exact and it is σ̂²(JᵀJ)⁻¹. With `linearisation`,
// each frame's at the solution (for the next round of the noise estimate; one pass gives both it
// and the covariance).
std::vector<std::vector<Eigen::Vector2d>> Refine(Chain* chain, const std::vector<Frame>& frames, const std::vector<Whitening>* whitening,
                                                 const Rigid3d& x_start, const Rigid3d& z_start, double delta_start,
                                                 const HandEyeOptions& options, HandEyeSolution* out,
                                                 std::vector<Linearisation>* linearisation = nullptr,
                                                 const std::vector<Instrument>* instruments = nullptr) {
  // The whitened cost's Jacobian carries w(δ)'s derivative; the covariance needs w held (below).
  VSTCAL_CHECK(!whitening || linearisation, "a weighted solve takes its covariance from the frames' linearisation");
  // X, Z as left perturbations of their starts, δ absolute.
  chain->x0 = x_start;
  chain->z0 = z_start;
  double x[6] = {0, 0, 0, 0, 0, 0}, z[6] = {0, 0, 0, 0, 0, 0}, delta = delta_start;
  ceres::Problem problem;
  std::vector<ceres::CostFunction*> costs;
  out->corners = out->views = out->right_views = out->right_corners = 0;
  for (size_t f = 0; f < frames.size(); ++f) {
    const Frame& frame = frames[f];
    const Whitening* w = whitening ? &(*whitening)[f] : nullptr;
    auto* functor = new FrameCost{chain, &frame, w, instruments ? &(*instruments)[f] : nullptr};
    auto* cost = new ceres::DynamicAutoDiffCostFunction<FrameCost, 13>(functor);
    cost->AddParameterBlock(6);
    cost->AddParameterBlock(6);
    cost->AddParameterBlock(1);
    cost->SetNumResiduals(static_cast<int>(frame.Residuals() + (w ? 6 : 0)));
    problem.AddResidualBlock(cost, nullptr, {x, z, &delta});
    costs.push_back(cost);
    for (const SolveView& v : frame.views) {
      ++out->views;
      out->corners += v.view->observations.size();
      if (v.right_from_left) {
        ++out->right_views;
        out->right_corners += v.view->observations.size();
      }
    }
  }
  ceres::Solver::Options solver;
  solver.max_num_iterations = options.max_iterations;
  // 13 unknowns over ~10⁵ residuals: the 13 × 13 normal equations, not a QR of the tall Jacobian
  // (which Ceres copies each iteration); the same minimum to the solver's tolerances.
  solver.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  solver.num_threads = 1;
  solver.function_tolerance = 1e-12;
  solver.parameter_tolerance = 1e-12;
  // With the tracker's noise weighed in, w(s(δ)) makes Gauss–Newton's curvature in δ too large (it
  // lacks −ẅ rᵀC⁻¹KC⁻¹r, which cancels the noisy slope's excess: docs/math/handeye.md#delta-likelihood),
  // so the last steps shrink only by about ⅔ an iteration; stopping at a relative change of 1e-10
  // moved the tests' mean δ̂ by ≤ 2 % of its σ and saves a third of the iterations (31 → 21 at 1,000
  // noisy views). D = 0: the model is exact and the tolerance as before.
  if (whitening && std::any_of(whitening->begin(), whitening->end(), [](const Whitening& w) { return !w.lambda.isZero(0); })) {
    solver.function_tolerance = 1e-10;
  }
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  out->iterations += static_cast<int>(summary.iterations.size());
  out->hmd_from_camera = PerturbLeft(chain->x0, Eigen::Vector3d(x[0], x[1], x[2]), Eigen::Vector3d(x[3], x[4], x[5]));
  out->tracker_from_board = PerturbLeft(chain->z0, Eigen::Vector3d(z[0], z[1], z[2]), Eigen::Vector3d(z[3], z[4], z[5]));
  out->time_offset = delta;

  // The covariance at the solution: references moved there, tangents zero, JᵀJ summed frame by
  // frame (each frame's Jacobian is 13 columns of its own rows: no Jacobian of all residuals).
  chain->x0 = out->hmd_from_camera;
  chain->z0 = out->tracker_from_board;
  std::fill(std::begin(x), std::end(x), 0.0);
  std::fill(std::begin(z), std::end(z), 0.0);
  Eigen::Matrix<double, 13, 13> information = Eigen::Matrix<double, 13, 13>::Zero();
  double score_excess = 0;  // whitened only: N
  if (linearisation) linearisation->clear();
  // Each view's residuals in px (unwhitened), and the fit from them.
  std::vector<std::vector<Eigen::Vector2d>> per_view;
  double sum = 0;
  for (size_t f = 0; f < frames.size(); ++f) {
    const Frame& frame = frames[f];
    Eigen::VectorXd r;
    if (linearisation) {
      // Unwhitened residuals and Jacobians (J_e too); the whitening applied to J_g here.
      Linearisation lin = Linearise(*chain, frame, delta);
      if (whitening) {
        // The whitened J_g at w(δ̂) held: J̄ᵀC⁻¹J̄ but for δ's column, the noisy slope's (below).
        const Whitening& W = (*whitening)[f];
        const double tau = frame.time + delta;
        const size_t k = ReportInterval(chain->log, tau);
        const double dt = chain->log[k + 1].time - chain->log[k].time;
        const double s = std::clamp((tau - chain->log[k].time) / dt, 0.0, 1.0);
        const double w = InterpolationWeight(s), beta = (2 * s - 1) / w;
        // δ's column the true velocity's, j̄ = Jₑ ν̄ (the noisy slope's excess is not information);
        // with D = 0 the reports are exact and their slope is it.
        Eigen::MatrixXd J_bar = lin.J_g;
        if (!W.lambda.isZero(0)) J_bar.col(12) = lin.J_e * SmoothedVelocity(chain->log, k);
        const Eigen::Matrix<double, 6, 1> den = (W.c + w * W.lambda.array()).matrix();
        const Eigen::Matrix<double, 6, 13> Lg = W.L.transpose() * J_bar;
        const Eigen::Matrix<double, 6, 13> G = (w / den.array()).matrix().asDiagonal() * Lg;
        const Eigen::MatrixXd P = (J_bar - W.L * G) * W.inv_sqrt_c;
        const Eigen::Matrix<double, 6, 13> E = (std::sqrt(w) / den.array()).matrix().asDiagonal() * Lg;
        information.noalias() += P.transpose() * P + E.transpose() * E;
        // docs/math/handeye.md#delta-likelihood: the score's excess variance N.
        score_excess += (W.lambda.array() / (w * den.array()) + beta * beta * w * W.c * W.lambda.array() / den.array().square()).sum() / (dt * dt);
      } else {
        information.noalias() += lin.J_g.transpose() * lin.J_g;
      }
      r = lin.r;
      linearisation->push_back(std::move(lin));
    } else {
      const auto rows = static_cast<Eigen::Index>(costs[f]->num_residuals());
      Eigen::VectorXd rw(rows);
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jx(rows, 6), jz(rows, 6), jd(rows, 1);
      const double* parameters[] = {x, z, &delta};
      double* jacobians[] = {jx.data(), jz.data(), jd.data()};
      VSTCAL_CHECK(costs[f]->Evaluate(parameters, rw.data(), jacobians), "a frame's residuals at the solution cannot be evaluated");
      Eigen::MatrixXd J(rows, 13);
      J << jx, jz, jd;
      information.noalias() += J.transpose() * J;
      r.resize(static_cast<Eigen::Index>(frame.Residuals()));
      const bool ok = FrameResiduals<double>(*chain, frame, x, z, delta, nullptr, r.data());
      VSTCAL_CHECK(ok, "a frame's residuals at the solution cannot be evaluated");
    }
    Eigen::Index at = 0;
    for (const SolveView& v : frame.views) {
      std::vector<Eigen::Vector2d> pixels;
      for (size_t i = 0; i < v.view->observations.size(); ++i, at += 2) {
        pixels.emplace_back(r[at], r[at + 1]);
        sum += r[at] * r[at] + r[at + 1] * r[at + 1];
      }
      per_view.push_back(std::move(pixels));
    }
  }
  const double residuals = 2.0 * static_cast<double>(out->corners);
  out->rms_px = std::sqrt(sum / residuals);
  out->sigma_px = residuals > kHandEyeParameters ? std::sqrt(sum / (residuals - kHandEyeParameters)) : 0.0;
  if (!whitening) {
    out->covariance = out->sigma_px * out->sigma_px * information.inverse();
    return per_view;
  }
  // Whitened, the residuals are in units of their σ's (estimated): no σ̂² factor. The profile
  // likelihood's sandwich (docs/math/handeye.md#delta-likelihood): Ī⁻¹ + N (Ī⁻¹e_δ)(Ī⁻¹e_δ)ᵀ, Ī the
  // information with δ's column the true velocity's. D = 0: N = 0 and Ī = J̃ᵀJ̃.
  const Eigen::Matrix<double, 13, 13> inverse = information.inverse();
  const Eigen::Matrix<double, 13, 1> u = inverse.col(12);
  // Instrumented, δ's score holds no noisy slope: its variance is Ī's, and the covariance Ī⁻¹.
  out->covariance = instruments ? Eigen::Matrix<double, 13, 13>(inverse) : Eigen::Matrix<double, 13, 13>(inverse + score_excess * u * u.transpose());
  out->slope_excess = score_excess * inverse(12, 12);
  return per_view;
}

// The most fixed-point steps of the instrumented δ a weighted solve takes.
constexpr int kMaxInstrumentSteps = 8;

// A σ from its variance's estimate v and standard error: σ = √v, σ(σ) = se/(2√v) (first order),
// the 95 % interval that of v (Wald) taken through the square root, clamped at 0.
EstimatedSigma SigmaOf(double v, double se) {
  EstimatedSigma s;
  s.sigma = std::sqrt(std::max(v, 0.0));
  s.sigma_sigma = s.sigma > 0 ? se / (2 * s.sigma) : std::sqrt(se);
  s.lower = std::sqrt(std::max(v - 1.96 * se, 0.0));
  s.upper = std::sqrt(std::max(v + 1.96 * se, 0.0));
  return s;
}

// The tracker's noise estimated with X, Z and δ (docs/math/handeye.md#tracker-noise): at the
// current solution each frame's Jacobians give the variance components' REML estimate; the frames
// are then weighed by it (Whitening) and solved again, until the σ's settle (1 %).
void EstimateTrackerNoiseJointly(Chain* chain, const std::vector<Frame>& frames, const HandEyeOptions& options, HandEyeSolution* out,
                                 std::vector<Linearisation> linearisation) {
  Eigen::Vector3d theta(out->sigma_px * out->sigma_px, 0, 0);
  bool have_theta = false;
  VarianceComponents components;
  JointTrackerNoise noise;
  noise.frames = frames.size();
  // Every frame's residuals and Jacobians at the solution; after each weighted solve, that solve's.
  chain->x0 = out->hmd_from_camera;
  chain->z0 = out->tracker_from_board;
  if (linearisation.empty()) {
    for (const Frame& frame : frames) linearisation.push_back(Linearise(*chain, frame, out->time_offset));
  }
  bool instrument_settled = true;  // the last weighted solve's fixed point
  for (int round = 1; round <= 4; ++round) {
    std::vector<NoiseFrame> reduced;
    for (size_t f = 0; f < frames.size(); ++f) {
      const Linearisation& lin = linearisation[f];
      const double s = InterpolationFraction(chain->log, frames[f].time + out->time_offset);
      reduced.push_back(ReduceNoiseFrame(lin.J_e, lin.J_g, lin.r, InterpolationWeight(s)));
    }
    if (!have_theta) theta = MomentStart(reduced);
    const Eigen::Vector3d previous = theta;
    components = EstimateVarianceComponents(reduced, theta);
    if (!components.converged) {
      out->warnings.push_back("the tracker's noise could not be estimated jointly (the likelihood has no maximum in reach); its poses were taken as exact");
      return;
    }
    theta = components.theta;
    // Settled when no variance moved by a tenth of its standard error since the last weighing: the
    // solution and covariance of that weighing stand.
    const Eigen::Vector3d se_v = components.covariance.diagonal().cwiseMax(0).cwiseSqrt();
    if (have_theta && ((theta - previous).cwiseAbs().array() <= 0.1 * se_v.array()).all()) break;
    have_theta = true;
    noise.rounds = round;
    // The frames weighed by the noise, solved again from where they are.
    // (With instrumented_offset false each frame's weight w follows δ inside the cost; instrumented,
    // it is held at the last δ̂ and δ solves the instrumented equation.)
    std::vector<Whitening> whitening;
    for (size_t f = 0; f < frames.size(); ++f) whitening.push_back(MakeWhitening(linearisation[f].J_e, theta));
    if (!options.instrumented_offset) {
      Refine(chain, frames, &whitening, out->hmd_from_camera, out->tracker_from_board, out->time_offset, options, out, &linearisation);
      continue;
    }
    // The fixed point δ̂(δ₀) = δ₀, to a hundredth of δ's σ. δ̂(δ₀) is close to linear in δ₀ with a
    // slope b of a few tenths (the noisy slopes' relative error over the views), so δ₀ ← δ̂ would
    // contract; but a noisy tracker and few views put b near or past ±1, where that stalls or
    // swings. So after the first step δ₀ takes the secant's root of g(δ₀) = δ̂(δ₀) − δ₀, exact for a
    // linear δ̂, with the plain step when the secant would jump more than 3σ.
    bool settled = false;
    double d0 = out->time_offset, previous_d0 = 0, previous_g = 0;
    for (int step = 0; step < kMaxInstrumentSteps && !settled; ++step) {
      std::vector<Instrument> instruments;
      for (const Frame& frame : frames) {
        const double tau = frame.time + d0;
        const double s = InterpolationFraction(chain->log, tau);
        instruments.push_back({d0, InterpolationWeight(s), SmoothedVelocity(chain->log, ReportInterval(chain->log, tau))});
      }
      Refine(chain, frames, &whitening, out->hmd_from_camera, out->tracker_from_board, d0, options, out, &linearisation, &instruments);
      const double sigma = std::sqrt(out->covariance(12, 12)), g = out->time_offset - d0;
      settled = std::abs(g) <= 0.01 * sigma;
      double next = out->time_offset;
      if (step > 0 && g != previous_g) {
        const double secant = d0 - g * (d0 - previous_d0) / (g - previous_g);
        if (std::abs(secant - d0) <= 3 * sigma) next = secant;
      }
      previous_d0 = d0;
      previous_g = g;
      d0 = next;
    }
    instrument_settled = settled;
  }
  if (!instrument_settled) {
    out->warnings.push_back("the time offset's instrumented estimate had not settled after " + std::to_string(kMaxInstrumentSteps) +
                            " steps (it still moved by more than 1 % of its σ a step): the motion may be too slow or too uneven for "
                            "the tracker's noise; record a faster, smoother motion");
  }
  const Eigen::Vector3d se = components.covariance.diagonal().cwiseMax(0).cwiseSqrt();
  noise.corner_px = SigmaOf(theta[0], se[0]);
  if (components.corner_variance_at_floor) {
    // At its bound the corners' σ is an upper limit, not an estimate.
    noise.corner_px.lower = 0;
    out->warnings.push_back("the corners' noise estimate reached its floor of " + MessageNumber(std::sqrt(kMinCornerVariance)) +
                            " px (noise-free corners, as a synthetic recording without pixel noise has): the tracker's noise is estimated "
                            "with the corners' held there");
  }
  noise.rotation = SigmaOf(theta[1], se[1]);
  noise.translation = SigmaOf(theta[2], se[2]);
  // The σ's join the covariance, uncorrelated with X, Z and δ (the struct's comment says why).
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(kHandEyeParameters + 2, kHandEyeParameters + 2);
  covariance.topLeftCorner<kHandEyeParameters, kHandEyeParameters>() = out->covariance;
  // Var σ = Var v / (4 v), with the covariance of the two variances' estimates likewise.
  const double ja = noise.rotation.sigma > 0 ? 1 / (2 * noise.rotation.sigma) : 0, jb = noise.translation.sigma > 0 ? 1 / (2 * noise.translation.sigma) : 0;
  covariance(13, 13) = noise.rotation.sigma_sigma * noise.rotation.sigma_sigma;
  covariance(14, 14) = noise.translation.sigma_sigma * noise.translation.sigma_sigma;
  covariance(13, 14) = covariance(14, 13) = ja * jb * components.covariance(1, 2);
  out->covariance = std::move(covariance);
  out->tracker_noise = noise;
}

// The bad-frame test with the tracker exact: every view against the others' corner noise
// (estimators/view_rejection.h; each view's dof less its share of the 13 parameters).
RejectionTest TestViewsExactTracker(const std::vector<SolveView>& active, const std::vector<std::vector<Eigen::Vector2d>>& residuals,
                                    const HandEyeOptions& options) {
  Correspondences c;
  Fit fit;
  for (size_t k = 0; k < active.size(); ++k) {
    c.views.push_back(View{active[k].view->name, "", std::nullopt, active[k].view->observations, std::nullopt});
    fit.views.push_back(ViewFit{active[k].view->name, {}, residuals[k]});
  }
  return TestResiduals(c, fit, kHandEyeParameters, 0, options.rejection);
}

// The bad-frame test under the full noise model (frame_test.h): every view alone, its residuals
// against the corners' noise and the tracker's at its time, the noise estimated from the views that
// pass. Falls back to the exact-tracker test when the noise cannot be estimated. Fills each view's
// linearisation (for the noise estimate that follows when no view is dropped).
RejectionTest TestViewsAgainstNoise(const Chain& chain, double delta, const std::vector<Frame>& views_alone,
                                    const std::vector<std::vector<Eigen::Vector2d>>& residuals, const HandEyeOptions& options,
                                    std::vector<Linearisation>* linearisation) {
  RejectionTest t;
  std::vector<NoiseFrame> reduced;
  for (const Frame& frame : views_alone) {
    linearisation->push_back(Linearise(chain, frame, delta));
    const Linearisation& lin = linearisation->back();
    const double s = InterpolationFraction(chain.log, frame.time + delta);
    reduced.push_back(ReduceNoiseFrame(lin.J_e, lin.J_g, lin.r, InterpolationWeight(s)));
  }
  if (views_alone.size() < kMinViewsToTest) return t;
  const FrameNoiseTest test = TestFramesAgainstNoise(reduced, options.rejection.view_false_alarm);
  if (!test.ok) {
    std::vector<SolveView> active;
    for (const Frame& f : views_alone) active.push_back(f.views.front());
    return TestViewsExactTracker(active, residuals, options);
  }
  t.sigma_px = std::sqrt(test.theta[0]);
  double worst = 1;
  for (size_t v = 0; v < views_alone.size(); ++v) {
    double sum = 0;
    for (const Eigen::Vector2d& r : residuals[v]) sum += r.squaredNorm();
    const double rms = std::sqrt(sum / static_cast<double>(std::max<size_t>(1, residuals[v].size())));
    t.view_rms_px.push_back(rms);
    // The statistics are quadratic in the residuals: the RMS at which this view would sit on its
    // threshold.
    t.view_threshold_px.push_back(rms / std::sqrt(std::max(test.excess[v], 1e-300)));
    if (test.excess[v] > worst) worst = test.excess[v], t.worst_view = v;
  }
  return t;
}

}  // namespace

Eigen::MatrixXd FitReportsQuadratic(std::span<const TrackedPose> log, size_t first, size_t count, const Rigid3d& at, double t0) {
  Eigen::MatrixXd A(count, 3), Y(count, 6);
  for (size_t m = 0; m < count; ++m) {
    const TrackedPose& p = log[first + m];
    const double t = p.time - t0;
    A.row(static_cast<Eigen::Index>(m)) << 1, t, t * t;
    Y.row(static_cast<Eigen::Index>(m)) << RotvecFromRotation(p.tracker_from_hmd.R * at.R.transpose()).transpose(), p.tracker_from_hmd.t.transpose();
  }
  return SolveLeastSquares(A, Y);
}

std::vector<Eigen::Vector3d> LogSteps(std::span<const TrackedPose> log) {
  std::vector<Eigen::Vector3d> steps;
  for (size_t k = 0; k + 1 < log.size(); ++k) {
    steps.push_back(RotvecFromRotation(log[k].tracker_from_hmd.R.transpose() * log[k + 1].tracker_from_hmd.R));
  }
  return steps;
}

HandEyeSolution SolveHandEye(const Camera& camera, std::span<const TrackedPose> log, std::span<const TimedView> views,
                             const HandEyeOptions& options, const HandEyeRig* rig) {
  CheckLog(log);
  const std::vector<Eigen::Vector3d> steps = LogSteps(log);
  const auto check_span = [&](const TimedView& v, const char* camera_name) {
    if (!(v.time >= log.front().time && v.time <= log.back().time)) {
      throw InputError(std::string(camera_name) + "view \"" + v.name + "\": time " + std::to_string(v.time) + " s is outside the tracker's log (" +
                       std::to_string(log.front().time) + " … " + std::to_string(log.back().time) + " s); drop the view or record longer");
    }
  };
  for (const TimedView& v : views) check_span(v, "");
  if (rig) {
    for (const TimedView& v : rig->views) check_span(v, "right camera's ");
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
  std::vector<SolveView> active;
  for (size_t k = 0; k < views.size(); ++k) active.push_back({&views[k], &camera, nullptr, k});
  if (rig) {
    for (size_t k = 0; k < rig->views.size(); ++k) active.push_back({&rig->views[k], &rig->right, &rig->right_from_left, views.size() + k});
  }
  Rigid3d x_start = out.start.hmd_from_camera, z_start = out.start.tracker_from_board;
  double delta_start = out.start_time_offset;
  Chain chain{log, steps, x_start, z_start};
  // The bad-frame test weighs every view alone, the tracker exact: one frame a view.
  const auto one_frame_a_view = [&] {
    std::vector<Frame> frames;
    for (const SolveView& v : active) frames.push_back({v.view->time, {v}});
    return frames;
  };
  // Each view's linearisation at the last solve, when the noise test took it: the noise estimate
  // below starts from it when its frames are the views.
  std::vector<Linearisation> view_linearisation;
  for (int round = 1;; ++round) {
    view_linearisation.clear();
    const std::vector<Frame> views_alone = one_frame_a_view();
    const std::vector<std::vector<Eigen::Vector2d>> residuals = Refine(&chain, views_alone, nullptr, x_start, z_start, delta_start, options, &out);
    if (!options.rejection.enabled || round > options.rejection.max_rounds) break;
    const RejectionTest test = options.estimate_tracker_noise ? TestViewsAgainstNoise(chain, out.time_offset, views_alone, residuals, options, &view_linearisation)
                                                              : TestViewsExactTracker(active, residuals, options);
    if (!test.worst_view) break;
    std::vector<double> rms = test.view_rms_px;
    std::nth_element(rms.begin(), rms.begin() + static_cast<long>(rms.size() / 2), rms.end());
    if (test.view_rms_px[*test.worst_view] < options.min_rms_ratio * rms[rms.size() / 2]) break;
    if (active.size() <= kMinHandEyeSamples) {
      out.warnings.push_back("view \"" + active[*test.worst_view].view->name + "\" is inconsistent with the others (RMS " +
                             MessageNumber(test.view_rms_px[*test.worst_view]) + " px, threshold " +
                             MessageNumber(test.view_threshold_px[*test.worst_view]) + " px) but only " + std::to_string(active.size()) +
                             " views remain; kept. Record more views");
      break;
    }
    const size_t worst = *test.worst_view;
    Rejection r;
    r.kind = Rejection::Kind::kView;
    r.round = round;
    r.view = active[worst].index;
    r.view_name = active[worst].view->name;
    r.rms_px = test.view_rms_px[worst];
    r.threshold_px = test.view_threshold_px[worst];
    r.because = options.estimate_tracker_noise
                    ? "its corners are inconsistent with the noise of the corners (σ̂ " + MessageNumber(test.sigma_px) +
                          " px) and of the tracker the other views show: a tracker glitch, a smeared or mislabelled board, or a pose log out of step at that time"
                    : "its corners are inconsistent with the other views' noise (σ̂ " + MessageNumber(test.sigma_px) +
                          " px): a tracker glitch, a smeared or mislabelled board, or a pose log out of step at that time";
    out.rejected.push_back(std::move(r));
    active.erase(active.begin() + static_cast<long>(worst));
    x_start = out.hmd_from_camera;
    z_start = out.tracker_from_board;
    delta_start = out.time_offset;
  }
  out.names = HandEyeCovarianceNames();
  if (rig) out.right_from_left = rig->right_from_left;
  if (options.estimate_tracker_noise) {
    // The frames: views of one instant share the tracker's error there (a rig's pairs).
    std::vector<SolveView> by_time = active;
    std::stable_sort(by_time.begin(), by_time.end(), [](const SolveView& a, const SolveView& b) { return a.view->time < b.view->time; });
    std::vector<Frame> frames;
    for (const SolveView& v : by_time) {
      if (!frames.empty() && std::abs(v.view->time - frames.back().time) <= kSameInstant) {
        frames.back().views.push_back(v);
      } else {
        frames.push_back({v.view->time, {v}});
      }
    }
    // The views' linearisation from the last test serves when the frames are the views, in order.
    bool same = !view_linearisation.empty() && frames.size() == active.size();
    for (size_t f = 0; same && f < frames.size(); ++f) same = frames[f].views.size() == 1 && frames[f].views[0].index == active[f].index;
    if (!same) view_linearisation.clear();
    EstimateTrackerNoiseJointly(&chain, frames, options, &out, std::move(view_linearisation));
    if (out.tracker_noise) {
      out.names.insert(out.names.end(), HandEyeNoiseCovarianceNames().begin(), HandEyeNoiseCovarianceNames().end());
    }
  }
  std::vector<double> times;
  for (const SolveView& v : active) times.push_back(v.view->time);
  out.report_phases = ViewReportPhases(log, times, out.time_offset);
  return out;
}

}  // namespace vstcal
