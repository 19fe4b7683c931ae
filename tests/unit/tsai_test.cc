// Tsai's two-stage method: exact recovery on data that follows Tsai's own model (non-coplanar and
// coplanar), the κ₁ → (k1, k2, k3) conversion against its series and its stated error, and the
// refusals.
#include <gtest/gtest.h>

#include <cmath>

#include "vstcal/calib/tsai.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

struct TsaiTruth {
  double f, sx, kappa1;
  Eigen::Vector2d c;
  Rigid3d camera_from_world;
};

// Pixels of world points under Tsai's model: undistorted sensor (X_u, Y_u) = f (x/z, y/z), then
// the distorted radius solves r_u = r_d (1 + κ₁ r_d²), then u = Cx + sx X_d, v = Cy + Y_d.
std::vector<Observation> TsaiPixels(const TsaiTruth& t, const std::vector<Eigen::Vector3d>& points, double noise = 0,
                                    uint64_t seed = 1) {
  std::vector<Observation> obs;
  const CounterRng rng(seed, 0);
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p = t.camera_from_world * points[i];
    const Eigen::Vector2d undistorted = t.f * p.head<2>() / p.z();
    const double ru = undistorted.norm();
    double rd = ru;
    for (int k = 0; k < 100; ++k) rd -= (rd * (1 + t.kappa1 * rd * rd) - ru) / (1 + 3 * t.kappa1 * rd * rd);
    const Eigen::Vector2d distorted = ru > 0 ? undistorted * (rd / ru) : undistorted;
    const auto e = rng.Normal2(i, 0);
    obs.push_back({points[i], Eigen::Vector2d(t.c.x() + t.sx * distorted.x(), t.c.y() + distorted.y()) +
                                  noise * Eigen::Vector2d(e[0], e[1])});
  }
  return obs;
}

std::vector<Eigen::Vector3d> Volume() {
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < 6; ++k) {
    for (int j = 0; j < 7; ++j) {
      for (int i = 0; i < 9; ++i) points.emplace_back(-400 + 100 * i, -300 + 100 * j, 300.0 * k);
    }
  }
  return points;
}

TsaiTruth Truth() {
  return TsaiTruth{1500, 1.012, 4e-8, Eigen::Vector2d(639.5, 511.5),
                   Rigid3d::FromRotvec(Eigen::Vector3d(0.08, -0.15, 0.04), Eigen::Vector3d(60, -40, 2200))};
}

TEST(Tsai, NonCoplanarRecoversTsaisOwnModelExactly) {
  const TsaiTruth truth = Truth();
  const TsaiResult r = SolveTsai(TsaiPixels(truth, Volume()), ImageSize{1280, 1024});
  ASSERT_EQ(r.status, TsaiStatus::kOk) << r.message;
  EXPECT_EQ(r.variant, TsaiOptions::Variant::kNonCoplanar);
  EXPECT_NEAR(r.f, truth.f, 1e-6 * truth.f);
  EXPECT_NEAR(r.sx, truth.sx, 1e-9);
  EXPECT_NEAR(r.kappa1, truth.kappa1, 1e-6 * truth.kappa1);
  EXPECT_LT(AngleBetween(r.camera_from_world.R, truth.camera_from_world.R), 1e-9);
  EXPECT_LT((r.camera_from_world.t - truth.camera_from_world.t).norm(), 1e-6);
  // The converted camera reproduces Tsai's projection to within the conversion error it states.
  for (const Observation& o : TsaiPixels(truth, Volume())) {
    const Eigen::Vector2d q = *r.camera.Project(r.camera_from_world * o.point);
    EXPECT_LT((q - o.pixel).norm(), r.conversion_max_error_px + 1e-6);
  }
  EXPECT_LT(r.conversion_max_error_px, 0.01);
}

TEST(Tsai, CoplanarRecoversATiltedBoard) {
  TsaiTruth truth = Truth();
  truth.sx = 1.0;  // known in the coplanar variant
  // A board tilted 35° about a diagonal, given in world coordinates off the Z = 0 plane.
  const Rigid3d world_from_board = Rigid3d::FromRotvec(DegToRad(35) * Eigen::Vector3d(1, 1, 0).normalized(),
                                                       Eigen::Vector3d(30, -20, 500));
  std::vector<Eigen::Vector3d> board;
  for (int j = 0; j < 9; ++j) {
    for (int i = 0; i < 12; ++i) board.push_back(world_from_board * Eigen::Vector3d(-550 + 100 * i, -400 + 100 * j, 0));
  }
  const TsaiResult r = SolveTsai(TsaiPixels(truth, board), ImageSize{1280, 1024});
  ASSERT_EQ(r.status, TsaiStatus::kOk) << r.message;
  EXPECT_EQ(r.variant, TsaiOptions::Variant::kCoplanar);
  EXPECT_NEAR(r.f, truth.f, 1e-6 * truth.f);
  EXPECT_NEAR(r.kappa1, truth.kappa1, 1e-6 * truth.kappa1);
  EXPECT_LT(AngleBetween(r.camera_from_world.R, truth.camera_from_world.R), 1e-9);
  EXPECT_LT((r.camera_from_world.t - truth.camera_from_world.t).norm(), 1e-6);
  EXPECT_LT(r.plane_rms, 1e-9);
}

// Tsai's method does not depend on the world's unit: coordinates scaled by 1e±150 and 1e±300,
// whose squares overflow or underflow, give the same f, κ₁ and R and a scaled t (they used to
// give a wrong planarity verdict and no camera).
TEST(Tsai, ScaledCoordinatesGiveTheSameCamera) {
  const TsaiTruth truth = Truth();
  const std::vector<Observation> obs = TsaiPixels(truth, Volume());
  const TsaiResult reference = SolveTsai(obs, ImageSize{1280, 1024});
  ASSERT_EQ(reference.status, TsaiStatus::kOk) << reference.message;
  for (const double scale : {1e-300, 1e-150, 1e150, 1e300}) {
    std::vector<Observation> scaled = obs;
    for (Observation& o : scaled) o.point *= scale;
    const TsaiResult r = SolveTsai(scaled, ImageSize{1280, 1024});
    ASSERT_EQ(r.status, TsaiStatus::kOk) << scale << ": " << r.message;
    EXPECT_EQ(r.variant, TsaiOptions::Variant::kNonCoplanar);
    EXPECT_NEAR(r.f, reference.f, 1e-9 * reference.f) << scale;
    EXPECT_NEAR(r.kappa1, reference.kappa1, 1e-6 * std::abs(reference.kappa1)) << scale;
    EXPECT_LT(AngleBetween(r.camera_from_world.R, reference.camera_from_world.R), 1e-9) << scale;
    EXPECT_LT((r.camera_from_world.t / scale - reference.camera_from_world.t).norm(),
              1e-9 * reference.camera_from_world.t.norm()) << scale;
  }
}

// With noise the estimates scatter around the truth; a loose, derived check (f to 0.1 % for
// 0.2 px noise on 378 points) guards the whole pipeline, the refinement does the rest.
TEST(Tsai, NoisyVolumeIsClose) {
  const TsaiTruth truth = Truth();
  const TsaiResult r = SolveTsai(TsaiPixels(truth, Volume(), 0.2, 9), ImageSize{1280, 1024});
  ASSERT_EQ(r.status, TsaiStatus::kOk) << r.message;
  EXPECT_NEAR(r.f, truth.f, 1e-3 * truth.f);
  EXPECT_NEAR(r.sx, truth.sx, 1e-3);
}

// The least-squares conversion beats the series k1 = −K, k2 = 3K², k3 = −12K³ (the inverse of
// r_n = r_d (1 + K r_d²) to third order) and its stated error bounds both.
TEST(Tsai, KappaConversionMatchesItsSeriesForSmallDistortion) {
  for (double K : {-0.08, -0.02, 0.01, 0.05}) {
    const double r_max = 0.8;
    const KappaConversion c = ConvertTsaiKappa(K, r_max);
    EXPECT_NEAR(c.k1, -K, 20 * std::pow(std::abs(K), 4) + 1e-12);
    EXPECT_NEAR(c.k2, 3 * K * K, 200 * std::pow(std::abs(K), 4) + 1e-12);
    double series_error = 0;
    for (int i = 1; i <= 100; ++i) {
      const double rn = r_max * i / 100;
      double rd = rn;
      for (int k = 0; k < 100; ++k) rd -= (rd * (1 + K * rd * rd) - rn) / (1 + 3 * K * rd * rd);
      const double r2 = rn * rn;
      const double fitted = rn * (1 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3)));
      const double series = rn * (1 + r2 * (-K + r2 * (3 * K * K - 12 * K * K * K * r2)));
      EXPECT_LE(std::abs(fitted - rd), c.max_error + 1e-15);
      series_error = std::max(series_error, std::abs(series - rd));
    }
    EXPECT_LE(c.max_error, series_error);
  }
}

TEST(Tsai, RefusalsAndVariants) {
  const TsaiTruth truth = Truth();
  std::vector<Eigen::Vector3d> plane;
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 8; ++i) plane.emplace_back(-350 + 100 * i, -250 + 100 * j, 0);
  }
  TsaiOptions forced;
  forced.variant = TsaiOptions::Variant::kNonCoplanar;
  const TsaiResult r1 = SolveTsai(TsaiPixels(truth, plane), ImageSize{1280, 1024}, forced);
  EXPECT_EQ(r1.status, TsaiStatus::kCoplanarForced);
  EXPECT_NE(r1.message.find("coplanar"), std::string::npos);
  EXPECT_EQ(TsaiStatusExitCode(r1.status), ExitCode::kDegenerate);
  // A board parallel to the image plane: f and Tz cannot be separated.
  const TsaiResult r2 = SolveTsai(TsaiPixels(TsaiTruth{1500, 1, 0, {639.5, 511.5}, Rigid3d::FromRotvec({0, 0, 0.2}, {10, 20, 2000})}, plane),
                                  ImageSize{1280, 1024});
  EXPECT_EQ(r2.status, TsaiStatus::kDegenerate) << r2.message;
  EXPECT_NE(r2.message.find("parallel"), std::string::npos) << r2.message;
  const std::vector<Eigen::Vector3d> few = {{-400, -300, 0}, {400, -300, 300}, {-400, 300, 600},
                                            {400, 300, 900},  {0, 0, 1200},    {-200, 100, 1500}};
  const TsaiResult r3 = SolveTsai(TsaiPixels(truth, few), ImageSize{1280, 1024});
  EXPECT_EQ(r3.status, TsaiStatus::kTooFewPoints);
  EXPECT_EQ(TsaiStatusExitCode(r3.status), ExitCode::kBadInput);
  TsaiOptions coplanar;
  coplanar.variant = TsaiOptions::Variant::kCoplanar;
  EXPECT_EQ(SolveTsai(TsaiPixels(truth, Volume()), ImageSize{1280, 1024}, coplanar).status, TsaiStatus::kDegenerate);
}

// With pixel noise a board parallel to the image no longer makes stage 2 rank deficient, but f
// stays undetermined: its standard error says so. Tilted by 30°, f is within 5σ of the truth.
TEST(Tsai, FocalStandardErrorRefusesANoisyParallelBoard) {
  std::vector<Eigen::Vector3d> plane;
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 8; ++i) plane.emplace_back(-350 + 100 * i, -250 + 100 * j, 0);
  }
  const TsaiTruth parallel{1500, 1, 0, {639.5, 511.5}, Rigid3d::FromRotvec({0, 0, 0.2}, {10, 20, 2000})};
  const TsaiResult r = SolveTsai(TsaiPixels(parallel, plane, 0.3), ImageSize{1280, 1024});
  EXPECT_EQ(r.status, TsaiStatus::kDegenerate) << r.message;
  EXPECT_NE(r.message.find("f is not determined"), std::string::npos) << r.message;
  EXPECT_GT(r.f_sigma, 0.1 * r.f);

  TsaiTruth tilted = parallel;
  tilted.camera_from_world = Rigid3d::FromRotvec(DegToRad(30) * Eigen::Vector3d(1, 0.5, 0).normalized(), {10, 20, 2000});
  const TsaiResult t = SolveTsai(TsaiPixels(tilted, plane, 0.3), ImageSize{1280, 1024});
  ASSERT_EQ(t.status, TsaiStatus::kOk) << t.message;
  EXPECT_GT(t.f_sigma, 0);
  EXPECT_LT(std::abs(t.f - tilted.f), 5 * t.f_sigma);
}

// A point moved behind the camera is named; a mirrored (left-handed) world is told apart from it:
// Tsai's first stage fits both, and only the mirrored rotation puts every point in front.
TEST(Tsai, PointsBehindTheCameraAndMirroredWorld) {
  const TsaiTruth truth = Truth();
  std::vector<Observation> obs = TsaiPixels(truth, Volume(), 0.2);
  const Eigen::Vector3d centre = truth.camera_from_world.inverse().t;
  obs[100].point = 2 * centre - obs[100].point;  // same ray, behind the camera
  const TsaiResult behind = SolveTsai(obs, ImageSize{1280, 1024});
  EXPECT_EQ(behind.status, TsaiStatus::kPointsBehind) << behind.message;
  EXPECT_EQ(behind.n_behind, 1u);
  EXPECT_EQ(behind.deepest_behind, 100u);
  EXPECT_NE(behind.message.find("1 of 378 points lie behind the camera"), std::string::npos) << behind.message;
  EXPECT_EQ(TsaiStatusExitCode(behind.status), ExitCode::kBadInput);

  std::vector<Observation> mirrored = TsaiPixels(truth, Volume(), 0.2);
  for (Observation& o : mirrored) o.point.x() = -o.point.x();
  const TsaiResult m = SolveTsai(mirrored, ImageSize{1280, 1024});
  EXPECT_EQ(m.status, TsaiStatus::kMirrored) << m.message;
  EXPECT_NE(m.message.find("mirrored"), std::string::npos) << m.message;
  EXPECT_EQ(TsaiStatusExitCode(m.status), ExitCode::kBadInput);
}

// Ty² from stage 1's block C = [[r1, r2], [r4, r5]] / Ty, for rotations whose r9 is known: a target
// nearly edge-on (r9 = 1e-8, where (S − √(S² − 4D²))/(2D²) loses ~9 % to cancellation) and exactly
// edge-on with a vanishing column of C (D = 0, Tsai's 1/S, which 1/max(row norm²) is not).
TEST(Tsai, CoplanarTySquaredNearAndAtEdgeOn) {
  const double ty = 250;
  const auto ty2_of = [&](const Eigen::Matrix3d& R) {
    return CoplanarTySquared(R(0, 0) / ty, R(0, 1) / ty, R(1, 0) / ty, R(1, 1) / ty);
  };
  for (const double r9 : {0.5, 1e-4, 1e-8, 1e-12}) {
    // Rz(0.3) Rx(θ) Rz(0.7) has r9 = cos θ and every entry of C non-zero.
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(std::acos(r9), Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    ASSERT_NEAR(R(2, 2), r9, 1e-15);
    EXPECT_NEAR(ty2_of(R), ty * ty, 1e-12 * ty * ty) << "r9 = " << r9;
  }
  // Rz(φ) Rx(90°), exact: rows (c, 0, s), (s, 0, −c), (0, 1, 0); C's second column vanishes.
  const double c = 0.6, s = 0.8;
  Eigen::Matrix3d edge_on;
  edge_on << c, 0, s, s, 0, -c, 0, 1, 0;
  EXPECT_NEAR(ty2_of(edge_on), ty * ty, 1e-12 * ty * ty);
}

}  // namespace
}  // namespace vstcal
