// The stereo rig's triangulated 3-D error (report/stereo_report.h) on closed forms
// (docs/math/stereo.md#triangulated-error): a noise-free rig measures no error; a right camera moved
// by Δb along the baseline scales every triangulated point about the left camera by (b + Δb)/b,
// so Δ = X·Δb/b (depth error z·Δb/b) exactly for a rig whose baseline lies along x, to first order
// for a slightly turned one; points seen by one camera only and views one camera saw are left out
// and counted; test points inside and outside the calibration points' box split by that closed form.
#include <algorithm>
#include <cmath>
#include <tuple>

#include <gtest/gtest.h>

#include "support/stereo_rigs.h"
#include "vstcal/core/error.h"
#include "vstcal/report/stereo_report.h"

namespace vstcal {
namespace {

size_t CommonPoints(const Correspondences& left, const Correspondences& right) {
  size_t n = 0;
  for (size_t v = 0; v < left.views.size(); ++v) {
    for (const Observation& l : left.views[v].observations) {
      for (const Observation& r : right.views[v].observations) n += l.point == r.point;
    }
  }
  return n;
}

// The rig with its right camera's centre moved by Δb along the left camera's x axis.
StereoRig WithBaselineError(StereoRig rig, double delta_b) {
  const Eigen::Vector3d right_centre = -(rig.right_from_left.R.transpose() * rig.right_from_left.t);
  rig.right_from_left.t = -(rig.right_from_left.R * (right_centre + Eigen::Vector3d(delta_b, 0, 0)));
  return rig;
}

TEST(StereoReport, NoiseFreeRigMeasuresNoError) {
  const StereoRig rig = testing::ZedLikeRig();
  const testing::StereoViews views = testing::SyntheticStereoViews(rig, 3, 5);
  const StereoReport report = BuildStereoReport(rig, views.left, views.right, "rig", "l", "r");
  ASSERT_TRUE(report.overall.linear);
  EXPECT_EQ(report.overall.linear->n, CommonPoints(views.left, views.right));
  EXPECT_LT(report.overall.linear->max, 1e-7);  // mm, 0.5–0.75 m away
  EXPECT_LT(report.overall.angular_deg->max, 1e-9);
  ASSERT_EQ(report.views.size(), 3u);
  for (const StereoViewReport& v : report.views) EXPECT_EQ(v.pose_status, "ok");
}

TEST(StereoReport, BaselineErrorAlongAParallelBaselineScalesDepthExactly) {
  StereoRig truth = testing::ZedLikeRig(false);
  const double b = 63.0, delta_b = 0.5;  // mm
  truth.right_from_left = Rigid3d{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-b, 0, 0)};
  const testing::StereoViews views = testing::SyntheticStereoViews(truth, 3, 8);
  const StereoReport report = BuildStereoReport(WithBaselineError(truth, delta_b), views.left, views.right, "rig", "l", "r");
  size_t checked = 0;
  for (const StereoViewReport& v : report.views) {
    for (const StereoPointError& e : v.points) {
      if (e.excluded != StereoExclusion::kNone) continue;
      const Eigen::Vector3d expected = e.truth * (delta_b / b);
      EXPECT_NEAR(e.error().z(), expected.z(), 1e-9 * e.truth.z()) << v.name;
      EXPECT_NEAR(e.error().x(), expected.x(), 1e-9 * e.truth.z());
      EXPECT_NEAR(e.error().y(), expected.y(), 1e-9 * e.truth.z());
      EXPECT_NEAR(e.linear, e.truth.norm() * delta_b / b, 1e-9 * e.truth.z());
      ++checked;
    }
  }
  EXPECT_EQ(checked, CommonPoints(views.left, views.right));
  EXPECT_GT(checked, 100u);
  // 0.45–0.75 m away: |Δz| between 3.6 and 6 mm, farther from the viewer.
  EXPECT_GT(report.overall.z->max, 0.45e3 * delta_b / b);
  EXPECT_GT(report.overall.depth_bias, 0);
}

TEST(StereoReport, BaselineErrorOfATurnedRigScalesDepthToFirstOrder) {
  const StereoRig truth = testing::ZedLikeRig();  // turned by about 0.3°, baseline off x by 0.4 mm
  const double b = truth.baseline(), delta_b = 0.2;
  const testing::StereoViews views = testing::SyntheticStereoViews(truth, 2, 9);
  const StereoReport report = BuildStereoReport(WithBaselineError(truth, delta_b), views.left, views.right, "rig", "l", "r");
  ASSERT_TRUE(report.overall.z);
  for (const StereoViewReport& v : report.views) {
    for (const StereoPointError& e : v.points) {
      if (e.excluded != StereoExclusion::kNone) continue;
      const double first_order = e.truth.z() * delta_b / b;
      // The sideways part Δb sin α (α ≈ 0.4°, docs/math/stereo.md#baseline-error) leaves 0.03–0.3 %.
      EXPECT_NEAR(e.error().z(), first_order, 0.005 * first_order);
    }
  }
}

TEST(StereoReport, PointsAndViewsSeenByOneCameraAreLeftOutAndCounted) {
  const StereoRig rig = testing::ZedLikeRig();
  testing::StereoViews views = testing::SyntheticStereoViews(rig, 3, 5);
  const size_t common = CommonPoints(views.left, views.right);
  Correspondences left_view2, right_view2;
  left_view2.views = {views.left.views[2]};
  right_view2.views = {views.right.views[2]};
  const size_t in_view2 = CommonPoints(left_view2, right_view2);
  views.right.views[0].observations.erase(views.right.views[0].observations.begin() + 4);  // left only
  views.left.views[1].observations.erase(views.left.views[1].observations.begin());        // right only
  views.right.views[2].name = "elsewhere";  // a view of each camera with no partner
  const StereoReport report = BuildStereoReport(rig, views.left, views.right, "rig", "l", "r");
  EXPECT_EQ(report.n_left_only, 1u);
  EXPECT_EQ(report.n_right_only, 1u);
  EXPECT_EQ(report.left_only_views, std::vector<std::string>{views.left.views[2].name});
  EXPECT_EQ(report.right_only_views, std::vector<std::string>{"elsewhere"});
  ASSERT_EQ(report.views.size(), 2u);
  EXPECT_EQ(report.views[0].points[4].excluded, StereoExclusion::kLeftOnly);
  EXPECT_EQ(report.views[1].points.back().excluded, StereoExclusion::kRightOnly);
  EXPECT_EQ(report.overall.linear->n, common - in_view2 - 2);
}

TEST(StereoReport, NoCommonViewIsBadInput) {
  const StereoRig rig = testing::ZedLikeRig();
  testing::StereoViews views = testing::SyntheticStereoViews(rig, 2, 5);
  for (View& v : views.right.views) v.name += "-r";
  EXPECT_THROW(BuildStereoReport(rig, views.left, views.right, "rig", "l", "r"), InputError);
}

// Both cameras' view "v" of a volume whose world frame is the left camera's: a 5 × 5 grid at 50 and
// 30 mm on three planes z = 500, 600, 700 mm (its convex hull the box |x| ≤ 100, |y| ≤ 60,
// 500 ≤ z ≤ 700), and the test points `tests`, each measured by both cameras.
testing::StereoViews BoxVolume(const StereoRig& rig, const std::vector<std::pair<std::string, Eigen::Vector3d>>& tests) {
  testing::StereoViews out;
  for (auto [c, camera, from_world] : {std::tuple{&out.left, &rig.left, Rigid3d{}}, std::tuple{&out.right, &rig.right, rig.right_from_left}}) {
    c->camera = camera->name;
    c->image_size = camera->camera.image_size;
    c->rig = Rig::kVolume;
    View view;
    view.name = "v";
    for (const double z : {500.0, 600.0, 700.0}) {
      for (int i = -2; i <= 2; ++i) {
        for (int j = -2; j <= 2; ++j) {
          const Eigen::Vector3d X(50.0 * i, 30.0 * j, z);
          view.observations.push_back({X, *camera->camera.Project(from_world * X), 1.0});
        }
      }
    }
    c->views.push_back(std::move(view));
    for (const auto& [name, X] : tests) c->test_points.push_back({name, X, *camera->camera.Project(from_world * X)});
  }
  return out;
}

TEST(StereoReport, TestPointsSplitInsideAndOutsideTheMeasuredVolume) {
  // A parallel rig with its baseline along x, measured with the baseline off by Δb: every point
  // triangulates at X·(b + Δb)/b (as above), so |Δz| = z·Δb/b and Holloway's linear = |X|·Δb/b.
  StereoRig truth = testing::ZedLikeRig(false);
  const double b = 63.0, delta_b = 0.5, k = delta_b / b;
  truth.right_from_left = Rigid3d{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-b, 0, 0)};
  const std::vector<std::pair<std::string, Eigen::Vector3d>> tests = {
      {"centre", {0, 0, 600}}, {"corner", {100, 60, 700}},  // inside, on the hull's boundary
      {"beyond", {0, 0, 900}}, {"aside", {150, 0, 600}}};  // outside: behind the far face, beside the box
  const testing::StereoViews views = BoxVolume(truth, tests);
  const StereoReport report = BuildStereoReport(WithBaselineError(truth, delta_b), views.left, views.right, "rig", "l", "r");
  EXPECT_EQ(report.volume.status, "ok");
  EXPECT_EQ(report.volume.vertices, 8u);  // the box's corners
  ASSERT_EQ(report.test_points.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    ASSERT_TRUE(report.test_points[i].inside_volume) << tests[i].first;
    EXPECT_EQ(*report.test_points[i].inside_volume, i < 2) << tests[i].first;
    EXPECT_EQ(report.test_points[i].error.excluded, StereoExclusion::kNone);
  }
  ASSERT_TRUE(report.test_inside.z && report.test_outside.z);
  EXPECT_EQ(report.test_inside.z->n, 2u);
  EXPECT_EQ(report.test_outside.z->n, 2u);
  EXPECT_NEAR(report.test_inside.z->mean, (600 + 700) / 2.0 * k, 1e-9);
  EXPECT_NEAR(report.test_outside.z->mean, (900 + 600) / 2.0 * k, 1e-9);
  EXPECT_NEAR(report.test_outside.z->max, 900 * k, 1e-9);
  EXPECT_NEAR(report.test_inside.linear->max, std::sqrt(100.0 * 100 + 60 * 60 + 700 * 700) * k, 1e-9);
  EXPECT_NEAR(report.test_inside.x->max, 100 * k, 1e-9);
  EXPECT_NEAR(report.test_outside.x->max, 150 * k, 1e-9);
  EXPECT_EQ(report.test_stats.z->n, 4u);
}

TEST(StereoReport, CalibrationPointsOnOnePlaneGiveNoVolume) {
  StereoRig truth = testing::ZedLikeRig(false);
  testing::StereoViews views = BoxVolume(truth, {{"centre", {0, 0, 600}}});
  for (Correspondences* c : {&views.left, &views.right}) {
    auto& points = c->views[0].observations;
    points.erase(std::remove_if(points.begin(), points.end(), [](const Observation& o) { return o.point.z() != 600; }),
                 points.end());
  }
  const StereoReport report = BuildStereoReport(truth, views.left, views.right, "rig", "l", "r");
  EXPECT_FALSE(report.volume.hull);
  EXPECT_NE(report.volume.status, "ok");
  ASSERT_EQ(report.test_points.size(), 1u);
  EXPECT_FALSE(report.test_points[0].inside_volume);
  EXPECT_FALSE(report.test_inside.z);
  EXPECT_FALSE(report.test_outside.z);
  EXPECT_EQ(report.test_stats.z->n, 1u);
}

TEST(StereoReport, GridCellsHoldEachCamerasReprojectionError) {
  // The baseline off by Δb moves every right prediction by fx·Δb/z along u (the parallel rig above);
  // the left camera, posed by PnP on its own noise-free pixels, reprojects exactly.
  StereoRig truth = testing::ZedLikeRig(false);
  const double b = 63.0, delta_b = 0.5, fx = truth.right.camera.K()(0, 0);
  truth.right_from_left = Rigid3d{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-b, 0, 0)};
  const testing::StereoViews views = BoxVolume(truth, {});
  StereoReportOptions one_cell;
  one_cell.grid_cols = one_cell.grid_rows = 1;
  const StereoReport report =
      BuildStereoReport(WithBaselineError(truth, delta_b), views.left, views.right, "rig", "l", "r", one_cell);
  ASSERT_EQ(report.left_grid.error_px.size(), 1u);
  ASSERT_EQ(report.right_grid.error_px.size(), 1u);
  const ErrorStats& left = *report.left_grid.error_px[0];
  const ErrorStats& right = *report.right_grid.error_px[0];
  EXPECT_EQ(left.n, 75u);
  EXPECT_LT(left.max, 1e-6);
  EXPECT_EQ(right.n, 75u);  // 25 points on each of the planes z = 500, 600, 700
  EXPECT_NEAR(right.mean, fx * delta_b * (1 / 500.0 + 1 / 600.0 + 1 / 700.0) / 3, 1e-6);
  EXPECT_NEAR(right.max, fx * delta_b / 500, 1e-6);
  // The default 8 × 6 cells: every point in one of them.
  const StereoReport cells = BuildStereoReport(WithBaselineError(truth, delta_b), views.left, views.right, "rig", "l", "r");
  ASSERT_EQ(cells.right_grid.error_px.size(), 48u);
  size_t n = 0;
  for (const auto& cell : cells.right_grid.error_px) n += cell ? cell->n : 0;
  EXPECT_EQ(n, 75u);
}

}  // namespace
}  // namespace vstcal
