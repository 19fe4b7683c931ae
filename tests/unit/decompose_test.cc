// P → K, R, t on synthetic matrices with known factors, any scale and sign.
#include <gtest/gtest.h>

#include "vstcal/estimators/decompose.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

TEST(Decompose, RecoversFactorsForAnyScaleAndSign) {
  const CounterRng rng(3, 0);
  for (uint64_t i = 0; i < 100; ++i) {
    const auto a = rng.Uniform2(i, 0), b = rng.Uniform2(i, 1), c = rng.Uniform2(i, 2), d = rng.Uniform2(i, 3);
    Eigen::Matrix3d K;
    K << 500 + 1500 * a[0], (b[0] - 0.5) * 20, 300 + 100 * a[1], 0, 500 + 1500 * b[1], 200 + 100 * c[0], 0, 0, 1;
    const Rigid3d pose = Rigid3d::FromRotvec(Eigen::Vector3d(c[1] - 0.5, d[0] - 0.5, 3 * (d[1] - 0.5)),
                                             Eigen::Vector3d(100 * a[0], -50 * b[1], 1000 + 500 * c[0]));
    const double scale = (i % 2 ? -1.0 : 1.0) * (1e-3 + 1e3 * d[0]);
    const Matrix34d P = scale * K * pose.matrix3x4();
    const auto result = DecomposeProjection(NormalizeProjectionScale(P, scale > 0 ? 1.0 : -1.0));
    ASSERT_TRUE(result.has_value());
    EXPECT_LT((result->K - K).norm() / K.norm(), 1e-12);
    EXPECT_LT((result->camera_from_world.R - pose.R).norm(), 1e-12);
    EXPECT_LT((result->camera_from_world.t - pose.t).norm() / pose.t.norm(), 1e-12);
    EXPECT_EQ(result->K(1, 0), 0.0);
    EXPECT_EQ(result->K(2, 2), 1.0);
  }
}

TEST(Decompose, RefusesSingularAndMirrored) {
  Matrix34d singular = Matrix34d::Zero();
  singular(0, 0) = singular(1, 1) = 1;
  singular(2, 3) = 1;
  EXPECT_FALSE(DecomposeProjection(singular).has_value());
  Eigen::Matrix3d K;
  K << 800, 0, 320, 0, 800, 240, 0, 0, 1;
  Matrix34d P = K * Rigid3d::Identity().matrix3x4();
  P(2, 3) = 1;
  P.col(0) *= -1;  // a reflected world
  EXPECT_FALSE(DecomposeProjection(NormalizeProjectionScale(P)).has_value());
}

}  // namespace
}  // namespace vstcal
