// PnP and binocular registration: the closed-form start exact on exact data, the refinement at
// OpenCV solvePnP's optimum on noisy data, degenerate configurations reported, and the three
// registration modes compared on a synthetic sequence with known truth.
#include <gtest/gtest.h>

#include <map>

#include <Eigen/Core>  // before opencv2/core/eigen.hpp, which needs it
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>

#include "support/stereo_rigs.h"
#include "vstcal/camera/opencv_distortion.h"
#include "vstcal/random/philox.h"
#include "vstcal/estimators/pnp.h"
#include "vstcal/estimators/pose_refine.h"
#include "vstcal/stereo/registration.h"
#include "vstcal/stereo/registration_accuracy.h"
#include "vstcal/stereo/synthetic_tracks.h"

namespace vstcal {
namespace {

using testing::ZedLikeRig;

struct Case {
  std::vector<Eigen::Vector3d> world;
  std::vector<Eigen::Vector2d> pixels;
  Rigid3d truth;
};

// Points of a planar square or a spatial layout seen from a posed camera, with noise σ.
Case MakeCase(const Camera& camera, bool planar, int n, double noise, uint64_t seed) {
  Case c;
  c.truth = Rigid3d::FromRotvec(Eigen::Vector3d(0.3, -0.2, 0.1), Eigen::Vector3d(30, -40, 900));
  const CounterRng rng(seed, 0);
  for (int i = 0; i < n; ++i) {
    const auto a = rng.Uniform2(static_cast<uint64_t>(i), 0);
    const auto b = rng.Uniform2(static_cast<uint64_t>(i), 1);
    const Eigen::Vector3d X((a[0] - 0.5) * 300, (a[1] - 0.5) * 300, planar ? 0.0 : (b[0] - 0.5) * 300);
    const auto g = rng.Normal2(static_cast<uint64_t>(i), 2);
    c.world.push_back(X);
    c.pixels.push_back(*camera.Project(c.truth * X) + noise * Eigen::Vector2d(g[0], g[1]));
  }
  return c;
}

double RotationErrorDeg(const Rigid3d& a, const Rigid3d& b) { return RadToDeg(AngleBetween(a.R, b.R)); }

TEST(Pnp, ClosedFormIsExactOnExactData) {
  for (const bool distorted : {false, true}) {
    const Camera camera = ZedLikeRig(distorted).left.camera;
    for (const auto& [planar, n] : {std::pair{true, 4}, std::pair{true, 12}, std::pair{false, 4}, std::pair{false, 6},
                                    std::pair{false, 30}}) {
      const Case c = MakeCase(camera, planar, n, 0.0, 3);
      EXPECT_EQ(ClassifyLayout(c.world), planar ? PointLayout::kPlanar : PointLayout::kSpatial);
      const ClosedFormPose p = SolvePnpClosedForm(camera, c.world, c.pixels);
      ASSERT_EQ(p.status, PoseStatus::kOk) << planar << " " << n;
      // EPnP with n = 4 is exact in exact arithmetic; its eigen-decompositions lose a few digits.
      EXPECT_LT(RotationErrorDeg(p.camera_from_world, c.truth), 1e-6) << planar << " " << n;
      EXPECT_LT((p.camera_from_world.t - c.truth.t).norm(), 1e-6 * c.truth.t.norm()) << planar << " " << n;
    }
  }
}

// Both minimise the reprojection error through the same lens model: OpenCV's
// SOLVEPNP_ITERATIVE (Levenberg–Marquardt, started from its own closed form) and ours end at the
// same pose up to their convergence tolerances.
TEST(Pnp, RefinedPoseIsOpenCvsOptimum) {
  const Camera camera = ZedLikeRig(true).left.camera;
  for (const auto& [planar, n] : {std::pair{true, 4}, std::pair{true, 20}, std::pair{false, 6}, std::pair{false, 20}}) {
    const Case c = MakeCase(camera, planar, n, 0.5, 17);
    const ClosedFormPose start = SolvePnpClosedForm(camera, c.world, c.pixels);
    ASSERT_EQ(start.status, PoseStatus::kOk);
    const PoseObservations set{&camera, Rigid3d::Identity(), c.world, c.pixels};
    const PoseRefinement ours = RefinePose({&set, 1}, start.camera_from_world);
    ASSERT_EQ(ours.status, PoseStatus::kOk);
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    for (int i = 0; i < n; ++i) {
      object.emplace_back(c.world[i].x(), c.world[i].y(), c.world[i].z());
      image.emplace_back(c.pixels[i].x(), c.pixels[i].y());
    }
    cv::Mat K, rvec, tvec;
    cv::eigen2cv(camera.K(), K);
    ASSERT_TRUE(cv::solvePnP(object, image, K, OpenCvDistortion(camera, 5), rvec, tvec, false, cv::SOLVEPNP_ITERATIVE));
    cv::solvePnPRefineLM(object, image, K, OpenCvDistortion(camera, 5), rvec, tvec,
                         cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-15));
    const Rigid3d theirs = Rigid3d::FromRotvec(Eigen::Vector3d(rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2)),
                                               Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)));
    // Compared where the cost is defined, in pixels: a planar target's pose slides along a nearly
    // flat valley (its tilt is poorly determined), where both solvers stop once no pixel moves.
    double our_cost = 0, their_cost = 0, worst = 0;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d a = *camera.Project(ours.body_from_world * c.world[i]), b = *camera.Project(theirs * c.world[i]);
      our_cost += (a - c.pixels[i]).squaredNorm();
      their_cost += (b - c.pixels[i]).squaredNorm();
      worst = std::max(worst, (a - b).norm());
    }
    EXPECT_LE(our_cost, their_cost * (1 + 1e-9)) << planar << " " << n;
    EXPECT_LT(worst, 1e-4) << planar << " " << n;  // px
    EXPECT_NEAR(our_cost, ours.cost, 1e-9 * our_cost);
    // The noise moved it away from the truth, as much as 0.5 px noise on n points does.
    EXPECT_GT(RotationErrorDeg(ours.body_from_world, c.truth), 1e-5);
  }
}

TEST(Pnp, DegenerateConfigurationsAreReported) {
  const Camera camera = ZedLikeRig().left.camera;
  Case c = MakeCase(camera, true, 4, 0.0, 3);
  EXPECT_EQ(SolvePnpClosedForm(camera, std::span(c.world).first(3), std::span(c.pixels).first(3)).status,
            PoseStatus::kTooFewPoints);
  for (int i = 0; i < 4; ++i) {
    c.world[i] = Eigen::Vector3d(10.0 * i, 5.0 * i, -3.0 * i);
    c.pixels[i] = *camera.Project(c.truth * c.world[i]);
  }
  EXPECT_EQ(ClassifyLayout(c.world), PointLayout::kCollinear);
  EXPECT_EQ(SolvePnpClosedForm(camera, c.world, c.pixels).status, PoseStatus::kCollinear);
  TrackedFrame frame;
  frame.left.assign(c.pixels.begin(), c.pixels.end());
  EXPECT_EQ(RegisterFrame(ZedLikeRig(), c.world, frame, {}, RegistrationMode::kLeft).status, PoseStatus::kCollinear);
  frame.left[2].reset();
  EXPECT_EQ(RegisterFrame(ZedLikeRig(), c.world, frame, {}, RegistrationMode::kLeft).status, PoseStatus::kTooFewPoints);
}

TEST(Registration, ExactOnExactTracksInEveryMode) {
  const StereoRig rig = ZedLikeRig();
  for (const bool planar : {true, false}) {
    SyntheticTracksSpec spec;
    spec.frames = 12;
    spec.noise_px = 0;
    spec.planar = planar;
    const Tracks tracks = SyntheticTracks(rig, spec);
    for (const RegistrationMode mode : {RegistrationMode::kLeft, RegistrationMode::kPerEye, RegistrationMode::kJoint}) {
      for (const bool warm : {false, true}) {
        const auto frames = RegisterSequence(rig, tracks, {mode, warm, {}});
        for (size_t k = 0; k < frames.size(); ++k) {
          ASSERT_EQ(frames[k].status, PoseStatus::kOk);
          const auto a = AccuracyOf(rig, tracks.frames[k], frames[k], tracks.virtual_points);
          for (int e = 0; e < 2; ++e) EXPECT_LT(a->virtual_px[e].max_px, 1e-6) << RegistrationModeName(mode) << k;
        }
      }
    }
  }
}

// Seed 000's composition: the right pose is right_from_left · left_from_world, exactly.
TEST(Registration, LeftModeComposesTheRightPose) {
  const StereoRig rig = ZedLikeRig();
  const Tracks tracks = SyntheticTracks(rig, {.frames = 3, .noise_px = 0.5});
  for (const auto& f : RegisterSequence(rig, tracks, {})) {
    const Rigid3d composed = rig.right_from_left * f.left_from_world;
    EXPECT_EQ(f.right_from_world.R, composed.R);
    EXPECT_EQ(f.right_from_world.t, composed.t);
    ASSERT_TRUE(f.right_fit.has_value());  // how well the composed pose fits the right image
    EXPECT_EQ(f.virtual_right.size(), tracks.virtual_points.size());
  }
}

// With noise on both images, the joint solve uses twice the observations: its overlay error is
// the smallest in both eyes; per-eye registration leaves the two eyes' poses inconsistent with
// the rig. 300 frames, seeded: the comparison is deterministic.
TEST(Registration, JointBeatsOneEyeOnNoisyTracks) {
  const StereoRig rig = ZedLikeRig();
  const Tracks tracks = SyntheticTracks(rig, {.frames = 300, .noise_px = 0.5, .seed = 5});
  std::map<RegistrationMode, SequenceAccuracy> accuracy;
  for (const RegistrationMode mode : {RegistrationMode::kLeft, RegistrationMode::kPerEye, RegistrationMode::kJoint}) {
    const auto frames = RegisterSequence(rig, tracks, {mode, false, {}});
    std::vector<std::optional<FrameAccuracy>> per_frame;
    for (size_t k = 0; k < frames.size(); ++k) per_frame.push_back(AccuracyOf(rig, tracks.frames[k], frames[k], tracks.virtual_points));
    accuracy[mode] = *SummarizeAccuracy(per_frame);
    EXPECT_EQ(accuracy[mode].frames, 300u);
    if (mode == RegistrationMode::kPerEye) {
      double worst = 0;
      for (const auto& f : frames) {
        worst = std::max(worst, ((rig.right_from_left * f.left_from_world).inverse().t - f.right_from_world.inverse().t).norm());
      }
      EXPECT_GT(worst, 1.0);  // mm: the right camera is not where the rig puts it
    }
  }
  for (int e = 0; e < 2; ++e) {
    EXPECT_LT(accuracy[RegistrationMode::kJoint].virtual_px[e].rms_px, accuracy[RegistrationMode::kLeft].virtual_px[e].rms_px) << e;
    EXPECT_LT(accuracy[RegistrationMode::kJoint].virtual_px[e].rms_px, accuracy[RegistrationMode::kPerEye].virtual_px[e].rms_px) << e;
  }
}

}  // namespace
}  // namespace vstcal
