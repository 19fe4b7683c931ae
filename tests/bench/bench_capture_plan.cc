// calib-capture plan (lib/vstcal/capture/plan.h): the whole plan — geometry of every position and
// the predicted σ's and test-point uncertainty — beside its peer, one refinement of the same
// planned corners (calib/refine.h): the Monte Carlo alternative needs ~200 of those for a σ good
// to ±5 %, the prediction needs none. Volumes of 3 … 41 template positions, planar views 10 … 200.
#include <benchmark/benchmark.h>

#include "vstcal/calib/refine.h"
#include "vstcal/capture/plan.h"

namespace {

using namespace vstcal;

PlanRequest Request(Rig rig, int positions) {
  PlanRequest r;
  r.camera = Camera::FromK((Eigen::Matrix3d() << 1400, 0, 639.5, 0, 1400, 511.5, 0, 0, 1).finished(), ImageSize{1280, 1024});
  r.target.cols = 13;
  r.target.rows = 9;
  r.target.square_size = 100;
  r.target.margin = 100;
  r.rig = rig;
  r.volume.near = 0;
  r.volume.far = 2000;
  r.volume.interval = 2000.0 / (positions - 1);
  r.volume.camera_distance = 3000;
  r.volume.tilt_deg = 20;
  r.views.num_views = positions;
  r.views.distance = 4000;
  r.test_points = {{"Middle", Eigen::Vector3d(0, 0, 1000), std::nullopt}};
  if (rig == Rig::kPlanarViews) r.test_points.clear();
  r.pixel_points = {Eigen::Vector3d(100, 100, 4000)};
  return r;
}

void BM_PlanVolume(benchmark::State& state) {
  const PlanRequest r = Request(Rig::kVolume, static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(PlanCapture(r));
}
BENCHMARK(BM_PlanVolume)->Arg(3)->Arg(11)->Arg(41)->Unit(benchmark::kMillisecond);

void BM_PlanViews(benchmark::State& state) {
  const PlanRequest r = Request(Rig::kPlanarViews, static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(PlanCapture(r));
}
BENCHMARK(BM_PlanViews)->Arg(10)->Arg(50)->Arg(200)->Unit(benchmark::kMillisecond);

// The peer: one refinement of the same corners (noise-free, started at the truth: its cheapest case).
void BM_OneRefinementVolume(benchmark::State& state) {
  const PlanRequest r = Request(Rig::kVolume, static_cast<int>(state.range(0)));
  const CapturePlan plan = PlanCapture(r);
  for (auto _ : state) benchmark::DoNotOptimize(Refine(plan.corners, r.camera, plan.poses, r.options));
}
BENCHMARK(BM_OneRefinementVolume)->Arg(3)->Arg(11)->Arg(41)->Unit(benchmark::kMillisecond);

void BM_OneRefinementViews(benchmark::State& state) {
  const PlanRequest r = Request(Rig::kPlanarViews, static_cast<int>(state.range(0)));
  const CapturePlan plan = PlanCapture(r);
  for (auto _ : state) benchmark::DoNotOptimize(Refine(plan.corners, r.camera, plan.poses, r.options));
}
BENCHMARK(BM_OneRefinementViews)->Arg(10)->Arg(50)->Arg(200)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
