// The analytic Jacobians of ProjectWithJacobians and of the reprojection cost against autodiff
// through the templated projection (Jets everywhere) and against central differences.
#include <gtest/gtest.h>

#include <ceres/jet.h>

#include "vstcal/calib/reprojection_cost.h"
#include "vstcal/camera/camera.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

// A wide-angle lens: the denominator 1 + k4 r² + k5 r⁴ + k6 r⁶ stays above 1 over the points drawn.
const std::vector<double> kRationalParams = {700, 690, 640, 360, 1.5, 0.12, -0.05, 0.001, -0.0005, 0.004, 0.45, 0.03, 0.002};

template <typename Model>
void CheckProjectWithJacobians(const std::vector<double>& params) {
  constexpr int n = Model::kNumParams;
  using Jet = ceres::Jet<double, n + 3>;
  const CounterRng rng(5, 0);
  for (uint64_t k = 0; k < 50; ++k) {
    const auto a = rng.Uniform2(k, 0), b = rng.Uniform2(k, 1);
    const double p[3] = {(a[0] - 0.5) * 2, (a[1] - 0.5) * 1.2, 0.8 + 2 * b[0]};
    Jet jp[n], jx[3], jq[2];
    for (int i = 0; i < n; ++i) jp[i] = Jet(params[i], i);
    for (int i = 0; i < 3; ++i) jx[i] = Jet(p[i], n + i);
    ASSERT_TRUE(Model::Project(jp, jx, jq));
    double q[2], d_params[2 * n], d_p[6];
    ASSERT_TRUE(Model::ProjectWithJacobians(params.data(), p, q, d_params, d_p));
    for (int r = 0; r < 2; ++r) {
      EXPECT_NEAR(q[r], jq[r].a, 1e-12 * std::abs(jq[r].a));
      for (int i = 0; i < n; ++i) EXPECT_NEAR(d_params[r * n + i], jq[r].v(i), 1e-10 * (1 + std::abs(jq[r].v(i)))) << i;
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(d_p[r * 3 + i], jq[r].v(n + i), 1e-10 * (1 + std::abs(jq[r].v(n + i))));
    }
  }
  const double behind[3] = {0.1, 0.2, -1};
  double q[2];
  EXPECT_FALSE(Model::ProjectWithJacobians(params.data(), behind, q, nullptr, nullptr));
}

TEST(ProjectWithJacobians, MatchesAutodiffForEveryModel) {
  CheckProjectWithJacobians<PinholeModel>({700, 690, 640, 360, 1.5});
  CheckProjectWithJacobians<RadialTangentialModel>({700, 690, 640, 360, 1.5, -0.17, 0.03, 0.001, -0.0005, -0.002});
  CheckProjectWithJacobians<RationalModel>(kRationalParams);
}

// The rational model's Jacobians against central differences of Project itself (no Jets: a check
// independent of the autodiff both sides of the test above use).
TEST(ProjectWithJacobians, RationalMatchesCentralDifferences) {
  constexpr int n = RationalModel::kNumParams;
  const CounterRng rng(9, 0);
  for (uint64_t k = 0; k < 20; ++k) {
    const auto a = rng.Uniform2(k, 0), b = rng.Uniform2(k, 1);
    const double p[3] = {(a[0] - 0.5) * 2, (a[1] - 0.5) * 1.2, 0.8 + 2 * b[0]};
    double q[2], d_params[2 * n], d_p[6];
    ASSERT_TRUE(RationalModel::ProjectWithJacobians(kRationalParams.data(), p, q, d_params, d_p));
    for (int i = 0; i < n + 3; ++i) {
      std::vector<double> plus = kRationalParams, minus = kRationalParams;
      double p_plus[3] = {p[0], p[1], p[2]}, p_minus[3] = {p[0], p[1], p[2]};
      double* const x_plus = i < n ? &plus[i] : &p_plus[i - n];
      double* const x_minus = i < n ? &minus[i] : &p_minus[i - n];
      const double h = 1e-6 * std::max(1.0, std::abs(*x_plus));
      *x_plus += h;
      *x_minus -= h;
      double q_plus[2], q_minus[2];
      ASSERT_TRUE(RationalModel::Project(plus.data(), p_plus, q_plus));
      ASSERT_TRUE(RationalModel::Project(minus.data(), p_minus, q_minus));
      for (int r = 0; r < 2; ++r) {
        const double analytic = i < n ? d_params[r * n + i] : d_p[r * 3 + i - n];
        EXPECT_NEAR(analytic, (q_plus[r] - q_minus[r]) / (2 * h), 1e-6 * (1 + std::abs(analytic))) << "column " << i << " row " << r;
      }
    }
  }
}

// The cost's Jacobians at a non-zero pose perturbation δ against central differences of its own
// residuals (so J_l(ω) is exercised).
TEST(ReprojectionCost, JacobiansMatchCentralDifferences) {
  const std::vector<double> params = {700, 690, 640, 360, 0.5, -0.17, 0.03, 0.001, -0.0005, -0.002};
  const Rigid3d reference = Rigid3d::FromRotvec(Eigen::Vector3d(0.1, -0.2, 0.05), Eigen::Vector3d(20, -10, 900));
  std::vector<Observation> obs;
  for (int i = 0; i < 5; ++i) obs.push_back({Eigen::Vector3d(-200 + 100 * i, 50.0 * i - 100, 30.0 * i), Eigen::Vector2d(600 + i, 350 - i)});
  const ReprojectionCost<RadialTangentialModel> cost(obs, reference);
  double delta[6] = {0.03, -0.02, 0.05, 4, -3, 6};
  std::vector<double> p = params;
  const double* blocks[2] = {p.data(), delta};
  std::vector<double> r(10), Ji(100), Jp(60);
  double* jacobians[2] = {Ji.data(), Jp.data()};
  ASSERT_TRUE(cost.Evaluate(blocks, r.data(), jacobians));
  auto residuals = [&](const double* params_in, const double* delta_in) {
    std::vector<double> out(10);
    const double* b[2] = {params_in, delta_in};
    EXPECT_TRUE(cost.Evaluate(b, out.data(), nullptr));
    return out;
  };
  for (int k = 0; k < 6; ++k) {
    double plus[6], minus[6];
    std::copy(delta, delta + 6, plus);
    std::copy(delta, delta + 6, minus);
    const double h = k < 3 ? 1e-7 : 1e-5;
    plus[k] += h;
    minus[k] -= h;
    const auto rp = residuals(p.data(), plus), rm = residuals(p.data(), minus);
    for (int i = 0; i < 10; ++i) EXPECT_NEAR(Jp[i * 6 + k], (rp[i] - rm[i]) / (2 * h), 1e-5 * (1 + std::abs(Jp[i * 6 + k]))) << k;
  }
  for (int k = 0; k < 10; ++k) {
    std::vector<double> plus = params, minus = params;
    const double h = 1e-6 * std::max(1.0, std::abs(params[k]));
    plus[k] += h;
    minus[k] -= h;
    const auto rp = residuals(plus.data(), delta), rm = residuals(minus.data(), delta);
    for (int i = 0; i < 10; ++i) EXPECT_NEAR(Ji[i * 10 + k], (rp[i] - rm[i]) / (2 * h), 1e-5 * (1 + std::abs(Ji[i * 10 + k]))) << k;
  }
}

TEST(LeftJacobianSO3, MatchesNumericDerivativeOfExp) {
  const Eigen::Vector3d y(0.3, -1.1, 2.0);
  for (const Eigen::Vector3d& omega : {Eigen::Vector3d(0.4, -0.7, 1.1), Eigen::Vector3d(1e-7, 2e-7, -1e-7)}) {
    const Eigen::Matrix3d analytic = -Hat(Eigen::Vector3d(RotationFromRotvec(omega) * y)) * LeftJacobianSO3(omega);
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d h = Eigen::Vector3d::Zero();
      h(k) = 1e-6;
      const Eigen::Vector3d numeric = (RotationFromRotvec<double>(omega + h) * y - RotationFromRotvec<double>(omega - h) * y) / 2e-6;
      EXPECT_LT((analytic.col(k) - numeric).norm(), 1e-8);
    }
  }
}

}  // namespace
}  // namespace vstcal
