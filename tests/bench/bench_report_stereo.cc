// reproj-report's stereo library call (BuildStereoReport: view and point matching, the left pose by
// PnP per view, midpoint triangulation, per-axis and Holloway terms, seven statistics per view and
// overall) on N views of the 9 × 6 board seen by the ZED-like rig with 0.3 px of noise, beside the
// peer a throwaway script would be: per view OpenCV's solvePnP on the left pixels,
// undistortPoints on both, triangulatePoints (linear DLT), the per-axis errors and a sorted median
// and p95 of |Δz| — with the points already matched (docs/performance.md#report-stereo).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <tuple>

#include <Eigen/Core>  // before opencv2/core/eigen.hpp, which needs it
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>

#include "support/scenes.h"
#include "support/stereo_rigs.h"
#include "vstcal/camera/opencv_distortion.h"
#include "vstcal/report/stereo_report.h"

namespace {

vstcal::testing::StereoViews NoisyViews(const vstcal::StereoRig& rig, int views) {
  vstcal::testing::StereoViews v = vstcal::testing::SyntheticStereoViews(rig, views, 11);
  v.left = vstcal::testing::WithNoise(v.left, 0.3, 1);
  v.right = vstcal::testing::WithNoise(v.right, 0.3, 2);
  return v;
}

void BM_StereoReport(benchmark::State& state) {
  const vstcal::StereoRig rig = vstcal::testing::ZedLikeRig();
  const vstcal::testing::StereoViews v = NoisyViews(rig, static_cast<int>(state.range(0)));
  size_t points = 0;
  for (auto _ : state) {
    vstcal::StereoReport report = vstcal::BuildStereoReport(rig, v.left, v.right, "rig", "l", "r");
    points = report.overall.linear->n;
    benchmark::DoNotOptimize(report);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points));
}

// One view's matched points, as OpenCV takes them.
struct CvView {
  std::vector<cv::Point3d> board;
  std::vector<cv::Point2d> left, right;
};

std::vector<CvView> MatchedViews(const vstcal::testing::StereoViews& v) {
  std::vector<CvView> out;
  for (size_t k = 0; k < v.left.views.size(); ++k) {
    std::map<std::tuple<double, double, double>, Eigen::Vector2d> right;
    for (const vstcal::Observation& o : v.right.views[k].observations) right[{o.point.x(), o.point.y(), o.point.z()}] = o.pixel;
    CvView cv_view;
    for (const vstcal::Observation& o : v.left.views[k].observations) {
      const auto it = right.find({o.point.x(), o.point.y(), o.point.z()});
      if (it == right.end()) continue;
      cv_view.board.emplace_back(o.point.x(), o.point.y(), o.point.z());
      cv_view.left.emplace_back(o.pixel.x(), o.pixel.y());
      cv_view.right.emplace_back(it->second.x(), it->second.y());
    }
    out.push_back(std::move(cv_view));
  }
  return out;
}

void BM_OpenCvTriangulationErrors(benchmark::State& state) {
  const vstcal::StereoRig rig = vstcal::testing::ZedLikeRig();
  const std::vector<CvView> views = MatchedViews(NoisyViews(rig, static_cast<int>(state.range(0))));
  cv::Mat K1, K2, R, t;
  cv::eigen2cv(rig.left.camera.K(), K1);
  cv::eigen2cv(rig.right.camera.K(), K2);
  const cv::Mat D1(vstcal::OpenCvDistortion(rig.left.camera, 5), true), D2(vstcal::OpenCvDistortion(rig.right.camera, 5), true);
  cv::eigen2cv(rig.right_from_left.R, R);
  cv::eigen2cv(Eigen::Vector3d(rig.right_from_left.t), t);
  cv::Mat P1 = cv::Mat::eye(3, 4, CV_64F), P2(3, 4, CV_64F);
  cv::hconcat(R, t, P2);
  size_t points = 0;
  for (auto _ : state) {
    std::vector<double> dz;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const CvView& view : views) {
      cv::Mat rvec, tvec, pose_R, l, r, X;
      cv::solvePnP(view.board, view.left, K1, D1, rvec, tvec);
      cv::Rodrigues(rvec, pose_R);
      cv::undistortPoints(view.left, l, K1, D1);
      cv::undistortPoints(view.right, r, K2, D2);
      cv::triangulatePoints(P1, P2, l, r, X);
      for (int i = 0; i < X.cols; ++i) {
        const cv::Mat truth = pose_R * cv::Mat(view.board[static_cast<size_t>(i)]) + tvec;
        const double w = X.at<double>(3, i);
        const Eigen::Vector3d d(X.at<double>(0, i) / w - truth.at<double>(0), X.at<double>(1, i) / w - truth.at<double>(1),
                                X.at<double>(2, i) / w - truth.at<double>(2));
        sum += d;
        dz.push_back(std::abs(d.z()));
      }
    }
    std::sort(dz.begin(), dz.end());
    points = dz.size();
    benchmark::DoNotOptimize(sum);
    benchmark::DoNotOptimize(dz[dz.size() / 2] + dz[dz.size() * 95 / 100]);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points));
}

BENCHMARK(BM_StereoReport)->Arg(4)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvTriangulationErrors)->Arg(4)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

}  // namespace
