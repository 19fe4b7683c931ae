// The analytic Jacobians of ProjectWithJacobians, of the reprojection cost and of the stereo
// solve's chained (right-camera) cost against autodiff through the templated projection (Jets
// everywhere) and against central differences.
#include <gtest/gtest.h>

#include <ceres/jet.h>

#include "vstcal/estimators/reprojection_cost.h"
#include "vstcal/camera/camera.h"
#include "vstcal/random/philox.h"
#include "vstcal/estimators/chained_reprojection_cost.h"

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

// calib-stereo solve's right-camera cost (estimators/chained_reprojection_cost.h) for one lens model:
// every block's analytic Jacobian — θ_R, δ_rl, δ_v — against central differences of the cost's own
// residuals, at non-zero δ's (so both J_l(ω) are exercised) and unequal weights, over a 9 × 6 board
// (70 mm) tilted 0.5 m in front, covering u ≈ 180…855 px, v ≈ 115…565 px of the right image (radius
// up to 0.75 in normalized coordinates, where distortion is strong). The
// parameters are the first kNumParams of kRationalParams (the models share their prefix).
//
// Tolerance. A central difference with step h is off by the truncation h²/6 · |r⁽³⁾| and the
// rounding ≈ ε |q| / h (q ≤ 1300 px, ε = 2.2e-16). Steps: 1e-6 rad for ω (rounding 3e-7 px/rad;
// r⁽³⁾ ≈ f |p| ≈ 7e5 px gives truncation 1e-7), 1e-4 mm for ρ (rounding 3e-9; r⁽³⁾ ≈ 6 f / z³
// ≈ 2e-5 px/mm³, truncation < 1e-12), 1e-6·max(1, |θ_k|) for the lens (rounding ≤ 3e-7; the
// pinhole and radial-tangential residuals are linear in θ, the rational one's denominator gives
// truncation < 1e-9). 2e-6 · (1 + |J|) is a few times the worst of these, and a wrong term (a
// missing J_l, a sign, a transposed R) is off by O(|J|) ≫ that.
template <typename Model>
void CheckChainedCostJacobians() {
  constexpr int n = Model::kNumParams;
  const std::vector<double> params(kRationalParams.begin(), kRationalParams.begin() + n);
  const Rigid3d right_from_left = Rigid3d::FromRotvec(Eigen::Vector3d(0.002, -0.004, 0.001), Eigen::Vector3d(-63, 0.2, -0.4));
  const Rigid3d left_from_board = Rigid3d::FromRotvec(Eigen::Vector3d(0.25, -0.35, 0.1), Eigen::Vector3d(-250, -170, 480));
  std::vector<Observation> obs;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 9; ++c) {
      obs.push_back({Eigen::Vector3d(70.0 * c, 70.0 * r, 0.0), Eigen::Vector2d(600 + 7 * c, 340 - 5 * r), 0.5 + 0.1 * ((r + c) % 4)});
    }
  }
  const ChainedReprojectionCost<Model> cost(obs, right_from_left, left_from_board);
  const int m = 2 * static_cast<int>(obs.size());
  std::vector<double> theta = params;
  double delta_rl[6] = {0.01, -0.02, 0.015, 1.5, -0.8, 2.0};
  double delta_v[6] = {-0.03, 0.02, 0.04, 5, -4, 8};
  std::vector<double> r(m), j_theta(m * n), j_rl(m * 6), j_v(m * 6);
  const double* blocks[3] = {theta.data(), delta_rl, delta_v};
  double* jacobians[3] = {j_theta.data(), j_rl.data(), j_v.data()};
  ASSERT_TRUE(cost.Evaluate(blocks, r.data(), jacobians));

  // Column k of block b by central differences, against the analytic one.
  double* block_values[3] = {theta.data(), delta_rl, delta_v};
  const std::vector<double>* analytic[3] = {&j_theta, &j_rl, &j_v};
  const int sizes[3] = {n, 6, 6};
  for (int b = 0; b < 3; ++b) {
    for (int k = 0; k < sizes[b]; ++k) {
      double& x = block_values[b][k];
      const double x0 = x;
      const double h = b == 0 ? 1e-6 * std::max(1.0, std::abs(x0)) : k < 3 ? 1e-6 : 1e-4;
      std::vector<double> plus(m), minus(m);
      x = x0 + h;
      ASSERT_TRUE(cost.Evaluate(blocks, plus.data(), nullptr));
      x = x0 - h;
      ASSERT_TRUE(cost.Evaluate(blocks, minus.data(), nullptr));
      x = x0;
      double largest = 0;
      for (int i = 0; i < m; ++i) {
        const double a = (*analytic[b])[i * sizes[b] + k];
        EXPECT_NEAR(a, (plus[i] - minus[i]) / (2 * h), 2e-6 * (1 + std::abs(a))) << "block " << b << " column " << k << " residual " << i;
        largest = std::max(largest, std::abs(a));
      }
      EXPECT_GT(largest, 0.0) << "block " << b << " column " << k;  // every parameter moves some residual
    }
  }

  // The per-point evaluation at δ = 0 (the covariance's) gives the rows Evaluate gives there.
  const double zero[6] = {0, 0, 0, 0, 0, 0};
  const double* at_reference[3] = {theta.data(), zero, zero};
  ASSERT_TRUE(cost.Evaluate(at_reference, r.data(), jacobians));
  for (size_t i = 0; i < obs.size(); i += 13) {
    double residual[2], d_theta[2 * n], d_rl[12], d_view[12];
    ASSERT_TRUE(cost.EvaluatePointAtReference(i, theta.data(), residual, d_theta, d_rl, d_view));
    for (int row = 0; row < 2; ++row) {
      EXPECT_EQ(residual[row], r[2 * i + row]);
      for (int k = 0; k < n; ++k) EXPECT_EQ(d_theta[row * n + k], j_theta[(2 * i + row) * n + k]);
      for (int k = 0; k < 6; ++k) {
        EXPECT_EQ(d_rl[row * 6 + k], j_rl[(2 * i + row) * 6 + k]);
        EXPECT_EQ(d_view[row * 6 + k], j_v[(2 * i + row) * 6 + k]);
      }
    }
  }
}

TEST(ChainedReprojectionCost, JacobiansMatchCentralDifferencesForEveryLensModel) {
  ForEachLensModel([](auto model) { CheckChainedCostJacobians<decltype(model)>(); });
}

TEST(ChainedReprojectionCost, PointBehindTheRightCameraRejectsTheStep) {
  const std::vector<Observation> obs = {{Eigen::Vector3d(0, 0, 0), Eigen::Vector2d(640, 360)}};
  const ChainedReprojectionCost<PinholeModel> cost(obs, Rigid3d::FromRotvec(Eigen::Vector3d::Zero(), Eigen::Vector3d(-63, 0, 0)),
                                                   Rigid3d::FromRotvec(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 500)));
  const std::vector<double> params = {700, 700, 640, 360, 0};
  const double delta_rl[6] = {0, 0, 0, 0, 0, -600};  // moves the right camera 100 mm beyond the point
  const double delta_v[6] = {0, 0, 0, 0, 0, 0};
  const double* blocks[3] = {params.data(), delta_rl, delta_v};
  double r[2];
  EXPECT_FALSE(cost.Evaluate(blocks, r, nullptr));
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
