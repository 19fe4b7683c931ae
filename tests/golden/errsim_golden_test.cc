// err-sim's chain against closed forms (shared/spec/VST-CHAIN.md "Closed forms", derived in
// docs/math/vst-chain.md#closed-forms): each error source is set to a fixed bias on a parallel
// orthostereo rig (tests/support/vst_scenes.h) and the chain must give the textbook number.
// Deterministic cases are exact to rounding; the fiducial-registration case is a Monte Carlo
// estimate checked against Fitzpatrick's TRE formula within its standard error.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Eigenvalues>

#include "support/vst_scenes.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/measures.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

using testing::ParallelRig;
using testing::WorldFromHmdPoint;

constexpr double kFocal = 700.0;
constexpr double kBaseline = 63.0;
constexpr double kHalf = kBaseline / 2;

struct Evaluated {
  ChainEvaluator chain;
  std::vector<double> theta;
  ChainSample<double> sample;
};

// Sets parameters (by name) to fixed biases, evaluates the chain once.
Evaluated EvaluateWith(ChainGeometry geometry, const std::vector<std::pair<std::string, double>>& biases) {
  ChainModel model = ChainModel::WithZeroErrors(std::move(geometry));
  for (const auto& [name, value] : biases) {
    ChainParameter* p = model.Find(name);
    EXPECT_NE(p, nullptr) << name;
    if (p) p->distribution = Distribution::MakeFixed(value);
  }
  Evaluated e{ChainEvaluator(model), model.MeanTheta(), ChainSample<double>(model.geometry.test_points.size())};
  e.chain.Evaluate(e.theta.data(), &e.sample);
  return e;
}

std::vector<Eigen::Vector3d> HmdPoints(const std::vector<Eigen::Vector3d>& in_hmd) {
  std::vector<Eigen::Vector3d> world;
  for (const auto& p : in_hmd) world.push_back(WorldFromHmdPoint(p));
  return world;
}

Eigen::Matrix3d HmdFromVirtual(const ChainGeometry& g) {
  return (g.hmd_from_tracker * g.tracker_from_world * g.world_from_virtual).R;
}

TEST(ErrsimGolden, NoErrorGivesNoError) {
  const auto e = EvaluateWith(ParallelRig(HmdPoints({{100, -50, 800}, {-300, 200, 3000}})), {});
  for (const auto& s : e.sample.points) {
    ASSERT_TRUE(s.valid());
    for (int eye = 0; eye < kNumEyes; ++eye) EXPECT_LT(s.pixel_error[eye].norm(), 1e-9);
    EXPECT_LT((s.overlay - s.seen).norm(), 1e-9);
    EXPECT_LT((s.seen - s.truth).norm(), 1e-9);
  }
}

// A translation Δt across the line of sight at depth Z: image error f·Δt/Z px in each eye, and the
// perceived overlay moves by exactly Δt (lateral Δt, depth 0 on the cyclopean axis) at every depth.
// Whichever factor of the virtual path carries the translation, expressed in its own frame.
TEST(ErrsimGolden, TranslationAcrossTheLineOfSight) {
  const double dt = 5.0;
  const std::vector<double> depths = {400, 800, 1500, 3000, 6000};
  std::vector<Eigen::Vector3d> on_axis;
  for (double z : depths) on_axis.emplace_back(0, 0, z);
  const ChainGeometry g = ParallelRig(HmdPoints(on_axis));
  const Eigen::Vector3d shift_in_hmd(dt, 0, 0);
  const Eigen::Vector3d in_tracker = g.hmd_from_tracker.R.transpose() * shift_in_hmd;
  const Eigen::Vector3d in_virtual = HmdFromVirtual(g).transpose() * shift_in_hmd;
  const std::vector<std::vector<std::pair<std::string, double>>> cases = {
      {{"tracking.translation.x", dt}},
      {{"camera_extrinsic.left.translation.x", dt}, {"camera_extrinsic.right.translation.x", dt}},
      {{"camera_extrinsic.rig.translation.x", dt}},
      {{"tracker_alignment.translation.x", in_tracker.x()},
       {"tracker_alignment.translation.y", in_tracker.y()},
       {"tracker_alignment.translation.z", in_tracker.z()}},
      {{"virtual_object_alignment.translation.x", in_virtual.x()},
       {"virtual_object_alignment.translation.y", in_virtual.y()},
       {"virtual_object_alignment.translation.z", in_virtual.z()}},
  };
  for (const auto& biases : cases) {
    SCOPED_TRACE(biases[0].first);
    const auto e = EvaluateWith(g, biases);
    for (size_t k = 0; k < depths.size(); ++k) {
      const auto& s = e.sample.points[k];
      ASSERT_TRUE(s.valid());
      for (int eye = 0; eye < kNumEyes; ++eye) {
        EXPECT_NEAR(s.pixel_error[eye].x(), kFocal * dt / depths[k], 1e-9);
        EXPECT_NEAR(s.pixel_error[eye].y(), 0.0, 1e-9);
      }
      const PointErrors m = MeasurePoint(e.chain, e.sample, e.theta.data(), k);
      EXPECT_NEAR(m.misregistration.linear, dt, 1e-9);
      EXPECT_NEAR(m.misregistration.lateral, dt, 1e-9);
      EXPECT_NEAR(m.misregistration.depth, 0.0, 1e-9);
      EXPECT_EQ(m.misperception.linear, 0.0);  // the video of the physical point is untouched
    }
  }
}

// A rotation Δθ of the cameras about their own centres: a point on a camera's axis moves by
// f·tan Δθ px whatever its depth. Each eye's ray turns by Δθ, so the perceived point slides along
// the Vieth–Müller circle through both eyes and the point: for a point at distance d on the
// cyclopean axis, radius R = (d² + h²)/(2d) (h = baseline/2), central angle 2Δθ, so the lateral error
// is R·sin 2Δθ = d·tan Δθ·(1 + h²/d²)·cos²Δθ → d·tan Δθ for d ≫ h and small Δθ.
TEST(ErrsimGolden, RotationOfTheCameras) {
  const double dtheta = DegToRad(0.3);
  const std::vector<double> depths = {400, 1000, 2500, 6000};
  std::vector<Eigen::Vector3d> points;
  for (double z : depths) points.emplace_back(-kHalf, 0, z);  // on the left camera's axis
  for (double z : depths) points.emplace_back(0, 0, z);       // on the cyclopean axis
  const auto e = EvaluateWith(ParallelRig(HmdPoints(points)), {{"camera_extrinsic.left.rotation.y", dtheta},
                                                              {"camera_extrinsic.right.rotation.y", dtheta}});
  for (size_t k = 0; k < depths.size(); ++k) {
    EXPECT_NEAR(e.sample.points[k].pixel_error[0].x(), kFocal * std::tan(dtheta), 1e-9) << depths[k];
    EXPECT_NEAR(e.sample.points[k].pixel_error[0].y(), 0.0, 1e-9);
  }
  for (size_t k = 0; k < depths.size(); ++k) {
    const double d = depths[k];
    const double radius = (d * d + kHalf * kHalf) / (2 * d);
    const PointErrors m = MeasurePoint(e.chain, e.sample, e.theta.data(), depths.size() + k);
    EXPECT_NEAR(m.misregistration.lateral, radius * std::sin(2 * dtheta), 1e-9 * d) << d;
    EXPECT_NEAR(m.misregistration.depth, radius * (std::cos(2 * dtheta) - 1), 1e-9 * d) << d;
    // The textbook d·tan Δθ, off by the factor (1 + h²/d²)·cos²Δθ.
    const double textbook = d * std::tan(dtheta);
    EXPECT_NEAR(m.misregistration.lateral / textbook, 1.0, kHalf * kHalf / (d * d) + dtheta * dtheta) << d;
  }
}

// IPD ≠ camera baseline on a parallel orthostereo rig with a collimated display: the seen point is
// the true one scaled by IPD/baseline about the cyclopean eye, so perceived depth is Z·IPD/b —
// with a perfect image, and the overlay moves with the video: no misregistration.
TEST(ErrsimGolden, IpdDifferentFromBaselineScalesPerceivedDepth) {
  const std::vector<Eigen::Vector3d> points = {{0, 0, 1500}, {100, -50, 800}, {-300, 200, 3000}};
  for (const double ipd_error : {-8.0, 7.0}) {
    const auto e = EvaluateWith(ParallelRig(HmdPoints(points)), {{"display.ipd", ipd_error}});
    const double scale = (kBaseline + ipd_error) / kBaseline;
    for (size_t k = 0; k < points.size(); ++k) {
      const auto& s = e.sample.points[k];
      for (int eye = 0; eye < kNumEyes; ++eye) EXPECT_LT(s.pixel_error[eye].norm(), 1e-9);  // the image is perfect
      EXPECT_NEAR(s.seen.z(), points[k].z() * scale, 1e-9 * points[k].z());
      EXPECT_LT((s.seen - scale * points[k]).norm(), 1e-9 * points[k].norm());
      EXPECT_LT((s.overlay - s.seen).norm(), 1e-9 * points[k].norm());
    }
  }
}

// Latency τ between the video frame and the pose the renderer uses, head turning at ω: the virtual
// camera lags by α = ω·τ about the hmd origin. For a point on the left camera's axis the exact
// shift is f·(h(1 − cos α) + Z sin α)/(Z cos α + h sin α) ≈ f·ω·τ, within α²/3 + 2hα/Z relative.
// Tracking and render latency add; display latency moves the perceived world, not the image.
TEST(ErrsimGolden, LatencyTimesHeadRate) {
  const double omega = DegToRad(60.0);  // rad/s, yaw
  const std::vector<double> depths = {500, 1000, 3000};
  std::vector<Eigen::Vector3d> points;
  for (double z : depths) points.emplace_back(-kHalf, 0, z);
  ChainGeometry g = ParallelRig(HmdPoints(points));
  g.head_angular_velocity = Eigen::Vector3d(0, omega, 0);
  const double tau_tracking = 0.015, tau_render = 0.005;
  const auto e = EvaluateWith(g, {{"tracking.latency", tau_tracking}, {"rendering.latency", tau_render}});
  const double alpha = omega * (tau_tracking + tau_render);
  for (size_t k = 0; k < depths.size(); ++k) {
    const double z = depths[k];
    const double exact = kFocal * (kHalf * (1 - std::cos(alpha)) + z * std::sin(alpha)) /
                         (z * std::cos(alpha) + kHalf * std::sin(alpha));
    EXPECT_NEAR(e.sample.points[k].pixel_error[0].x(), exact, 1e-9) << z;
    const double textbook = kFocal * omega * (tau_tracking + tau_render);
    EXPECT_NEAR(exact / textbook, 1.0, alpha * alpha / 3 + 2 * kHalf * alpha / z) << z;
  }

  // Display latency: nothing in the image; the perceived world lags by the head's turn.
  const double tau_display = 0.02;
  const auto d = EvaluateWith(g, {{"display.latency", tau_display}});
  for (size_t k = 0; k < depths.size(); ++k) {
    const auto& s = d.sample.points[k];
    EXPECT_LT(s.pixel_error[0].norm() + s.pixel_error[1].norm(), 1e-9);
    const double a = omega * tau_display;  // the world seems to turn by a about the hmd origin
    EXPECT_NEAR((s.seen - s.truth).norm(), 2 * std::sin(a / 2) * points[k].norm(), 1e-9 * depths[k]);
    EXPECT_LT((s.overlay - s.seen).norm(), 1e-9 * depths[k]);
  }
}

// Point-based registration of the virtual object from N fiducials with isotropic localization error
// FLE (RMS 3-D): the target registration error obeys TRE²(r) ≈ FLE²/N · (1 + ⅓ Σ_k d_k²/f_k²)
// (Fitzpatrick, West & Maurer 1998, IEEE TMI 17(5) Eq. 46), d_k the target's distance from
// principal axis k of the fiducials, f_k the fiducials' RMS distance from that axis. With every
// other source off and a perfect display the perceived overlay is the registered point itself, so
// the chain's linear error is the TRE. The Monte Carlo mean of TRE² must match within 4 standard
// errors (plus the formula's O(FLE²/f²) first-order remainder, below 1e-4 relative here).
TEST(ErrsimGolden, FiducialRegistrationFollowsFitzpatrick) {
  const std::vector<Eigen::Vector3d> fiducials = {
      {-120, -80, 0}, {150, -60, 20}, {130, 90, -30}, {-100, 110, 10}, {10, 0, 150}, {-30, 20, -90}};
  const std::vector<Eigen::Vector3d> targets_in_object = {{0, 0, 0}, {300, 0, 0}, {0, 400, 200}, {-500, -300, 600}};
  ChainGeometry g = ParallelRig({});
  for (size_t i = 0; i < targets_in_object.size(); ++i) {
    g.test_points.push_back({"t" + std::to_string(i), g.world_from_object * targets_in_object[i], std::nullopt});
  }
  ChainModel model = ChainModel::WithZeroErrors(g, fiducials);
  const double fle = 0.5;  // mm, RMS of the 3-D localization error
  const double sigma = fle / std::sqrt(3.0);
  const int begin = model.layout.Offset(Term::kFiducial);
  const int end = begin + model.layout.Size(Term::kFiducial);
  for (int i = begin; i < end; ++i) model.parameters[i].distribution = Distribution::MakeNormal(0, sigma);
  const ChainEvaluator chain(model);

  // The formula's geometry: principal axes of the fiducial set.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& f : fiducials) centroid += f;
  centroid /= fiducials.size();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& f : fiducials) scatter += (f - centroid) * (f - centroid).transpose();
  const Eigen::Matrix3d axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors();
  auto distance_from_axis = [&](const Eigen::Vector3d& p, int k) {
    const Eigen::Vector3d r = p - centroid;
    return (r - r.dot(axes.col(k)) * axes.col(k)).norm();
  };

  const int n = 40000;
  const CounterRng rng(1998, 0);
  std::vector<double> theta = model.MeanTheta();
  ChainSample<double> sample(targets_in_object.size());
  std::vector<double> sum(targets_in_object.size()), sum2(targets_in_object.size());
  for (int i = 0; i < n; ++i) {
    for (int j = begin; j < end; j += 2) {
      const auto z = rng.Normal2(i, j);
      theta[j] = sigma * z[0];
      if (j + 1 < end) theta[j + 1] = sigma * z[1];
    }
    chain.Evaluate(theta.data(), &sample);
    for (size_t t = 0; t < targets_in_object.size(); ++t) {
      ASSERT_TRUE(sample.points[t].valid());
      // A perfect display: the overlay is seen at the registered point, the video at the truth.
      const double tre2 = MeasurePoint(chain, sample, theta.data(), t).misregistration.linear;
      sum[t] += tre2 * tre2;
      sum2[t] += tre2 * tre2 * tre2 * tre2;
    }
  }
  for (size_t t = 0; t < targets_in_object.size(); ++t) {
    double ratio = 0;
    for (int k = 0; k < 3; ++k) {
      double fk2 = 0;
      for (const auto& f : fiducials) fk2 += std::pow(distance_from_axis(f, k), 2);
      ratio += std::pow(distance_from_axis(targets_in_object[t], k), 2) / (fk2 / fiducials.size());
    }
    const double predicted = fle * fle / fiducials.size() * (1 + ratio / 3);
    const double mean = sum[t] / n;
    const double standard_error = std::sqrt((sum2[t] / n - mean * mean) / (n - 1));
    EXPECT_NEAR(mean, predicted, 4 * standard_error + 1e-4 * predicted)
        << "target " << t << ": TRE² " << mean << " vs Fitzpatrick " << predicted;
  }
}

// Every display-only error moves the overlay and the video of the point together: zero
// misregistration, in the image and in 3-D, and a non-zero misperception (issue 12 item 1).
TEST(ErrsimGolden, DisplayErrorsGiveNoMisregistrationButMisperception) {
  ChainGeometry g = ParallelRig(HmdPoints({{100, -50, 800}, {-300, 200, 2500}}));
  g.display.inverse_image_distance = 1 / 1500.0;
  g.head_angular_velocity = Eigen::Vector3d(0.1, 0.5, 0);
  const std::vector<std::pair<std::string, double>> cases = {
      {"display.left.eyepoint.x", 4.0},   {"display.right.eyepoint.y", -3.0}, {"display.left.screen_shift.u", 2.0},
      {"display.right.magnification", 0.01}, {"display.left.lens_k1", 0.05},  {"display.eye_offset.z", 10.0},
      {"display.ipd", 5.0},               {"display.latency", 0.03}};
  for (const auto& [name, value] : cases) {
    SCOPED_TRACE(name);
    const auto e = EvaluateWith(g, {{name, value}});
    for (size_t k = 0; k < e.sample.points.size(); ++k) {
      const PointErrors m = MeasurePoint(e.chain, e.sample, e.theta.data(), k);
      EXPECT_LT(m.pixel_px[0] + m.pixel_px[1], 1e-9);
      EXPECT_LT(m.misregistration.linear, 1e-9);
      EXPECT_GT(m.misperception.linear, 1e-3);
    }
  }
}

// The camera–eye offset (Biocca & Rolland 1998): with the eyes at the cameras' centres moved by o
// (both eyes alike), each eye looks along its camera's rays from a point o away, so the whole seen
// world is displaced by exactly o — the systematic misperception, at every depth and for any
// virtual image distance (the eyes sit at their design eyepoints). Its visual angle at the eyes,
// ∠(P − c − o, P − c), falls with depth.
TEST(ErrsimGolden, CameraEyeOffsetDisplacesTheSeenWorld) {
  const std::vector<Eigen::Vector3d> points = {{0, 0, 400}, {0, 0, 1000}, {150, -80, 2500}, {-300, 100, 6000}};
  for (const double inverse_distance : {0.0, 1 / 1200.0}) {
    ChainGeometry g = ParallelRig(HmdPoints(points));
    const Eigen::Vector3d offset(0, 40, -85);  // eyes 40 mm below, 85 mm behind the cameras
    g.display.eye_centre_in_hmd = offset;
    g.display.inverse_image_distance = inverse_distance;
    const auto e = EvaluateWith(g, {});
    double previous_angle = HUGE_VAL;
    for (size_t k = 0; k < points.size(); ++k) {
      const auto& s = e.sample.points[k];
      ASSERT_TRUE(s.valid());
      EXPECT_LT((s.seen - (points[k] + offset)).norm(), 1e-9 * points[k].norm());
      const Systematic& systematic = e.chain.systematic(k);
      EXPECT_LT((systematic.offset - offset).norm(), 1e-9 * points[k].norm());
      EXPECT_NEAR(systematic.error.linear, offset.norm(), 1e-9 * points[k].norm());
      const double angle = std::atan2((points[k] - offset).cross(points[k]).norm(), (points[k] - offset).dot(points[k]));
      EXPECT_NEAR(systematic.error.angular, angle, 1e-12);
      EXPECT_LT(angle, previous_angle);
      previous_angle = angle;
      // Relative to the systematic error nothing is left.
      EXPECT_LT(MeasurePoint(e.chain, e.sample, e.theta.data(), k).misperception.linear, 1e-9 * points[k].norm());
    }
  }
}

// Display optics: the virtual image at distance D. Both eyes off their design eyepoints by δ (the
// HMD slipped) see pixel q at E⁰ + D·d(q) from E⁰ + δ: for a point at depth Z (parallel rig, eyes
// in one plane) both rays pass through P + δ(1 − Z/D) — no error at the image plane, the full δ at
// infinity. One eye moved by its IPD share: the rays meet at depth (h + δ)/(h/Z + δ/D), h half
// the baseline — Z·I/b for a collimated display, exactly Z at Z = D.
TEST(ErrsimGolden, EyepointErrorsTurnRaysThroughTheVirtualImage) {
  const double distance = 1500;
  const std::vector<Eigen::Vector3d> points = {{0, 0, 600}, {80, -40, 1500}, {-200, 60, 4000}};
  ChainGeometry g = ParallelRig(HmdPoints(points));
  g.display.inverse_image_distance = 1 / distance;
  const Eigen::Vector3d delta(6, -4, 3);
  const auto e = EvaluateWith(g, {{"display.eye_offset.x", delta.x()}, {"display.eye_offset.y", delta.y()},
                                  {"display.eye_offset.z", delta.z()}});
  for (size_t k = 0; k < points.size(); ++k) {
    // Z: depth from the design eyepoints' plane (the image plane is D in front of it).
    const Eigen::Vector3d expected = points[k] + delta * (1 - points[k].z() / distance);
    EXPECT_LT((e.sample.points[k].seen - expected).norm(), 1e-9 * points[k].norm()) << k;
  }
  const double ipd_error = 6.0;
  const auto i = EvaluateWith(g, {{"display.ipd", ipd_error}});
  for (size_t k = 0; k < points.size(); ++k) {
    const double z = points[k].z(), shift = ipd_error / 2;
    EXPECT_NEAR(i.sample.points[k].seen.z(), (kHalf + shift) / (kHalf / z + shift / distance), 1e-9 * z) << k;
  }
}

}  // namespace
}  // namespace vstcal
