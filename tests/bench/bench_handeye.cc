// calib-handeye's solve (issue 22 item 7: 1,000 poses × 50 corners ≤ 1 s on one core, linear in the
// poses), beside OpenCV's calibrateHandEye (Park) on the same views' PnP poses and the tracker's
// poses at the true times — OpenCV's closed form only: no corners, no time offset, no covariance.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "support/handeye_scenes.h"
#include "vstcal/estimators/pose_refine.h"
#include "vstcal/handeye/refine.h"

namespace {

void BM_HandEyeSolve(benchmark::State& state) {
  const auto r = vstcal::testing::RecordHandEye(0.03, 0.2, 1, false, static_cast<int>(state.range(0)));
  for (auto _ : state) {
    auto s = vstcal::SolveHandEye(r.camera, r.log, r.views);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

// The same with the tracker's poses taken as exact (no joint noise estimate): the solve before the
// tracker's noise model, to show what the model costs.
void BM_HandEyeSolveTrackerExact(benchmark::State& state) {
  const auto r = vstcal::testing::RecordHandEye(0.03, 0.2, 1, false, static_cast<int>(state.range(0)));
  vstcal::HandEyeOptions options;
  options.estimate_tracker_noise = false;
  for (auto _ : state) {
    auto s = vstcal::SolveHandEye(r.camera, r.log, r.views, options);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

// The same recording with every tracker report noisy (0.05°, 0.2 mm per axis, as
// handeye_noise_test's): the noise σ's are then away from their bound 0, and the weighted solves
// and REML rounds that follow are the ones a real tracker takes. `instrumented` false: the time
// offset minimising the cost, as up to stop 39, beside calib-handeye's instrumented one.
void SolveNoisy(benchmark::State& state, bool instrumented) {
  vstcal::HandEyeSpec spec = vstcal::testing::HandEyeTestSpec(0.03, 0.2, 1);
  spec.tracker_noise_deg = 0.05;
  spec.tracker_noise = 0.2;
  spec.views = static_cast<int>(state.range(0));
  const auto r = vstcal::testing::RecordHandEye(spec);
  vstcal::HandEyeOptions options;
  options.instrumented_offset = instrumented;
  for (auto _ : state) {
    auto s = vstcal::SolveHandEye(r.camera, r.log, r.views, options);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
void BM_HandEyeSolveNoisyTracker(benchmark::State& state) { SolveNoisy(state, true); }
void BM_HandEyeSolveNoisyTrackerCostDelta(benchmark::State& state) { SolveNoisy(state, false); }

void BM_OpenCvCalibrateHandEyePark(benchmark::State& state) {
  const auto r = vstcal::testing::RecordHandEye(0.0, 0.2, 1, false, static_cast<int>(state.range(0)));
  std::vector<cv::Mat> Rg, tg, Rt, tt;
  const std::vector<Eigen::Vector3d> steps = vstcal::LogSteps(r.log);
  for (const auto& v : r.views) {
    std::vector<Eigen::Vector3d> points;
    std::vector<Eigen::Vector2d> pixels;
    for (const auto& o : v.observations) {
      points.push_back(o.point);
      pixels.push_back(o.pixel);
    }
    const auto pose = vstcal::SolvePnp(r.camera, points, pixels).body_from_world;
    const auto H = *vstcal::InterpolatePose(std::span(r.log), std::span(steps), v.time);
    cv::Mat a, b, c, d;
    cv::eigen2cv(H.R, a);
    cv::eigen2cv(H.t, b);
    cv::eigen2cv(pose.R, c);
    cv::eigen2cv(pose.t, d);
    Rg.push_back(a);
    tg.push_back(b);
    Rt.push_back(c);
    tt.push_back(d);
  }
  for (auto _ : state) {
    cv::Mat R, t;
    cv::calibrateHandEye(Rg, tg, Rt, tt, R, t, cv::CALIB_HAND_EYE_PARK);
    benchmark::DoNotOptimize(R);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK(BM_HandEyeSolve)->Arg(30)->Arg(250)->Arg(500)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HandEyeSolveTrackerExact)->Arg(30)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HandEyeSolveNoisyTracker)->Arg(250)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HandEyeSolveNoisyTrackerCostDelta)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvCalibrateHandEyePark)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
