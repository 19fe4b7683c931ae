// DLT: exact recovery, agreement with the textbook SVD route, accuracy against the Cramér–Rao
// bound, the two decomposition routes (RQ and seed 001 Eq. 13–14), and every refusal.
#include <gtest/gtest.h>

#include <cmath>

#include "support/crb.h"
#include "support/scenes.h"
#include "vstcal/estimators/decompose.h"
#include "vstcal/estimators/dlt.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

using testing::RandomVolumeScene;

double RelativeError(const Eigen::MatrixXd& estimate, const Eigen::MatrixXd& truth) {
  return (estimate - truth).norm() / truth.norm();
}

ProjectionDecomposition Solve(std::span<const Observation> obs, DltOptions options = {}) {
  const DltResult r = SolveDlt(obs, options);
  EXPECT_EQ(r.status, DltStatus::kOk) << r.message;
  const auto d = DecomposeProjection(r.P);
  EXPECT_TRUE(d.has_value());
  return d.value_or(ProjectionDecomposition{});
}

// Noise-free scenes give K (with skew), R and t to 1e-8 relative (issue 2 §8), whatever N.
TEST(Dlt, ExactDataRecoversKRt) {
  for (size_t n : {6u, 7u, 20u, 600u, 6000u}) {
    for (uint64_t seed = 1; seed <= 3; ++seed) {
      const auto scene = RandomVolumeScene(n, 0.0, seed);
      for (auto solver : {DltOptions::Solver::kNormalEquations, DltOptions::Solver::kFullSvd}) {
        DltOptions options;
        options.solver = solver;
        const auto d = Solve(scene.observations, options);
        EXPECT_LT(RelativeError(d.K, scene.camera.K()), 1e-8) << n << " " << seed;
        EXPECT_LT(AngleBetween(d.camera_from_world.R, scene.camera_from_world.R), 1e-8);
        EXPECT_LT(RelativeError(d.camera_from_world.t, scene.camera_from_world.t), 1e-8);
      }
    }
  }
}

// The fast path (moments + secular equation) and the reference (SVD of the 2N×12 system)
// compute the same estimator: on noisy data they agree far below the noise-induced error.
TEST(Dlt, NormalEquationsAgreeWithFullSvd) {
  for (size_t n : {60u, 600u, 6000u}) {
    const auto scene = RandomVolumeScene(n, 0.5, 100 + n);
    DltOptions fast, reference;
    fast.exact_diagnostics = true;
    reference.solver = DltOptions::Solver::kFullSvd;
    const DltResult a = SolveDlt(scene.observations, fast), b = SolveDlt(scene.observations, reference);
    ASSERT_EQ(a.status, DltStatus::kOk);
    ASSERT_EQ(b.status, DltStatus::kOk);
    EXPECT_LT(RelativeError(a.P, b.P), 1e-10) << n;
    EXPECT_NEAR(a.sigma_11, b.sigma_11, 1e-9 * b.sigma_11);
    EXPECT_NEAR(a.sigma_12, b.sigma_12, 1e-6 * b.sigma_12);
    EXPECT_NEAR(a.frobenius, b.frobenius, 1e-12 * b.frobenius);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a.extents[i], b.extents[i], 1e-12);
    // The error against the truth is the same to well under a part in a million.
    const double err_a = (DecomposeProjection(a.P)->K - scene.camera.K()).norm();
    const double err_b = (DecomposeProjection(b.P)->K - scene.camera.K()).norm();
    EXPECT_NEAR(err_a, err_b, 1e-6 * err_b);
  }
}

// Without exact_diagnostics σ₁₁ is not computed on the fast path, but the refusal test still
// decides exactly: the result is the same P.
TEST(Dlt, CertifiedConditioningGivesTheSameSolution) {
  const auto scene = RandomVolumeScene(300, 0.3, 5);
  DltOptions exact;
  exact.exact_diagnostics = true;
  const DltResult a = SolveDlt(scene.observations), b = SolveDlt(scene.observations, exact);
  EXPECT_TRUE(std::isnan(a.sigma_11));
  EXPECT_GT(b.conditioning, exact.min_conditioning);
  EXPECT_EQ(a.P, b.P);
}

// Accuracy: over 200 noisy trials the DLT's empirical standard deviation of fx, fy, cx, cy is
// close to the Cramér–Rao bound of the same geometry (the algebraic estimator on a well-spread
// volume is nearly efficient). With 200 trials the SE of a σ estimate is 1/√398 ≈ 5%, so the
// band [0.85, 1.35] only fails for a real loss of efficiency. Both solvers are held to it.
TEST(Dlt, NoisyVolumeIsNearlyEfficient) {
  const double sigma = 0.5;
  const int trials = 200;
  const auto base = RandomVolumeScene(300, 0.0, 77);
  const auto crb = testing::PinholeCrb(base.camera, base.camera_from_world, base.observations, sigma);
  for (auto solver : {DltOptions::Solver::kNormalEquations, DltOptions::Solver::kFullSvd}) {
    DltOptions options;
    options.solver = solver;
    Eigen::Vector4d sum2 = Eigen::Vector4d::Zero();
    const CounterRng noise(99, 0);
    for (int t = 0; t < trials; ++t) {
      std::vector<Observation> obs = base.observations;
      for (size_t i = 0; i < obs.size(); ++i) {
        const auto e = noise.Normal2(static_cast<uint64_t>(t) * 100000 + i, 0);
        obs[i].pixel += sigma * Eigen::Vector2d(e[0], e[1]);
      }
      const Eigen::Matrix3d K = Solve(obs, options).K;
      const Eigen::Vector4d err(K(0, 0) - base.camera.K()(0, 0), K(1, 1) - base.camera.K()(1, 1),
                                K(0, 2) - base.camera.K()(0, 2), K(1, 2) - base.camera.K()(1, 2));
      sum2 += err.cwiseAbs2();
    }
    const Eigen::Vector4d empirical = (sum2 / trials).cwiseSqrt();
    const Eigen::Vector4d bound(std::sqrt(crb(0, 0)), std::sqrt(crb(1, 1)), std::sqrt(crb(2, 2)), std::sqrt(crb(3, 3)));
    ::testing::Test::RecordProperty(solver == DltOptions::Solver::kFullSvd ? "svd_efficiency" : "fast_efficiency",
                                    ::testing::PrintToString(empirical.cwiseQuotient(bound).transpose()));
    for (int i = 0; i < 4; ++i) {
      EXPECT_GT(empirical(i) / bound(i), 0.85) << i;
      EXPECT_LT(empirical(i) / bound(i), 1.35) << i;
    }
  }
}

// Seed 001 Eq. 13–14 and the RQ route are two derivations of the same numbers.
TEST(Dlt, Eq13AgreesWithRq) {
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const auto scene = RandomVolumeScene(200, 0.3, seed);
    const DltResult r = SolveDlt(scene.observations);
    ASSERT_EQ(r.status, DltStatus::kOk);
    const auto rq = *DecomposeProjection(r.P);
    const auto eq13 = DecomposeProjectionEq13(r.P);
    EXPECT_LT(RelativeError(KFromSkewForm(eq13.intrinsics), rq.K), 1e-12);
    EXPECT_LT((eq13.camera_from_world.R - rq.camera_from_world.R).norm(), 1e-12);
    EXPECT_LT(RelativeError(eq13.camera_from_world.t, rq.camera_from_world.t), 1e-12);
    EXPECT_GT(eq13.rho, 0);
  }
}

// --- refusals -------------------------------------------------------------------------------

std::vector<Observation> Project(const testing::Scene& s, const std::vector<Eigen::Vector3d>& points) {
  std::vector<Observation> obs;
  for (const auto& p : points) obs.push_back({p, *s.camera.Project(s.camera_from_world * p)});
  return obs;
}

std::vector<Eigen::Vector3d> Grid(double z_jitter) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 6; ++j) points.emplace_back(i * 100.0 - 350, j * 100.0 - 250, 1000 + ((i + j) % 2) * z_jitter);
  }
  return points;
}

TEST(Dlt, RefusesTooFewPoints) {
  const auto scene = RandomVolumeScene(5, 0.0, 1);
  const DltResult r = SolveDlt(scene.observations);
  EXPECT_EQ(r.status, DltStatus::kTooFewPoints);
  EXPECT_NE(r.message.find("at least 6"), std::string::npos);
  EXPECT_EQ(DltStatusExitCode(r.status), ExitCode::kBadInput);
}

TEST(Dlt, RefusesNonFinite) {
  auto scene = RandomVolumeScene(50, 0.0, 1);
  scene.observations[7].point.y() = NAN;
  EXPECT_EQ(SolveDlt(scene.observations).status, DltStatus::kNonFinite);
  // Finite coordinates up to 1e308 (moved to the origin): the depths overflow a double. Say so,
  // instead of "46 of 50 points lie behind the camera".
  auto huge = RandomVolumeScene(50, 0.0, 1);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& o : huge.observations) centroid += o.point / 50.0;
  double largest = 0;
  for (const auto& o : huge.observations) largest = std::max(largest, (o.point - centroid).cwiseAbs().maxCoeff());
  for (auto& o : huge.observations) o.point = (o.point - centroid) * (1e308 / largest);
  const DltResult r = SolveDlt(huge.observations);
  EXPECT_EQ(r.status, DltStatus::kNonFinite);
  EXPECT_NE(r.message.find("the world coordinates are beyond double precision for the DLT"), std::string::npos)
      << r.message;
  EXPECT_NE(r.message.find("a larger length unit"), std::string::npos) << r.message;
}

// The DLT does not depend on the world's unit: coordinates scaled by 1e±150 and 1e±300 (where
// their squares overflow or underflow) give the same K and R and a scaled t, with both solvers.
// They used to give NaN and "points behind the camera", or a refusal quoting the pixels.
TEST(Dlt, ScaledCoordinatesGiveTheSameCamera) {
  const auto scene = RandomVolumeScene(60, 0.0, 5);
  for (const double scale : {1e-300, 1e-150, 1e150, 1e300}) {
    auto scaled = scene.observations;
    for (auto& o : scaled) o.point *= scale;
    for (auto solver : {DltOptions::Solver::kNormalEquations, DltOptions::Solver::kFullSvd}) {
      DltOptions options;
      options.solver = solver;
      const auto d = Solve(scaled, options);
      EXPECT_LT(RelativeError(d.K, scene.camera.K()), 1e-9) << scale;
      EXPECT_LT(AngleBetween(d.camera_from_world.R, scene.camera_from_world.R), 1e-9) << scale;
      EXPECT_LT(RelativeError(d.camera_from_world.t / scale, scene.camera_from_world.t), 1e-9) << scale;
    }
  }
}

// Depth exactly 0 (a point in the camera's principal plane) counts as not in front.
TEST(Dlt, PointInThePrincipalPlaneIsRefused) {
  auto scene = RandomVolumeScene(60, 0.0, 4);
  const Rigid3d world_from_camera = scene.camera_from_world.inverse();
  scene.observations[3].point = world_from_camera * Eigen::Vector3d(400, -200, 0);
  const DltResult r = SolveDlt(scene.observations);
  EXPECT_EQ(r.status, DltStatus::kPointsBehind) << r.message;
}

TEST(Dlt, RefusesCoplanarAndNearlyCoplanar) {
  const auto scene = RandomVolumeScene(6, 0.0, 1);
  for (auto solver : {DltOptions::Solver::kNormalEquations, DltOptions::Solver::kFullSvd}) {
    DltOptions options;
    options.solver = solver;
    const DltResult flat = SolveDlt(Project(scene, Grid(0.0)), options);
    EXPECT_EQ(flat.status, DltStatus::kCoplanar);
    EXPECT_NE(flat.message.find("the points are coplanar"), std::string::npos) << flat.message;
    EXPECT_NE(flat.message.find("calib-tsai"), std::string::npos);
    EXPECT_EQ(DltStatusExitCode(flat.status), ExitCode::kDegenerate);
    const DltResult thin = SolveDlt(Project(scene, Grid(1.0)), options);  // 1 mm over 0.7 m
    EXPECT_EQ(thin.status, DltStatus::kCoplanar);
    EXPECT_NE(thin.message.find("nearly coplanar"), std::string::npos) << thin.message;
  }
  // Thick enough to solve, thin enough to warn.
  const DltResult warned = SolveDlt(Project(scene, Grid(20.0)));  // thickness/extent ≈ 0.04
  EXPECT_EQ(warned.status, DltStatus::kOk) << warned.message;
  ASSERT_EQ(warned.warnings.size(), 1u);
  EXPECT_NE(warned.warnings[0].find("thin"), std::string::npos);
}

TEST(Dlt, RefusesCollinear) {
  const auto scene = RandomVolumeScene(6, 0.0, 1);
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 20; ++i) line.emplace_back(-300 + 30.0 * i, 50 + 10.0 * i, 800 + 40.0 * i);
  const DltResult r = SolveDlt(Project(scene, line));
  EXPECT_EQ(r.status, DltStatus::kCollinear);
  EXPECT_NE(r.message.find("collinear"), std::string::npos);
  std::vector<Observation> same(10, Observation{Eigen::Vector3d(1, 2, 3), Eigen::Vector2d(100, 100)});
  const DltResult coincident = SolveDlt(same);
  EXPECT_EQ(coincident.status, DltStatus::kCoincident);
  EXPECT_NE(coincident.message.find("the same 3-D point"), std::string::npos);
  EXPECT_EQ(DltStatusExitCode(coincident.status), ExitCode::kDegenerate);
}

// Hartley & Zisserman §7.1.3: points on a plane π plus points on a line through the camera
// centre C leave P ambiguous (P + (PD)πᵀ fits them all, D the line's direction). The cloud is
// not thin, so only the singular values of the system reveal it.
TEST(Dlt, RefusesCriticalConfiguration) {
  const auto scene = RandomVolumeScene(6, 0.0, 1);
  std::vector<Eigen::Vector3d> points = Grid(0.0);
  const Eigen::Vector3d centre = scene.camera_from_world.inverse().t;
  const Eigen::Vector3d target(40, -30, 1500);
  for (int i = 0; i < 12; ++i) points.push_back(centre + (0.3 + 0.1 * i) * (target - centre));
  for (auto solver : {DltOptions::Solver::kNormalEquations, DltOptions::Solver::kFullSvd}) {
    DltOptions options;
    options.solver = solver;
    const DltResult r = SolveDlt(Project(scene, points), options);
    EXPECT_EQ(r.status, DltStatus::kIllConditioned) << r.message;
    EXPECT_NE(r.message.find("critical configuration"), std::string::npos);
    EXPECT_LT(r.conditioning, options.min_conditioning);
  }
}

// A point mirrored through the camera centre projects to the same pixel but lies behind it.
TEST(Dlt, RefusesPointsBehindTheCamera) {
  auto scene = RandomVolumeScene(100, 0.0, 3);
  const Eigen::Vector3d centre = scene.camera_from_world.inverse().t;
  scene.observations[42].point = 2 * centre - scene.observations[42].point;
  const DltResult r = SolveDlt(scene.observations);
  EXPECT_EQ(r.status, DltStatus::kPointsBehind);
  EXPECT_EQ(r.n_behind, 1u);
  EXPECT_EQ(r.deepest_behind, 42u);
  EXPECT_EQ(DltStatusExitCode(r.status), ExitCode::kBadInput);
}

TEST(Dlt, RefusesMirroredWorld) {
  auto scene = RandomVolumeScene(100, 0.0, 3);
  for (auto& o : scene.observations) o.point.x() = -o.point.x();
  const DltResult r = SolveDlt(scene.observations);
  EXPECT_EQ(r.status, DltStatus::kMirrored);
  EXPECT_NE(r.message.find("mirrored"), std::string::npos);
}

TEST(Dlt, ProjectionMatrixIsNormalized) {
  const auto scene = RandomVolumeScene(100, 0.0, 8);
  const DltResult r = SolveDlt(scene.observations);
  ASSERT_EQ(r.status, DltStatus::kOk);
  EXPECT_NEAR((r.P.block<1, 3>(2, 0).norm()), 1.0, 1e-15);
  // With a unit third row, P's depth row is the point's depth in the camera frame.
  for (const Observation& o : scene.observations) {
    const double depth = (scene.camera_from_world * o.point).z();
    EXPECT_NEAR(r.P.row(2).dot(o.point.homogeneous()), depth, 1e-9 * depth);
  }
}

}  // namespace
}  // namespace vstcal
