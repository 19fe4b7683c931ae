// --reject-views (docs/math/uncertainty.md#view-rejection): a view whose corners are mislabelled by
// one square, and a view 5× noisier than the others, are rejected and the solution is then the one
// without them; clean sets lose a view or a corner about as often as the false-alarm
// probabilities say; a rejection that would leave too few views is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/scenes.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/capture/synthetic_views.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/random/philox.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

Camera PlanarCamera() {
  Eigen::Matrix3d K;
  K << 800, 0, 330, 0, 805, 235, 0, 0, 1;
  Camera c = Camera::FromK(K, ImageSize{640, 480}, RadialTangentialModel{});
  c.params[5] = -0.12;  // k1
  c.params[6] = 0.05;   // k2
  return c;
}

Correspondences PlanarViews(int views, double noise_px, uint64_t seed) {
  PlanarViewsSpec spec;
  spec.num_views = views;
  spec.noise_px = noise_px;
  spec.seed = seed;
  return SynthesizePlanarViews(PlanarCamera(), spec).correspondences;
}

CalibrationOptions Rejecting(bool on = true) {
  CalibrationOptions o;
  o.refinement.free_distortion = {"k1", "k2"};
  o.reject_views.enabled = on;
  return o;
}

// One view's labels shifted by one square along the rows, wrapping at the board's edge (a
// detector that missed the first column): all but one column move rigidly, which a pose would
// absorb; the wrapped column cannot be.
void MislabelByOneSquare(View* view, double spacing) {
  double min_x = INFINITY, max_x = -INFINITY;
  for (const Observation& o : view->observations) min_x = std::min(min_x, o.point.x()), max_x = std::max(max_x, o.point.x());
  for (Observation& o : view->observations) {
    o.point.x() += spacing;
    if (o.point.x() > max_x + 1e-9) o.point.x() = min_x;
  }
}

double RelativeDifference(const Camera& a, const Camera& b) {
  double worst = 0;
  for (size_t i = 0; i < a.params.size(); ++i) worst = std::max(worst, std::abs(a.params[i] - b.params[i]) / std::max(1.0, std::abs(b.params[i])));
  return worst;
}

Correspondences Without(Correspondences c, size_t view) {
  c.views.erase(c.views.begin() + static_cast<std::ptrdiff_t>(view));
  return c;
}

TEST(ViewRejection, MislabelledPlanarViewIsRejected) {
  Correspondences c = PlanarViews(12, 0.3, 11);
  const size_t bad = 4;
  MislabelByOneSquare(&c.views[bad], PlanarViewsSpec{}.spacing);
  const CalibrationResult r = Calibrate(c, Rejecting());
  ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
  ASSERT_EQ(r.rejections.size(), 1u);
  EXPECT_EQ(r.rejections[0].kind, Rejection::Kind::kView);
  EXPECT_EQ(r.rejections[0].view, bad);
  EXPECT_GT(r.rejections[0].rms_px, r.rejections[0].threshold_px);
  // The solution is the clean solve of the other views.
  const CalibrationResult clean = Calibrate(Without(c, bad), Rejecting(false));
  ASSERT_EQ(clean.exit_code, ExitCode::kOk);
  EXPECT_LT(RelativeDifference(r.camera.camera, clean.camera.camera), 1e-9);
  // Without rejection the mislabelled view ruins the refinement: it does not converge, or fits
  // far worse.
  const CalibrationResult kept = Calibrate(c, Rejecting(false));
  EXPECT_TRUE(kept.exit_code != ExitCode::kOk || kept.camera.fit->overall.rms_px > 3 * r.camera.fit->overall.rms_px);
}

TEST(ViewRejection, NoisyPlanarViewIsRejected) {
  Correspondences c = PlanarViews(12, 0.3, 12);
  const size_t bad = 7;
  const CounterRng extra(99, 3);
  for (size_t i = 0; i < c.views[bad].observations.size(); ++i) {
    const auto e = extra.Normal2(i, 0);
    c.views[bad].observations[i].pixel += 0.3 * std::sqrt(24.0) * Eigen::Vector2d(e[0], e[1]);  // σ 5× in all
  }
  const CalibrationResult r = Calibrate(c, Rejecting());
  ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
  ASSERT_GE(r.rejections.size(), 1u);
  EXPECT_EQ(r.rejections[0].kind, Rejection::Kind::kView);
  EXPECT_EQ(r.rejections[0].view, bad);
  EXPECT_EQ(std::count_if(r.rejections.begin(), r.rejections.end(),
                          [](const Rejection& x) { return x.kind == Rejection::Kind::kView; }),
            1);
  EXPECT_NEAR(*r.rejection_sigma_px, 0.3, 0.03);
}

// One corner off by 2 px in a view of 70 (σ 0.3 px): too little to make its view inconsistent, far
// beyond what the noise gives one corner. That corner alone is rejected, named by its view and its
// index in the input, and the solution is the clean solve without it.
TEST(ViewRejection, SingleDisplacedCornerIsRejected) {
  Correspondences c = PlanarViews(12, 0.3, 13);
  const size_t bad_view = 5, bad_point = 17;
  ASSERT_GT(c.views[bad_view].observations.size(), bad_point);
  c.views[bad_view].observations[bad_point].pixel += Eigen::Vector2d(1.6, -1.2);
  const CalibrationResult r = Calibrate(c, Rejecting());
  ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
  ASSERT_EQ(r.rejections.size(), 1u);
  const Rejection& x = r.rejections[0];
  EXPECT_EQ(x.kind, Rejection::Kind::kCorner);
  EXPECT_EQ(x.view, bad_view);
  ASSERT_TRUE(x.point.has_value());
  EXPECT_EQ(*x.point, bad_point);
  EXPECT_GT(x.rms_px, x.threshold_px);
  Correspondences without = c;
  auto& obs = without.views[bad_view].observations;
  obs.erase(obs.begin() + static_cast<std::ptrdiff_t>(bad_point));
  const CalibrationResult clean = Calibrate(without, Rejecting(false));
  ASSERT_EQ(clean.exit_code, ExitCode::kOk);
  EXPECT_LT(RelativeDifference(r.camera.camera, clean.camera.camera), 1e-9);
}

// A volume (calib-dlt): one template position's world coordinates off by one square.
TEST(ViewRejection, ShiftedVolumePlaneIsRejected) {
  VolumeSpec spec;
  spec.noise_px = 0.3;
  spec.seed = 3;
  spec.interval = 400;  // 6 planes
  Eigen::Matrix3d K;
  K << 1500, 0, 640, 0, 1500, 480, 0, 0, 1;
  Correspondences c = SynthesizeVolume(Camera::FromK(K, ImageSize{1280, 960}), spec, {}).correspondences;
  ASSERT_GE(c.views.size(), 5u);
  const size_t bad = 2;
  for (Observation& o : c.views[bad].observations) o.point.x() += spec.spacing;
  CalibrationOptions o;
  o.start = CalibrationOptions::Start::kDlt;
  o.refine = false;
  o.reject_views.enabled = true;
  const CalibrationResult r = Calibrate(c, o);
  ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
  ASSERT_EQ(r.rejections.size(), 1u);
  EXPECT_EQ(r.rejections[0].view, bad);
  o.reject_views.enabled = false;
  const CalibrationResult clean = Calibrate(Without(c, bad), o);
  EXPECT_LT(RelativeDifference(r.camera.camera, clean.camera.camera), 1e-12);
}

// Clean sets: the probability that a calibration loses any view is view_false_alarm (0.01) and any
// corner corner_false_alarm (0.01), so at most ≈ 2 % of seeds reject anything. Over 150 seeds the
// count is Binomial(150, 0.02), mean 3: more than 10 has probability < 1e-3.
TEST(ViewRejection, CleanSetsRarelyRejectAnything) {
  int planar = 0, volume = 0;
  for (uint64_t seed = 1; seed <= 150; ++seed) {
    const CalibrationResult r = Calibrate(PlanarViews(10, 0.3, 1000 + seed), Rejecting());
    ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
    planar += !r.rejections.empty();
    VolumeSpec spec;
    spec.noise_px = 0.5;
    spec.seed = 2000 + seed;
    spec.interval = 400;
    Eigen::Matrix3d K;
    K << 1500, 0, 640, 0, 1500, 480, 0, 0, 1;
    CalibrationOptions o;
    o.start = CalibrationOptions::Start::kDlt;
    o.refine = false;
    o.reject_views.enabled = true;
    const CalibrationResult v = Calibrate(SynthesizeVolume(Camera::FromK(K, ImageSize{1280, 960}), spec, {}).correspondences, o);
    ASSERT_EQ(v.exit_code, ExitCode::kOk) << v.message;
    volume += !v.rejections.empty();
  }
  ::testing::Test::RecordProperty("planar_seeds_rejecting", planar);
  ::testing::Test::RecordProperty("volume_seeds_rejecting", volume);
  EXPECT_LE(planar, 10);
  EXPECT_LE(volume, 10);
}

TEST(ViewRejection, RefusesToLeaveTooFewViews) {
  Correspondences c = PlanarViews(3, 0.3, 21);
  ASSERT_EQ(c.views.size(), 3u);
  MislabelByOneSquare(&c.views[1], PlanarViewsSpec{}.spacing);
  const CalibrationResult r = Calibrate(c, Rejecting());
  EXPECT_EQ(r.exit_code, ExitCode::kBadInput);
  EXPECT_NE(r.message.find(VSTCAL_OPT("reject_views") ": view \"" + c.views[1].name + "\" is inconsistent"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("would leave 2 views, fewer than the 3 planar views need"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace vstcal
