// Stereo display planning against closed forms (docs/math/stereo.md#display) and against err-sim's
// display model: the HMD viewer of `calib-stereo plan` is err-sim's viewer, so both must perceive
// the same depth for the same IPD, baseline and image translation.
#include <gtest/gtest.h>

#include <cmath>

#include "support/error_of.h"
#include "support/vst_scenes.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/stereo/display_plan.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

using testing::ErrorOf;

DisplayPlanInput Zed() {
  DisplayPlanInput in;
  in.baseline = 63;
  in.focal_px = 700;
  in.display_width = 1200;
  in.depths = {300, 500, 1000, 2000, 5000};
  return in;
}

// Seed 000 Eq. 3–4: d = f·b/z; after the translation t = d(z0), p = t − d = f·b·(1/z0 − 1/z),
// zero at z0, negative (in front) nearer, positive (behind) farther, t at infinity.
TEST(DisplayPlan, DisparityAndParallaxFollowEq3And4) {
  DisplayPlanInput in = Zed();
  in.z0 = 1000;
  const DisplayPlan plan = PlanDisplay(in);
  EXPECT_DOUBLE_EQ(plan.translation_px, 700 * 63 / 1000.0);  // 44.1 px
  EXPECT_DOUBLE_EQ(plan.capture_width_needed, 1200 + 44.1);
  for (const DepthRow& r : plan.rows) {
    EXPECT_DOUBLE_EQ(r.disparity_px, 700 * 63 / r.depth);
    EXPECT_NEAR(r.parallax_px, 700 * 63 * (1 / 1000.0 - 1 / r.depth), 1e-12);
    EXPECT_EQ(r.side, r.depth < 1000 ? -1 : r.depth > 1000 ? 1 : 0);
  }
  EXPECT_EQ(plan.rows[2].parallax_px, 0.0);
}

// Eq. 6 with θ across the capture width: A′ = A/(1 − b/(2 tan(θ/2) z0)), and then f = A′/(2 tan(θ/2))
// gives back A′ = A + f·b/z0 (the same relation in the focal length's form).
TEST(DisplayPlan, CaptureWidthFromTheFieldOfViewIsEq6) {
  DisplayPlanInput in = Zed();
  in.focal_px.reset();
  in.hfov_rad = DegToRad(90);
  in.z0 = 800;
  in.capture_width = 1280;
  const DisplayPlan plan = PlanDisplay(in);
  const double expected = 1200 / (1 - 63 / (2 * std::tan(DegToRad(45)) * 800));
  EXPECT_NEAR(plan.capture_width_needed, expected, 1e-9);
  EXPECT_NEAR(plan.focal_px, expected / 2, 1e-9);  // tan 45° = 1
  EXPECT_NEAR(plan.capture_width_needed, 1200 + plan.focal_px * 63 / 800, 1e-9);
  EXPECT_EQ(*plan.capture_margin_px, 1280 - static_cast<int>(std::ceil(expected)));
  // z0 nearer than b/(2 tan(θ/2)) = 31.5: no width holds the translation.
  in.z0 = 30;
  EXPECT_NE(ErrorOf([&] { PlanDisplay(in); }).find(VSTCAL_OPT("z0") ": 30 is not beyond 31.5"), std::string::npos);
}

// Seed 001 §4.6 on an HMD that shows each camera's image to its eye at the camera's field of view:
// without translation the viewer perceives every depth scaled by IPD/baseline.
TEST(DisplayPlan, HmdViewerScalesDepthByIpdOverBaseline) {
  DisplayPlanInput in = Zed();
  in.viewer = Viewer::kHmd;
  for (const double ipd : {58.0, 63.0, 70.0}) {
    in.ipd = ipd;
    for (const DepthRow& r : PlanDisplay(in).rows) EXPECT_NEAR(*r.perceived_depth, r.depth * ipd / 63, 1e-12 * r.depth);
  }
  // With seed 000's translation an HMD puts z0 at infinity: nearer depths are stretched, farther ones diverge.
  in.z0 = 1000;
  const DisplayPlan plan = PlanDisplay(in);
  EXPECT_EQ(*plan.diverges_beyond, 1000);
  EXPECT_FALSE(plan.rows[3].perceived_depth.has_value());
  EXPECT_NEAR(*plan.rows[0].perceived_depth, 70 / (63 / 300.0 - 63 / 1000.0), 1e-9);
}

// A screen viewer is orthostereoscopic when b = IPD, the screen subtends the camera's field of
// view from the eyes (S/D = A/f) and z0 = D: every depth is perceived where it is.
TEST(DisplayPlan, ScreenViewerIsOrthostereoUnderTheClassicConditions) {
  DisplayPlanInput in = Zed();
  in.viewer = Viewer::kScreen;
  in.ipd = 63;
  in.viewing_distance = 600;
  in.screen_width = 600 * 1200 / 700.0;
  in.z0 = 600;
  const DisplayPlan plan = PlanDisplay(in);
  for (const DepthRow& r : plan.rows) EXPECT_NEAR(*r.perceived_depth, r.depth, 1e-9 * r.depth);
  EXPECT_FALSE(plan.diverges_beyond.has_value());  // the parallax at infinity is exactly the IPD
  // A wider screen magnifies the parallax: beyond some depth it exceeds the IPD and the eyes diverge.
  in.screen_width *= 2;
  const DisplayPlan wide = PlanDisplay(in);
  ASSERT_TRUE(wide.diverges_beyond.has_value());
  const double z = *wide.diverges_beyond;
  EXPECT_NEAR((wide.translation_px - 700 * 63 / z) * in.screen_width / 1200, 63, 1e-9);
}

// err-sim's chain on its parallel orthostereo rig (the same focal length and baseline), with the
// IPD error and a screen shift of ∓t/2 per eye set as fixed biases: its perceived depth is the plan's.
TEST(DisplayPlan, AgreesWithErrSimsDisplayModel) {
  const double focal = 700, baseline = 63;
  const std::vector<double> depths = {400, 700, 1000, 2500};
  std::vector<Eigen::Vector3d> points;
  for (const double z : depths) points.push_back(testing::WorldFromHmdPoint(Eigen::Vector3d(40, -30, z)));
  for (const double ipd : {56.0, 63.0, 71.0}) {
    for (const std::optional<double> z0 : {std::optional<double>(), std::optional<double>(3000.0)}) {
      DisplayPlanInput in;
      in.baseline = baseline;
      in.focal_px = focal;
      in.display_width = 1280;
      in.z0 = z0;
      in.depths = depths;
      in.viewer = Viewer::kHmd;
      in.ipd = ipd;
      const DisplayPlan plan = PlanDisplay(in);

      ChainModel model = ChainModel::WithZeroErrors(testing::ParallelRig(points, focal, baseline));
      const std::pair<const char*, double> biases[] = {{"display.ipd", ipd - baseline},
                                                       {"display.left.screen_shift.u", -plan.translation_px / 2},
                                                       {"display.right.screen_shift.u", plan.translation_px / 2}};
      for (const auto& [name, value] : biases) {
        ChainParameter* p = model.Find(name);
        ASSERT_NE(p, nullptr) << name;
        p->distribution = Distribution::MakeFixed(value);
      }
      const ChainEvaluator chain(model);
      const std::vector<double> theta = model.MeanTheta();
      ChainSample<double> sample(points.size());
      chain.Evaluate(theta.data(), &sample);
      for (size_t k = 0; k < depths.size(); ++k) {
        ASSERT_TRUE(plan.rows[k].perceived_depth.has_value());
        EXPECT_NEAR(sample.points[k].seen.z(), *plan.rows[k].perceived_depth, 1e-9 * depths[k]) << ipd << " " << depths[k];
      }
    }
  }
}

TEST(DisplayPlan, RefusesInputsOutsideTheirDomain) {
  DisplayPlanInput in = Zed();
  in.hfov_rad = 1.0;
  EXPECT_NE(ErrorOf([&] { PlanDisplay(in); }).find(VSTCAL_OPT("focal_px") ", " VSTCAL_OPT("hfov_deg") ": give exactly one"), std::string::npos);
  in = Zed();
  in.baseline = 0;
  EXPECT_NE(ErrorOf([&] { PlanDisplay(in); }).find(VSTCAL_OPT("baseline") ": must be a positive finite number"), std::string::npos);
}

}  // namespace
}  // namespace vstcal
