// Rotations and rigid transforms: closed forms, round trips, Jet instantiation.
#include <gtest/gtest.h>

#include <ceres/jet.h>

#include "vstcal/geometry/rigid3.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

Eigen::Vector3d RandomVector(uint64_t i, double scale) {
  const CounterRng rng(7, 0);
  const auto a = rng.Uniform2(i, 0), b = rng.Uniform2(i, 1);
  return scale * Eigen::Vector3d(2 * a[0] - 1, 2 * a[1] - 1, 2 * b[0] - 1);
}

TEST(Rotation, RodriguesMatchesEigenAngleAxis) {
  for (uint64_t i = 0; i < 200; ++i) {
    const Eigen::Vector3d r = RandomVector(i, 3.0);
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
    EXPECT_LT((RotationFromRotvec(r) - expected).cwiseAbs().maxCoeff(), 1e-14) << r.transpose();
    const Eigen::Vector3d p = RandomVector(i + 1000, 5.0);
    EXPECT_LT((RotateByRotvec(r, p) - expected * p).norm(), 1e-13);
  }
}

TEST(Rotation, QuarterTurnAboutZ) {
  // x → y under a +90° rotation about z (right-hand rule).
  const Eigen::Matrix3d R = RotationFromRotvec(Eigen::Vector3d(0, 0, kPi / 2));
  EXPECT_LT((R * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-15);
  const auto q = QuaternionWxyzFromRotation(R);
  EXPECT_NEAR(q[0], std::sqrt(0.5), 1e-15);  // w first
  EXPECT_NEAR(q[1], 0, 1e-15);
  EXPECT_NEAR(q[2], 0, 1e-15);
  EXPECT_NEAR(q[3], std::sqrt(0.5), 1e-15);
}

TEST(Rotation, RotvecRoundTripIncludingZeroAndNearPi) {
  std::vector<Eigen::Vector3d> cases = {Eigen::Vector3d::Zero(), Eigen::Vector3d(1e-12, -2e-12, 3e-13),
                                        Eigen::Vector3d(kPi - 1e-9, 0, 0),
                                        (kPi - 1e-7) * Eigen::Vector3d(1, 2, -2).normalized()};
  for (uint64_t i = 0; i < 100; ++i) cases.push_back(RandomVector(i, 1.8));
  for (const Eigen::Vector3d& r : cases) {
    const Eigen::Vector3d back = RotvecFromRotation(RotationFromRotvec(r));
    EXPECT_LT((back - r).norm(), 1e-9 * (1 + r.norm())) << r.transpose();
  }
}

TEST(Rotation, QuaternionRoundTripAndPositiveW) {
  for (uint64_t i = 0; i < 100; ++i) {
    const Eigen::Matrix3d R = RotationFromRotvec(RandomVector(i, 3.0));
    const auto q = QuaternionWxyzFromRotation(R);
    EXPECT_GE(q[0], 0.0);
    EXPECT_LT((RotationFromQuaternionWxyz(q) - R).cwiseAbs().maxCoeff(), 1e-14);
    // A non-unit quaternion is normalized, a negated one is the same rotation.
    EXPECT_LT((RotationFromQuaternionWxyz({-3 * q[0], -3 * q[1], -3 * q[2], -3 * q[3]}) - R).cwiseAbs().maxCoeff(), 1e-14);
  }
}

TEST(Rotation, NearestRotationAndIsRotation) {
  const Eigen::Matrix3d R = RotationFromRotvec(Eigen::Vector3d(0.3, -0.2, 0.9));
  Eigen::Matrix3d noisy = R;
  noisy(0, 1) += 1e-4;
  EXPECT_FALSE(IsRotation(noisy, 1e-6));
  const Eigen::Matrix3d fixed = NearestRotation(noisy);
  EXPECT_TRUE(IsRotation(fixed, 1e-12));
  EXPECT_LT(AngleBetween(fixed, R), 1e-4);
  const Eigen::Matrix3d reflection = Eigen::Vector3d(1, 1, -1).asDiagonal();
  EXPECT_FALSE(IsRotation(reflection));
  EXPECT_GT(NearestRotation(reflection).determinant(), 0);
  EXPECT_NEAR(AngleBetween(Eigen::Matrix3d::Identity(), RotationFromRotvec(Eigen::Vector3d(0, 0.25, 0))), 0.25, 1e-15);
}

// d(R(r) p)/dr at r = 0 is −[p]× (since R ≈ I + [r]× and [r]× p = −[p]× r): the Jet branch for
// tiny angles must give it exactly, and away from zero Jets must match central differences.
TEST(Rotation, JetDerivatives) {
  using Jet = ceres::Jet<double, 3>;
  const Eigen::Vector3d p(0.3, -1.2, 2.0);
  {
    const Vec3<Jet> r(Jet(0.0, 0), Jet(0.0, 1), Jet(0.0, 2));
    const Vec3<Jet> q = RotateByRotvec<Jet>(r, p.cast<Jet>());
    Eigen::Matrix3d J;
    for (int i = 0; i < 3; ++i) J.row(i) = q(i).v.transpose();
    EXPECT_LT((J + Hat(p)).cwiseAbs().maxCoeff(), 1e-15);
  }
  const Eigen::Vector3d r0(0.4, -0.7, 1.1);
  const Vec3<Jet> r(Jet(r0(0), 0), Jet(r0(1), 1), Jet(r0(2), 2));
  const Mat3<Jet> R = RotationFromRotvec(r);
  const Vec3<Jet> q = RotateByRotvec<Jet>(r, p.cast<Jet>());
  for (int k = 0; k < 3; ++k) {
    const double h = 1e-6;
    Eigen::Vector3d dr = Eigen::Vector3d::Zero();
    dr(k) = h;
    const Eigen::Vector3d numeric = (RotationFromRotvec<double>(r0 + dr) * p - RotationFromRotvec<double>(r0 - dr) * p) / (2 * h);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(q(i).v(k), numeric(i), 1e-8);
      EXPECT_NEAR((R * p.cast<Jet>())(i).v(k), numeric(i), 1e-8);
    }
  }
}

// The series form agrees with Rodrigues to rounding on both sides of its 0.1 rad switch, and its
// Jet derivative at r = 0 is the generator [e_i]×.
TEST(Rotation, SmallRotvecSeriesMatchesRodrigues) {
  for (const double angle : {0.0, 1e-12, 1e-6, 1e-3, 0.05, 0.0999, 0.1001, 0.7}) {
    const Eigen::Vector3d r = angle * Eigen::Vector3d(0.36, -0.48, 0.8);
    EXPECT_LT((RotationFromSmallRotvec(r) - RotationFromRotvec(r)).cwiseAbs().maxCoeff(), 4e-16) << angle;
  }
  using Jet = ceres::Jet<double, 3>;
  const Vec3<Jet> r(Jet(0.0, 0), Jet(0.0, 1), Jet(0.0, 2));
  const Mat3<Jet> R = RotationFromSmallRotvec(r);
  for (int i = 0; i < 3; ++i) {
    Eigen::Matrix3d d;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) d(a, b) = R(a, b).v[i];
    EXPECT_LT((d - Hat(Eigen::Vector3d(Eigen::Vector3d::Unit(i)))).cwiseAbs().maxCoeff(), 1e-15) << i;
  }
}

TEST(Rigid3, CompositionNamesCancel) {
  const Rigid3d a_from_b = Rigid3d::FromRotvec(Eigen::Vector3d(0.1, 0.2, -0.3), Eigen::Vector3d(1, 2, 3));
  const Rigid3d b_from_c = Rigid3d::FromRotvec(Eigen::Vector3d(-0.5, 0.0, 0.4), Eigen::Vector3d(-4, 0.5, 2));
  const Eigen::Vector3d x_c(0.7, -0.1, 5);
  const Rigid3d a_from_c = a_from_b * b_from_c;
  EXPECT_LT((a_from_c * x_c - a_from_b * (b_from_c * x_c)).norm(), 1e-14);
  const Rigid3d identity = a_from_c * a_from_c.inverse();
  EXPECT_LT((identity.R - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_LT(identity.t.norm(), 1e-14);
  EXPECT_LT((a_from_b.matrix3x4() * x_c.homogeneous() - a_from_b * x_c).norm(), 1e-14);
}

// docs/conventions.md: a left perturbation acts in the destination frame.
TEST(Rigid3, PerturbLeftActsInDestinationFrame) {
  const Rigid3d cam_from_hmd = Rigid3d::FromRotvec(Eigen::Vector3d(0.2, -0.1, 0.05), Eigen::Vector3d(30, -5, 10));
  const Eigen::Vector3d rho(1, 2, 3);
  const Rigid3d shifted = PerturbLeft(cam_from_hmd, Eigen::Vector3d::Zero().eval(), rho);
  const Eigen::Vector3d x(4, 5, 6);
  EXPECT_LT(((shifted * x) - (cam_from_hmd * x + rho)).norm(), 1e-13);
  const Eigen::Vector3d omega(0, 0, 0.01);
  const Rigid3d turned = PerturbLeft(cam_from_hmd, omega, Eigen::Vector3d::Zero().eval());
  EXPECT_LT(((turned * x) - RotationFromRotvec(omega) * (cam_from_hmd * x)).norm(), 1e-12);
}

// LeftPerturbationBetween undoes PerturbLeft: the tangent it returns, applied to `from`, gives
// `to` again, and it is zero between a pose and itself.
TEST(Rigid3, LeftPerturbationBetweenInvertsPerturbLeft) {
  const Rigid3d from = Rigid3d::FromRotvec(Eigen::Vector3d(0.5, 0.1, -1.0), Eigen::Vector3d(1000, 200, 1500));
  const Eigen::Vector3d omega(0.003, -0.002, 0.004), rho(0.5, -0.25, 2);
  const Rigid3d to = PerturbLeft(from, omega, rho);
  const Vector6d e = LeftPerturbationBetween(from, to);
  EXPECT_LT((e.head<3>() - omega).norm(), 1e-15);
  EXPECT_LT((e.tail<3>() - rho).norm(), 1e-10);
  EXPECT_LT(LeftPerturbationBetween(from, from).norm(), 1e-12);  // R Rᵀ is I to rounding
  // A large turn too (RotvecFromRotation is exact beyond the small-angle path): 2 rad about one axis.
  const Rigid3d far = Rigid3d{RotationFromRotvec(Eigen::Vector3d(0, 2, 0)), Eigen::Vector3d(1, 2, 3)} * from;
  const Vector6d g = LeftPerturbationBetween(from, far);
  EXPECT_LT((g.head<3>() - Eigen::Vector3d(0, 2, 0)).norm(), 1e-12);
  EXPECT_LT((g.tail<3>() - Eigen::Vector3d(1, 2, 3)).norm(), 1e-9);
}

}  // namespace
}  // namespace vstcal
