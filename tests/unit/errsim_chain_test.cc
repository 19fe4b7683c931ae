// Unit tests of the err-sim chain's pieces: point registration (Horn vs the templated
// Gauss–Newton form), the small-angle path of AngleBetweenVectors, the parameter schema (every
// slot named once, laid out from the one declaration, any lens model), the lens's valid domain
// against Unproject, and the chain under ceres::Jet (derivatives against central differences of
// the double chain).
#include <gtest/gtest.h>

#include <cmath>

#include <ceres/jet.h>

#include <set>

#include "support/vst_scenes.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/measures.h"
#include "vstcal/geometry/point_registration.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

const std::vector<Eigen::Vector3d> kFiducials = {{-120, -80, 0}, {150, -60, 20}, {130, 90, -30}, {-100, 110, 10}};

TEST(PointRegistration, HornRecoversAnExactTransform) {
  const Rigid3d b_from_a = Rigid3d::FromRotvec(Eigen::Vector3d(0.4, -1.1, 2.0), Eigen::Vector3d(10, -200, 35));
  std::vector<Eigen::Vector3d> in_b;
  for (const auto& a : kFiducials) in_b.push_back(b_from_a * a);
  const auto found = RegisterPointsHorn(kFiducials, in_b);
  ASSERT_TRUE(found.has_value());
  EXPECT_LT((found->R - b_from_a.R).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((found->t - b_from_a.t).cwiseAbs().maxCoeff(), 1e-11);
}

TEST(PointRegistration, RefusesDegenerateSets) {
  const std::vector<Eigen::Vector3d> collinear = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {5, 5, 5}};
  EXPECT_FALSE(RegisterPointsHorn(collinear, collinear).has_value());
  EXPECT_FALSE(RegistrationFrame::For(collinear).has_value());
  const std::vector<Eigen::Vector3d> two = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_FALSE(RegisterPointsHorn(two, two).has_value());
  EXPECT_FALSE(RegisterPointsHorn(kFiducials, two).has_value());
}

// With noisy b-points the least-squares answer is not the generating transform; the Gauss–Newton
// form must still land on Horn's closed form.
TEST(PointRegistration, GaussNewtonConvergesToHorn) {
  const Rigid3d b_from_a = Rigid3d::FromRotvec(Eigen::Vector3d(0.2, 0.1, -0.3), Eigen::Vector3d(5, 6, 7));
  const auto frame = RegistrationFrame::For(kFiducials);
  ASSERT_TRUE(frame.has_value());
  const CounterRng rng(7, 0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Eigen::Vector3d> in_b;
    for (size_t k = 0; k < kFiducials.size(); ++k) {
      const auto z = rng.Normal2(trial, k);
      in_b.push_back(b_from_a * kFiducials[k] + Eigen::Vector3d(z[0], z[1], 0.5 * z[0] * z[1]));
    }
    const Rigid3d horn = *RegisterPointsHorn(kFiducials, in_b);
    const Rigid3d gn = RefineRegistration<double>(*frame, b_from_a.R, in_b.data());
    EXPECT_LT((gn.R - horn.R).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((gn.t - horn.t).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(AngleBetweenVectors, MatchesAtan2OnBothSidesOfTheSeries) {
  for (const double angle : {0.0, 1e-9, 1e-4, 0.01, 0.0999, 0.1001, 0.5, 2.0, 3.1}) {
    const Eigen::Vector3d a(3, 0, 0);
    const Eigen::Vector3d b(2 * std::cos(angle), 2 * std::sin(angle), 0);
    EXPECT_NEAR(AngleBetweenVectors(a, b), angle, 4e-16 * std::max(1.0, angle)) << angle;
  }
}

TEST(ParameterSchema, EverySlotIsNamedOnceAndLaidOutFromItsDeclaration) {
  const ChainModel m = ChainModel::WithZeroErrors(testing::ParallelRig({{0, 0, 0}, {10, 0, 0}}), kFiducials);
  // Sizes from kTerms: 6 + 7 + (2·6 + 1 + 6) + 2·5 (pinhole lenses) + (1 + 2 points) + (2·7 + 3 + 2)
  // + (6 + 3·4 fiducials).
  EXPECT_EQ(m.layout.size(), 6 + 7 + 19 + 10 + 3 + 19 + 18);
  std::set<std::string> names;
  for (const auto& p : m.parameters) EXPECT_TRUE(names.insert(p.name()).second) << p.name();
  EXPECT_EQ(m.parameters[m.layout.Offset(Term::kTrackingLatency)].name(), "tracking.latency");
  EXPECT_EQ(m.parameters[m.layout.Offset(Term::kLens, 1)].name(), "camera_intrinsic.right.fx");
  EXPECT_EQ(m.parameters[m.layout.Offset(Term::kDisparity) + 1].name(), "rendering.disparity[p1]");
  EXPECT_EQ(m.parameters[m.layout.Offset(Term::kIpd)].name(), "display.ipd");
  EXPECT_EQ(m.parameters[m.layout.Offset(Term::kEyeOffset) + 2].name(), "display.eye_offset.z");
  EXPECT_EQ(m.parameters[m.layout.Offset(Term::kRigRotation) + 1].name(), "camera_extrinsic.rig.rotation.y");
  EXPECT_EQ(m.parameters[m.layout.Offset(Term::kScreenShift, 1) + 1].name(), "display.right.screen_shift.v");
  EXPECT_EQ(m.parameters.back().name(), "virtual_object_alignment.fiducial[3].z");
  EXPECT_EQ(m.parameters[m.layout.Offset(Term::kCameraRotation)].slot.file_unit, "deg");
  EXPECT_EQ(m.parameters[m.layout.Offset(Term::kCameraTranslation)].slot.file_unit, "mm");
  // A term that exists once reads the same block for both eyes.
  EXPECT_EQ(m.layout.Offset(Term::kIpd, 0), m.layout.Offset(Term::kIpd, 1));
  for (int s = 0; s < kNumSources; ++s) {
    for (int i = m.layout.Begin(static_cast<Source>(s)); i < m.layout.End(static_cast<Source>(s)); ++i) {
      EXPECT_EQ(static_cast<int>(m.parameters[i].source), s) << m.parameters[i].name();
    }
  }
  // Every slot belongs to exactly one term's block.
  std::vector<int> owner(m.layout.size(), -1);
  for (const TermDecl& d : kTerms) {
    for (int e = 0; e < (d.scope == TermScope::kPerEye ? kNumEyes : 1); ++e) {
      for (int j = 0; j < m.layout.Size(d.term, e); ++j) {
        EXPECT_EQ(owner[m.layout.Offset(d.term, e) + j], -1);
        owner[m.layout.Offset(d.term, e) + j] = static_cast<int>(d.term);
        EXPECT_EQ(m.parameters[m.layout.Offset(d.term, e) + j].slot.term, d.term);
      }
    }
  }
  EXPECT_EQ(std::count(owner.begin(), owner.end(), -1), 0);
}

// Each eye's renderer lens comes from its camera through the variant: a rational left camera and
// a pinhole right one give 13 and 5 lens slots, named after the models' parameters.
TEST(ParameterSchema, EachEyesLensFromItsCameraAnyModel) {
  ChainGeometry g = testing::ParallelRig({testing::WorldFromHmdPoint({0, 0, 1000})});
  const std::vector<double> rational = {-0.1, 0.02, 0.001, -0.001, 0.0, 0.05, 0.01, 0.002};
  g.cameras[0] = Camera::FromK(g.cameras[0].K(), g.cameras[0].image_size, RationalModel{}, rational);
  const ChainModel m = ChainModel::WithZeroErrors(g);
  EXPECT_EQ(m.layout.Size(Term::kLens, 0), 13);
  EXPECT_EQ(m.layout.Size(Term::kLens, 1), 5);
  EXPECT_EQ(m.parameters[m.layout.Offset(Term::kLens, 0) + 12].name(), "camera_intrinsic.left.k6");
  EXPECT_EQ(m.parameters[m.layout.Offset(Term::kLens, 1) + 4].name(), "camera_intrinsic.right.s");
  // A renderer that carries distortion the pinhole right lens lacks: its nominal terms are 0.
  const ChainModel wider = ChainModel::WithZeroErrors(g, {}, std::array<AnyLensModel, kNumEyes>{RationalModel{}, RadialTangentialModel{}});
  EXPECT_EQ(wider.layout.Size(Term::kLens, 1), 10);
  EXPECT_EQ(wider.renderer[1].params[5], 0.0);
  // The error-free chain puts the overlay exactly on the video, through the rational lens too. The
  // display shows each pixel along the camera's pinhole ray (K⁻¹): a distorting camera's video shown
  // as captured is seen displaced, a systematic misperception of its own.
  const ChainEvaluator chain(m);
  ChainSample<double> sample(1);
  const std::vector<double> zero(m.layout.size(), 0.0);
  chain.Evaluate(zero.data(), &sample);
  ASSERT_TRUE(sample.points[0].valid());
  EXPECT_LT(sample.points[0].pixel_error[0].norm(), 1e-9);
  EXPECT_LT((sample.points[0].overlay - sample.points[0].seen).norm(), 1e-9);
  EXPECT_GT(chain.systematic(0).error.linear, 0.01);
  EXPECT_EQ((chain.systematic(0).offset - (sample.points[0].seen - sample.points[0].truth)).norm(), 0.0);
}

// The valid domain is where Unproject inverts Project: inside it the round trip returns the ray;
// a strong barrel lens folds over beyond it, where a ray far off axis lands back in the image and
// Unproject does not return it.
TEST(LensValidDomain, IsWhereUnprojectInvertsProject) {
  Eigen::Matrix3d K;
  K << 600, 0, 639.5, 0, 600, 359.5, 0, 0, 1;
  const std::vector<double> barrel = {-0.35, 0.0, 0.0, 0.0, 0.0};
  const Camera camera = Camera::FromK(K, {1280, 720}, RadialTangentialModel{}, barrel);
  const double r2 = camera.ValidRadiusSquared();
  // r (1 − 0.35 r²) has its maximum at r² = 1/1.05.
  EXPECT_NEAR(r2, 1 / 1.05, 1e-6);
  for (const double r : {0.2, 0.6, 0.95 * std::sqrt(r2)}) {
    const Eigen::Vector3d ray(r * std::cos(0.3), r * std::sin(0.3), 1.0);
    const auto px = camera.Project(ray);
    ASSERT_TRUE(px.has_value());
    const auto back = camera.Unproject(*px);
    ASSERT_TRUE(back.has_value()) << r;
    EXPECT_LT((*back - ray).norm(), 1e-9) << r;
  }
  // Beyond the fold: r = 1.3 maps to r_d = 1.3 (1 − 0.35·1.69) = 0.531, back inside the image.
  const Eigen::Vector3d folded(1.3, 0.0, 1.0);
  const auto px = camera.Project(folded);
  ASSERT_TRUE(px.has_value());
  EXPECT_TRUE(camera.InImage(*px));
  const auto back = camera.Unproject(*px);
  EXPECT_TRUE(!back.has_value() || (*back - folded).norm() > 0.1);
  EXPECT_EQ(Camera::FromK(K, {1280, 720}).ValidRadiusSquared(), std::numeric_limits<double>::infinity());
  // Each answer is the lens's own, whichever was asked before (the last one is kept): another k1,
  // then the same model with the first k1 again, then the first camera.
  const std::vector<double> stronger_barrel = {-0.7, 0.0, 0.0, 0.0, 0.0};
  const std::vector<double> rational_barrel = {-0.35, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const Camera stronger = Camera::FromK(K, {1280, 720}, RadialTangentialModel{}, stronger_barrel);
  EXPECT_NEAR(stronger.ValidRadiusSquared(), 1 / 2.1, 1e-6);  // r (1 − 0.7 r²): maximum at r² = 1/2.1
  const Camera rational = Camera::FromK(K, {1280, 720}, RationalModel{}, rational_barrel);
  EXPECT_NEAR(rational.ValidRadiusSquared(), 1 / 1.05, 1e-6);
  EXPECT_EQ(camera.ValidRadiusSquared(), r2);
}

// The same chain code under ceres::Jet: its derivatives agree with central differences of the
// double chain at a perturbed θ (every source active, fiducial alignment, intrinsics mixed).
TEST(ChainJet, DerivativesMatchCentralDifferences) {
  ChainGeometry g = testing::ParallelRig(
      {testing::WorldFromHmdPoint({100, -50, 800}), testing::WorldFromHmdPoint({-300, 200, 2000})});
  g.head_angular_velocity = Eigen::Vector3d(0.2, 0.5, -0.1);
  g.head_linear_velocity = Eigen::Vector3d(50, -20, 10);
  ChainModel model = ChainModel::WithZeroErrors(g, kFiducials);
  model.intrinsic_mixing[1](1, 0) = 0.3;  // a correlated (covariance-form) right camera
  model.extrinsic_mixing[1](4, 0) = 30.0;  // a rig covariance's correlated right camera pose
  model.extrinsic_mixing[1](2, 3) = 0.01;
  model.geometry.display.inverse_image_distance = 1 / 1500.0;
  model.geometry.display.eye_centre_in_hmd = Eigen::Vector3d(0, 20, -80);  // the camera–eye offset
  const ChainEvaluator chain(model);
  std::vector<double> theta(model.layout.size());
  const CounterRng rng(3, 0);
  for (size_t i = 0; i < theta.size(); ++i) theta[i] = 1e-3 * rng.Normal2(i, 0)[0];

  constexpr int kN = 4;
  using Jet = ceres::Jet<double, kN>;
  const size_t m = chain.num_vector_outputs();
  std::vector<double> y0(m);
  ASSERT_TRUE(chain(theta.data(), y0.data()));
  for (size_t first = 0; first < theta.size(); first += kN) {
    std::vector<Jet> tj(theta.size());
    for (size_t i = 0; i < theta.size(); ++i) {
      tj[i] = Jet(theta[i]);
      if (i >= first && i < first + kN) tj[i].v[i - first] = 1;
    }
    std::vector<Jet> yj(m);
    ASSERT_TRUE(chain(tj.data(), yj.data()));
    for (size_t i = first; i < std::min(theta.size(), first + kN); ++i) {
      const double h = 1e-5;
      std::vector<double> plus = theta, minus = theta, yp(m), ym(m);
      plus[i] += h;
      minus[i] -= h;
      ASSERT_TRUE(chain(plus.data(), yp.data()));
      ASSERT_TRUE(chain(minus.data(), ym.data()));
      for (size_t o = 0; o < m; ++o) {
        EXPECT_NEAR(yj[o].a, y0[o], 1e-12 * (1 + std::abs(y0[o])));
        const double numeric = (yp[o] - ym[o]) / (2 * h);
        // Central differences: rounding ε·|P|·(Z/b)/h ≈ 1.3e-6 (perceived points |P| ≈ 2e3 mm, amplified
        // Z/b ≈ 30 by the triangulation) and truncation h²·|y'''| ≲ 1e-10·f ≈ 7e-8.
        EXPECT_NEAR(yj[o].v[i - first], numeric, 1e-5 * (1 + std::abs(numeric)))
            << model.parameters[i].name() << " → output " << o;
      }
    }
  }
}

}  // namespace
}  // namespace vstcal
