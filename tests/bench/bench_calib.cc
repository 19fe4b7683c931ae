// Calibration solvers (issue 3 targets, 600 points: Tsai including its nonlinear stage < 1 ms,
// full refinement from a DLT start < 3 ms), with OpenCV's calibrateCamera on the same data as the
// peer, and the three solvers of seed 000's comparison on the shipped distorted seed-000 volume.
// Planar views at scale (issue 10: 50 … 2,000 views of a 10×7 board, 1280×720): the whole solve
// with its covariance, beside OpenCV's calibrateCamera and the dense covariance it replaced
// (tests/support/dense_covariance.h), which are cubic in the views and run only where they finish.
#include <benchmark/benchmark.h>

#include <map>

#include <opencv2/calib3d.hpp>

#include "support/dense_covariance.h"
#include "support/opencv_views.h"
#include "support/scenes.h"
#include "vstcal/estimators/decompose.h"
#include "vstcal/estimators/dlt.h"
#include "vstcal/estimators/information.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/calib/refine.h"
#include "vstcal/calib/tsai.h"
#include "vstcal/capture/synthetic_views.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/formats/camera/correspondences_io.h"

namespace {

using namespace vstcal;

// 600 points: a 12×5 template at 10 positions 2–3.8 m from a 1280×1024 camera with barrel
// distortion, 0.2 px noise.
const Correspondences& Volume600() {
  static const Correspondences c = [] {
    Eigen::Matrix3d K;
    K << 1509.4, 0, 647.5, 0, 1509.4, 505.5, 0, 0, 1;
    const double d[5] = {-0.09, 0.015, 0.0004, -0.0003, 0};
    VolumeSpec spec;
    spec.grid_cols = 12;
    spec.grid_rows = 5;
    spec.far = 1800;
    spec.tilt_deg = 5;
    spec.noise_px = 0.2;
    return SynthesizeVolume(Camera::FromK(K, ImageSize{1280, 1024}, RadialTangentialModel{}, d), spec, {}).correspondences;
  }();
  return c;
}

const Correspondences& Seed000() {
  static const Correspondences c = ReadCorrespondences(std::string(VSTCAL_SOURCE_DIR) + "/datasets/seed000/distorted-noisy.json");
  return c;
}

void BM_Tsai(benchmark::State& state) {
  const Correspondences& c = state.range(0) == 600 ? Volume600() : Seed000();
  const std::vector<Observation> obs = AllObservations(c);
  for (auto _ : state) {
    TsaiResult r = SolveTsai(obs, c.image_size);
    benchmark::DoNotOptimize(r);
  }
  state.counters["points"] = static_cast<double>(obs.size());
}

void BM_Dlt(benchmark::State& state) {
  const Correspondences& c = state.range(0) == 600 ? Volume600() : Seed000();
  const std::vector<Observation> obs = AllObservations(c);
  for (auto _ : state) {
    DltResult r = SolveDlt(obs);
    auto d = DecomposeProjection(r.P);
    benchmark::DoNotOptimize(d);
  }
}

// Refinement of fx, fy, cx, cy, k1, k2, p1, p2 and the pose from the DLT camera (skew dropped),
// including the covariance at the optimum.
void BM_RefineFromDlt(benchmark::State& state) {
  const Correspondences& c = state.range(0) == 600 ? Volume600() : Seed000();
  const DltResult dlt = SolveDlt(AllObservations(c));
  const auto d = *DecomposeProjection(dlt.P);
  Camera start = Camera::FromK(d.K, c.image_size);
  start.params[4] = 0;
  for (auto _ : state) {
    Refinement r = Refine(c, start, {d.camera_from_world}, RefineOptions{});
    benchmark::DoNotOptimize(r);
  }
}

// Tsai's start then the refinement: calib-tsai's whole solve.
void BM_TsaiRefined(benchmark::State& state) {
  const Correspondences& c = state.range(0) == 600 ? Volume600() : Seed000();
  for (auto _ : state) {
    CalibrationResult r = Calibrate(c, CalibrationOptions{});
    benchmark::DoNotOptimize(r);
  }
}

// Peer: OpenCV's calibrateCamera from the same DLT start (CALIB_USE_INTRINSIC_GUESS, k3 fixed):
// the same parameters and objective, without covariance.
void BM_OpenCvCalibrateCamera(benchmark::State& state) {
  const Correspondences& c = state.range(0) == 600 ? Volume600() : Seed000();
  const testing::OpenCvViews views = testing::ToOpenCvViews(c);  // a volume: one view of all points
  const auto d = *DecomposeProjection(SolveDlt(AllObservations(c)).P);
  for (auto _ : state) {
    cv::Mat K = (cv::Mat_<double>(3, 3) << d.K(0, 0), 0, d.K(0, 2), 0, d.K(1, 1), d.K(1, 2), 0, 0, 1);
    cv::Mat dist = cv::Mat::zeros(5, 1, CV_64F);
    std::vector<cv::Mat> rvecs, tvecs;
    const double rms = cv::calibrateCamera(views.object, views.image, cv::Size(c.image_size.width, c.image_size.height), K,
                                           dist, rvecs, tvecs, cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_FIX_K3);
    benchmark::DoNotOptimize(rms);
  }
}

// V views of a 10×7 board (30 mm) by a 1280×720 camera with barrel distortion, 0.3 px noise, as
// calib-synth --rig planar-views --views V makes them; built once per V.
const Correspondences& PlanarViews(int views) {
  static std::map<int, Correspondences> cache;
  auto it = cache.find(views);
  if (it != cache.end()) return it->second;
  PlanarViewsSpec spec;
  spec.num_views = views;
  spec.noise_px = 0.3;
  return cache[views] = SynthesizePlanarViews(testing::DistortedWideCamera(), spec).correspondences;
}

// calib-tsai's solve of planar views: Zhang's start, the refinement (k1, k2, p1, p2) and its
// covariance, poses eliminated by the Schur complement.
void BM_CalibratePlanarViews(benchmark::State& state) {
  const Correspondences& c = PlanarViews(static_cast<int>(state.range(0)));
  int iterations = 0;
  for (auto _ : state) {
    CalibrationResult r = Calibrate(c, CalibrationOptions{});
    iterations = r.refinement->iterations;
    benchmark::DoNotOptimize(r);
  }
  state.counters["points"] = static_cast<double>(NumObservations(c));
  state.counters["iterations"] = iterations;
}

// The same with --reject-views on a clean set: one solve plus the linear residual test (a rejection
// would add one solve per round).
void BM_CalibratePlanarViewsRejecting(benchmark::State& state) {
  const Correspondences& c = PlanarViews(static_cast<int>(state.range(0)));
  CalibrationOptions options;
  options.reject_views.enabled = true;
  size_t rejected = 0;
  for (auto _ : state) {
    CalibrationResult r = Calibrate(c, options);
    rejected = r.rejections.size();
    benchmark::DoNotOptimize(r);
  }
  state.counters["points"] = static_cast<double>(NumObservations(c));
  state.counters["rejected"] = static_cast<double>(rejected);
}

// The covariance alone at the optimum: by the Schur complement (CovarianceAt) and by the dense
// inverse of the whole information matrix it replaced (the test oracle, long double).
void BM_SchurCovariance(benchmark::State& state) {
  const Correspondences& c = PlanarViews(static_cast<int>(state.range(0)));
  const CalibrationResult r = Calibrate(c, CalibrationOptions{});
  for (auto _ : state) {
    CalibrationCovariance cov = CovarianceAt(c, r.refinement->camera, r.refinement->poses, RefineOptions{}, r.refinement->sigma_px);
    benchmark::DoNotOptimize(cov);
  }
}

void BM_DenseCovariance(benchmark::State& state) {
  const Correspondences& c = PlanarViews(static_cast<int>(state.range(0)));
  const CalibrationResult r = Calibrate(c, CalibrationOptions{});
  for (auto _ : state) {
    testing::DenseCovariance cov =
        testing::DenseCovarianceAt(c, r.refinement->camera, r.refinement->poses, RefineOptions{}, r.refinement->sigma_px);
    benchmark::DoNotOptimize(cov);
  }
}

// Peer: OpenCV's calibrateCamera on the same views (its own start, k3 fixed, as calib-tsai's
// default terms): it solves the normal equations of every pose at once, cubic in the views.
void BM_OpenCvPlanarViews(benchmark::State& state) {
  const Correspondences& c = PlanarViews(static_cast<int>(state.range(0)));
  const testing::OpenCvViews views = testing::ToOpenCvViews(c);
  for (auto _ : state) {
    cv::Mat K, dist;
    std::vector<cv::Mat> rvecs, tvecs;
    const double rms = cv::calibrateCamera(views.object, views.image, cv::Size(c.image_size.width, c.image_size.height), K,
                                           dist, rvecs, tvecs, cv::CALIB_FIX_K3);
    benchmark::DoNotOptimize(rms);
  }
}

// Arg 600: the 600-point volume; arg 0: the shipped seed-000 distorted volume (1,287 points).
BENCHMARK(BM_Dlt)->Arg(600)->Arg(0)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Tsai)->Arg(600)->Arg(0)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RefineFromDlt)->Arg(600)->Arg(0)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TsaiRefined)->Arg(600)->Arg(0)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OpenCvCalibrateCamera)->Arg(600)->Arg(0)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CalibratePlanarViews)->Arg(50)->Arg(100)->Arg(200)->Arg(400)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CalibratePlanarViewsRejecting)->Arg(50)->Arg(100)->Arg(200)->Arg(400)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SchurCovariance)->Arg(50)->Arg(100)->Arg(200)->Arg(400)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DenseCovariance)->Arg(50)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvPlanarViews)->Arg(50)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
