#include "vstcal/handeye/bootstrap.h"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "vstcal/core/error.h"
#include "vstcal/core/parallel.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

// The motion the replicates share: each report replaced by a quadratic fit of the eleven around it
// (k − 5 … k + 5, shifted inside the log) evaluated at its time — the rotation as log(R_m R_kᵀ),
// the translation per component. The reports themselves would not do: their noise is in them
// already, and fresh noise on top doubles the noise of the slope between two reports, which is
// the information on δ (the headset's velocity): with the raw reports the bootstrap's σ_δ came out
// half the spread (docs/math/handeye.md#delta-bootstrap).
std::vector<TrackedPose> SmoothedMotion(std::span<const TrackedPose> log) {
  constexpr size_t kReports = 11;
  std::vector<TrackedPose> out(log.begin(), log.end());
  const size_t count = std::min(kReports, log.size());
  if (count < 3) return out;
  for (size_t k = 0; k < log.size(); ++k) {
    const size_t first = std::min(k >= kReports / 2 ? k - kReports / 2 : 0, log.size() - count);
    const Rigid3d& at = log[k].tracker_from_hmd;
    const Eigen::MatrixXd c = FitReportsQuadratic(log, first, count, at, log[k].time);
    out[k].tracker_from_hmd.R = RotationFromRotvec(Eigen::Vector3d(c.row(0).head<3>().transpose())) * at.R;
    out[k].tracker_from_hmd.t = c.row(0).tail<3>().transpose();
  }
  return out;
}

// Stream words of the replicates' draws (CounterRng): tracker reports, left corners, right corners.
constexpr uint32_t kTrackerStream = 0x42540001, kLeftStream = 0x42540002, kRightStream = 0x42540003;

}  // namespace

HandEyeBootstrap BootstrapHandEye(const Camera& camera, std::span<const TrackedPose> log, std::span<const TimedView> views,
                                  const HandEyeSolution& solution, const HandEyeOptions& options,
                                  const HandEyeBootstrapOptions& bootstrap, const HandEyeRig* rig) {
  if (bootstrap.replicates < 2) throw InputError("bootstrap replicates: " + std::to_string(bootstrap.replicates) + " — at least 2 are needed for a spread");
  // The views the solution kept (rejections index the left views, then the right).
  std::vector<bool> dropped(views.size() + (rig ? rig->views.size() : 0), false);
  for (const Rejection& r : solution.rejected) {
    if (r.view < dropped.size()) dropped[r.view] = true;
  }
  std::vector<TimedView> left, right;
  for (size_t k = 0; k < views.size(); ++k) {
    if (!dropped[k]) left.push_back(views[k]);
  }
  if (rig) {
    for (size_t k = 0; k < rig->views.size(); ++k) {
      if (!dropped[views.size() + k]) right.push_back(rig->views[k]);
    }
  }
  const std::vector<TrackedPose> motion = SmoothedMotion(log);
  const std::vector<Eigen::Vector3d> steps = LogSteps(motion);
  double sigma_r = 0, sigma_t = 0, sigma_px = solution.sigma_px;
  if (solution.tracker_noise) {
    sigma_r = solution.tracker_noise->rotation.sigma;
    sigma_t = solution.tracker_noise->translation.sigma;
    sigma_px = solution.tracker_noise->corner_px.sigma;
  }
  // Each view's board pose at the estimate, through the smoothed motion at its time + δ̂.
  const auto camera_from_board = [&](const TimedView& v) {
    const std::optional<Rigid3d> H = InterpolatePose<double>(motion, steps, v.time + solution.time_offset);
    if (!H) throw InputError("view \"" + v.name + "\": its time + the time offset is outside the tracker's log; the bootstrap needs every kept view inside it");
    return Rigid3d(solution.hmd_from_camera.inverse() * H->inverse() * solution.tracker_from_board);
  };
  std::vector<Rigid3d> left_pose, right_pose;
  for (const TimedView& v : left) left_pose.push_back(camera_from_board(v));
  for (const TimedView& v : right) right_pose.push_back(rig->right_from_left * camera_from_board(v));

  HandEyeOptions replicate_options = options;
  replicate_options.rejection.enabled = false;
  const size_t B = static_cast<size_t>(bootstrap.replicates);
  std::vector<std::optional<Eigen::Matrix<double, 13, 1>>> result(B);
  ParallelFor(B, bootstrap.threads, [&](size_t b) {
    const CounterRng tracker_rng(bootstrap.seed, kTrackerStream), left_rng(bootstrap.seed, kLeftStream), right_rng(bootstrap.seed, kRightStream);
    // Index (replicate, item): 2³² items a replicate.
    const uint64_t base = static_cast<uint64_t>(b) << 32;
    std::vector<TrackedPose> replicate_log = motion;
    for (size_t k = 0; k < replicate_log.size(); ++k) {
      const auto a = tracker_rng.Normal2(base + k, 0), c = tracker_rng.Normal2(base + k, 1), d = tracker_rng.Normal2(base + k, 2);
      Rigid3d& H = replicate_log[k].tracker_from_hmd;
      H.R = RotationFromRotvec(Eigen::Vector3d(sigma_r * Eigen::Vector3d(a[0], a[1], c[0]))) * H.R;
      H.t += sigma_t * Eigen::Vector3d(c[1], d[0], d[1]);
    }
    const auto simulate = [&](const std::vector<TimedView>& in, const std::vector<Rigid3d>& pose, const Camera& cam, const CounterRng& rng) {
      std::vector<TimedView> out = in;
      uint64_t item = base;
      for (size_t v = 0; v < out.size(); ++v) {
        std::vector<Observation> kept;
        for (Observation o : out[v].observations) {
          const auto z = rng.Normal2(item++, 0);
          const std::optional<Eigen::Vector2d> q = cam.Project(pose[v] * o.point);
          if (!q) continue;
          o.pixel = *q + sigma_px * Eigen::Vector2d(z[0], z[1]);
          kept.push_back(o);
        }
        out[v].observations = std::move(kept);
      }
      return out;
    };
    const std::vector<TimedView> replicate_left = simulate(left, left_pose, camera, left_rng);
    std::optional<HandEyeRig> replicate_rig;
    if (rig) replicate_rig = HandEyeRig{rig->right, rig->right_from_left, simulate(right, right_pose, rig->right, right_rng)};
    try {
      const HandEyeSolution s = SolveHandEye(camera, replicate_log, replicate_left, replicate_options, replicate_rig ? &*replicate_rig : nullptr);
      Eigen::Matrix<double, 13, 1> g;
      g << LeftPerturbationBetween(solution.hmd_from_camera, s.hmd_from_camera), LeftPerturbationBetween(solution.tracker_from_board, s.tracker_from_board),
          s.time_offset - solution.time_offset;
      result[b] = g;
    } catch (const DegenerateError&) {
      // Left out and counted: a replicate the solver cannot solve says nothing of the spread of
      // those it can.
    }
  });
  HandEyeBootstrap out;
  out.replicates = bootstrap.replicates;
  out.seed = bootstrap.seed;
  out.mean = Eigen::VectorXd::Zero(kHandEyeParameters);
  out.covariance = Eigen::MatrixXd::Zero(kHandEyeParameters, kHandEyeParameters);
  for (const auto& g : result) {
    if (g) {
      out.mean += *g;
      ++out.solved;
    }
  }
  if (out.solved < 2) throw DegenerateError("bootstrap: fewer than 2 of " + std::to_string(out.replicates) + " replicates could be solved; the recording is too weak to bootstrap");
  out.mean /= out.solved;
  for (const auto& g : result) {
    if (g) out.covariance += (*g - out.mean) * (*g - out.mean).transpose();
  }
  out.covariance /= out.solved - 1;
  return out;
}

}  // namespace vstcal
