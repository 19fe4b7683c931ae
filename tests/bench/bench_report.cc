// reproj-report's library call (BuildReprojReport: residuals, lateral and angular errors, grid,
// statistics with exact quantiles, the measured volume's Qhull hull, test points) on N random
// points of a 1.2 × 0.9 × 2 m volume, beside the peer a throwaway script would be: OpenCV's
// projectPoints, the residual norms, and their sorted median and p95 (docs/performance.md#report).
#include <benchmark/benchmark.h>

#include <algorithm>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "support/scenes.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/geometry/convex_hull.h"
#include "vstcal/report/reprojection_report.h"

namespace {

using vstcal::testing::Scene;

vstcal::Correspondences CorrespondencesOf(const Scene& scene) {
  vstcal::Correspondences c;
  c.image_size = scene.camera.image_size;
  c.views.push_back({"all", "", std::nullopt, scene.observations, std::nullopt});
  return c;
}

void BM_ReprojReport(benchmark::State& state) {
  const Scene scene = vstcal::testing::RandomVolumeScene(static_cast<size_t>(state.range(0)), 0.3, 42);
  vstcal::ReportCamera camera;
  camera.file = "truth";
  camera.camera.camera = scene.camera;
  camera.camera.camera_from_world = scene.camera_from_world;
  const vstcal::Correspondences c = CorrespondencesOf(scene);
  for (auto _ : state) {
    vstcal::ReprojReport report = vstcal::BuildReprojReport({&camera, 1}, c, "bench");
    benchmark::DoNotOptimize(report);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_OpenCvResidualStats(benchmark::State& state) {
  const Scene scene = vstcal::testing::RandomVolumeScene(static_cast<size_t>(state.range(0)), 0.3, 42);
  std::vector<cv::Point3d> points;
  std::vector<cv::Point2d> pixels;
  for (const vstcal::Observation& o : scene.observations) {
    points.emplace_back(o.point.x(), o.point.y(), o.point.z());
    pixels.emplace_back(o.pixel.x(), o.pixel.y());
  }
  const Eigen::Matrix3d K = scene.camera.K();
  const cv::Matx33d cv_K(K(0, 0), K(0, 1), K(0, 2), K(1, 0), K(1, 1), K(1, 2), 0, 0, 1);
  const Eigen::Vector3d r = vstcal::RotvecFromRotation(scene.camera_from_world.R);
  const cv::Vec3d rvec(r.x(), r.y(), r.z());
  const cv::Vec3d tvec(scene.camera_from_world.t.x(), scene.camera_from_world.t.y(), scene.camera_from_world.t.z());
  std::vector<cv::Point2d> projected;
  std::vector<double> errors(points.size());
  for (auto _ : state) {
    cv::projectPoints(points, rvec, tvec, cv_K, cv::noArray(), projected);
    double sum2 = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      errors[i] = cv::norm(projected[i] - pixels[i]);
      sum2 += errors[i] * errors[i];
    }
    std::sort(errors.begin(), errors.end());
    benchmark::DoNotOptimize(sum2);
    benchmark::DoNotOptimize(errors[errors.size() / 2] + errors[errors.size() * 95 / 100]);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_ConvexHull(benchmark::State& state) {
  const Scene scene = vstcal::testing::RandomVolumeScene(static_cast<size_t>(state.range(0)), 0.0, 42);
  std::vector<Eigen::Vector3d> points;
  for (const vstcal::Observation& o : scene.observations) points.push_back(o.point);
  for (auto _ : state) {
    auto hull = vstcal::ConvexHull3::Of(points);
    benchmark::DoNotOptimize(hull);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK(BM_ReprojReport)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvResidualStats)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ConvexHull)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
