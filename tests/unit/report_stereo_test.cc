// The stereo rig's triangulated 3-D error (report/stereo_report.h) on closed forms
// (docs/math/stereo.md#triangulated-error): a noise-free rig measures no error; a right camera moved
// by Δb along the baseline scales every triangulated point about the left camera by (b + Δb)/b,
// so Δ = X·Δb/b (depth error z·Δb/b) exactly for a rig whose baseline lies along x, to first order
// for a slightly turned one; points seen by one camera only and views one camera saw are left out
// and counted; test points inside and outside the calibration points' box split by that closed form;
// one view's right pixels moved by a known offset give that view's right-camera residuals exactly
// (the left pose, from the left pixels alone, does not move).
#include <algorithm>
#include <cmath>
#include <tuple>

#include <gtest/gtest.h>

#include "support/stereo_rigs.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/report/report_format.h"
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

TEST(StereoReport, PerViewReprojectionOfEachCameraThroughTheRig) {
  // Noise-free views; the right camera's pixels of view 1 all moved by s = (3, −4) px. Its left
  // pose (PnP on the left pixels) and so every prediction p̂ stay where they were, on the unmoved
  // pixels: each of its right residuals p̂ − m is exactly −s (|r| = 5 px), every other residual 0.
  const StereoRig rig = testing::ZedLikeRig();
  testing::StereoViews views = testing::SyntheticStereoViews(rig, 3, 5);
  const Eigen::Vector2d shift(3, -4);
  for (Observation& o : views.right.views[1].observations) o.pixel += shift;
  views.right.views[0].image = "right0.png";
  // The right file's views in another order: each camera's reprojection names its own file's view.
  std::reverse(views.right.views.begin(), views.right.views.end());
  const StereoReport report = BuildStereoReport(rig, views.left, views.right, "rig", "l", "r");
  ASSERT_EQ(report.views.size(), 3u);
  size_t n_right = 0;
  for (size_t v = 0; v < 3; ++v) {
    const StereoViewReport& view = report.views[v];
    const View& lv = views.left.views[v];
    const View& rv = views.right.views[2 - v];
    EXPECT_EQ(view.left.file_view, v);
    EXPECT_EQ(view.right.file_view, 2 - v);
    EXPECT_EQ(view.right.image, v == 0 ? "right0.png" : "");
    ASSERT_EQ(view.left.points.size(), lv.observations.size());
    ASSERT_EQ(view.right.points.size(), rv.observations.size());
    EXPECT_EQ(view.left.error_px->n, lv.observations.size());
    EXPECT_LT(view.left.error_px->max, 1e-6);
    EXPECT_EQ(view.right.error_px->n, rv.observations.size());
    n_right += rv.observations.size();
    const double expected = v == 1 ? 5.0 : 0.0;
    EXPECT_NEAR(view.right.error_px->rms, expected, 1e-6) << view.name;
    EXPECT_NEAR(view.right.error_px->max, expected, 1e-6) << view.name;
    EXPECT_NEAR(view.right.error_px->median, expected, 1e-6) << view.name;
    for (size_t i = 0; i < rv.observations.size(); ++i) {
      const PointError& e = view.right.points[i];
      ASSERT_EQ(e.excluded, Exclusion::kNone);
      EXPECT_EQ(e.measured, rv.observations[i].pixel);
      const Eigen::Vector2d residual = v == 1 ? Eigen::Vector2d(-shift) : Eigen::Vector2d::Zero();
      EXPECT_LT((*e.predicted - e.measured - residual).norm(), 1e-6);
    }
    // The view's triangulated error: only the moved view's, over every point both cameras saw.
    Correspondences l, r;
    l.views = {lv};
    r.views = {rv};
    EXPECT_EQ(view.stats.linear->n, CommonPoints(l, r));
    if (v == 1) {
      EXPECT_GT(view.stats.linear->rms, 1.0);  // mm: 5 px of disparity-ish error at 0.45–0.75 m
    } else {
      EXPECT_LT(view.stats.linear->max, 1e-7);
    }
  }
  // Over every right point: √(25 · n₁ / n).
  const double n1 = static_cast<double>(views.right.views[1].observations.size());
  EXPECT_NEAR(report.right_grid.overall_px->rms, std::sqrt(25.0 * n1 / static_cast<double>(n_right)), 1e-6);
  EXPECT_LT(report.left_grid.overall_px->max, 1e-6);

  // The JSON report carries them: [u, v, du, dv] and each view's stats.
  const OrderedJson j = StereoReportToJson(report, Provenance{"report_stereo_test", {}, std::nullopt});
  const OrderedJson& right1 = j["stereo"]["views"][1]["reprojection"]["right"];
  EXPECT_NEAR(right1["error_px"]["rms"].get<double>(), 5.0, 1e-6);
  EXPECT_EQ(right1["points"].size(), views.right.views[1].observations.size());
  EXPECT_EQ(right1["points"][0][0].get<double>(), views.right.views[1].observations[0].pixel.x());
  EXPECT_NEAR(right1["points"][0][2].get<double>(), -3.0, 1e-6);
  EXPECT_NEAR(right1["points"][0][3].get<double>(), 4.0, 1e-6);
  EXPECT_EQ(j["stereo"]["reprojection"]["right"]["error_px"]["n"].get<size_t>(), n_right);
}

TEST(StereoReport, AViewWithoutALeftPoseReprojectsNoPoint) {
  const StereoRig rig = testing::ZedLikeRig();
  testing::StereoViews views = testing::SyntheticStereoViews(rig, 2, 5);
  views.left.views[0].observations.resize(2);  // too few for PnP
  const StereoReport report = BuildStereoReport(rig, views.left, views.right, "rig", "l", "r");
  ASSERT_EQ(report.views.size(), 2u);
  EXPECT_NE(report.views[0].pose_status, "ok");
  for (const StereoReprojection* cam : {&report.views[0].left, &report.views[0].right}) {
    EXPECT_FALSE(cam->error_px);
    for (const PointError& e : cam->points) EXPECT_EQ(e.excluded, Exclusion::kNoPose);
  }
  EXPECT_EQ(report.views[0].right.points.size(), views.right.views[0].observations.size());
  EXPECT_EQ(report.views[1].right.error_px->n, views.right.views[1].observations.size());
  const OrderedJson j = StereoReportToJson(report, Provenance{"report_stereo_test", {}, std::nullopt});
  const OrderedJson& right0 = j["stereo"]["views"][0]["reprojection"]["right"];
  EXPECT_TRUE(right0["error_px"].is_null());
  EXPECT_TRUE(right0["points"][0][2].is_null());
  EXPECT_EQ(right0["excluded"].size(), views.right.views[0].observations.size());
  EXPECT_EQ(right0["excluded"][0]["reason"], "no-pose");
}

}  // namespace
}  // namespace vstcal
