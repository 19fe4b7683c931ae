// lib/vstcal/geometry/linalg: each decomposition against the identity that defines it, on matrices
// whose answers are known by construction (eigenvalues and singular values put in by hand, a
// least-squares system with an exact solution, a rank-deficient one), and the contracts the
// callers rely on: ordering, which factors are filled, the rank's threshold.
#include <gtest/gtest.h>

#include <cmath>

#include "vstcal/geometry/linalg.h"

namespace vstcal {
namespace {

// An orthonormal basis from Gram–Schmidt on a fixed, well-conditioned matrix: Q's columns are
// known to be orthonormal without any decomposition under test.
Eigen::MatrixXd LinalgTestOrthonormal(int n) {
  Eigen::MatrixXd M(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) M(i, j) = std::sin(1.0 + 3.0 * i + 7.0 * j) + (i == j ? 3.0 : 0.0);
  }
  Eigen::MatrixXd Q = M;
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < j; ++k) Q.col(j) -= Q.col(k).dot(Q.col(j)) * Q.col(k);
    Q.col(j).normalize();
  }
  return Q;
}

TEST(Linalg, SymmetricEigenReturnsTheValuesPutInIncreasingWithTheirVectors) {
  const Eigen::MatrixXd Q = LinalgTestOrthonormal(5);
  const Eigen::VectorXd lambda = (Eigen::VectorXd(5) << 4.0, -1.0, 9.0, 0.5, 2.0).finished();
  const Eigen::MatrixXd A = Q * lambda.asDiagonal() * Q.transpose();

  const SymmetricEigen eig = DecomposeSymmetric(A);
  const Eigen::VectorXd sorted = (Eigen::VectorXd(5) << -1.0, 0.5, 2.0, 4.0, 9.0).finished();
  EXPECT_LT((eig.values - sorted).cwiseAbs().maxCoeff(), 1e-12);
  ASSERT_EQ(eig.vectors.rows(), 5);
  ASSERT_EQ(eig.vectors.cols(), 5);
  EXPECT_LT((eig.vectors * eig.values.asDiagonal() * eig.vectors.transpose() - A).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((eig.vectors.transpose() * eig.vectors - Eigen::MatrixXd::Identity(5, 5)).cwiseAbs().maxCoeff(), 1e-12);

  const SymmetricEigen values_only = DecomposeSymmetric(A, /*with_vectors=*/false);
  EXPECT_EQ(values_only.vectors.size(), 0);
  EXPECT_LT((values_only.values - sorted).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Linalg, TwelveByTwelveEigenOnItsFixedTypeReconstructs) {
  const Eigen::MatrixXd Q = LinalgTestOrthonormal(12);
  Eigen::VectorXd lambda(12);
  for (int i = 0; i < 12; ++i) lambda(i) = 12.0 - i;  // decreasing in, increasing out
  const Eigen::Matrix<double, 12, 12> A = Q * lambda.asDiagonal() * Q.transpose();
  const SymmetricEigen12 eig = DecomposeSymmetric12(A);
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(eig.values(i), i + 1.0, 1e-12);
  EXPECT_LT((eig.vectors * eig.values.asDiagonal() * eig.vectors.transpose() - A).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Linalg, SvdReturnsTheSingularValuesPutInAndOnlyTheFactorsAskedFor) {
  const Eigen::MatrixXd U = LinalgTestOrthonormal(6).leftCols(3);
  const Eigen::MatrixXd V = LinalgTestOrthonormal(3);
  const Eigen::Vector3d sigma(5.0, 2.0, 0.25);
  const Eigen::MatrixXd A = U * sigma.asDiagonal() * V.transpose();  // 6 × 3

  const SingularValueDecomposition values_only = DecomposeSvd(A, 0);
  EXPECT_LT((values_only.singular_values - sigma).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(values_only.U.size(), 0);
  EXPECT_EQ(values_only.V.size(), 0);

  const SingularValueDecomposition thin = DecomposeSvd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  ASSERT_EQ(thin.U.rows(), 6);
  ASSERT_EQ(thin.U.cols(), 3);
  ASSERT_EQ(thin.V.rows(), 3);
  EXPECT_LT((thin.U * thin.singular_values.asDiagonal() * thin.V.transpose() - A).cwiseAbs().maxCoeff(), 1e-12);

  // The full V of a wide matrix holds its null space: A v = 0 for the last column.
  const SingularValueDecomposition wide = DecomposeSvd(A.transpose(), Eigen::ComputeFullV);
  ASSERT_EQ(wide.V.cols(), 6);
  EXPECT_EQ(wide.U.size(), 0);
  EXPECT_LT((A.transpose() * wide.V.col(5)).norm(), 1e-12);
}

TEST(Linalg, LeastSquaresSolvesAndCountsTheRankAboveItsThreshold) {
  Eigen::MatrixXd A(5, 3);
  A << 1, 0, 2, 0, 1, 1, 1, 1, 0, 2, -1, 1, 0, 3, 1;
  const Eigen::Vector3d x(0.5, -2.0, 1.25);
  const Eigen::VectorXd Ax = A * x;
  const LeastSquaresSolution exact = SolveLeastSquares(A, Ax);
  EXPECT_EQ(exact.rank, 3);
  EXPECT_LT((exact.x - x).cwiseAbs().maxCoeff(), 1e-12);

  // An inconsistent right-hand side: the solution makes the residual orthogonal to A's columns.
  const Eigen::VectorXd b = (Eigen::VectorXd(5) << 1, 2, 3, 4, 5).finished();
  const LeastSquaresSolution fit = SolveLeastSquares(A, b);
  EXPECT_LT((A.transpose() * (A * fit.x - b)).cwiseAbs().maxCoeff(), 1e-12);

  // A third column equal to the first two's sum up to 1e-8: rank 3 by the default threshold (about
  // n ε), rank 2 by a threshold of 1e-6 (Tsai's stages ask 1e-10 of theirs).
  Eigen::MatrixXd near(5, 3);
  near.leftCols(2) = A.leftCols(2);
  near.col(2) = A.col(0) + A.col(1);
  near(4, 2) += 1e-8;
  EXPECT_EQ(SolveLeastSquares(near, b).rank, 3);
  EXPECT_EQ(SolveLeastSquares(near, b, 1e-6).rank, 2);

  // Several right-hand sides: a column of X for each column of B.
  Eigen::MatrixXd B(5, 2);
  B.col(0) = A * x;
  B.col(1) = b;
  const Eigen::MatrixXd X = SolveLeastSquares(A, B);
  EXPECT_LT((X.col(0) - x).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((X.col(1) - fit.x).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Linalg, HouseholderRIsUpperTriangularAndKeepsTheGramMatrix) {
  Eigen::MatrixXd A(6, 4);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 4; ++j) A(i, j) = std::cos(0.3 + 1.7 * i - 0.9 * j) + (i == j ? 2.0 : 0.0);
  }
  const Eigen::MatrixXd R = HouseholderR(A);
  ASSERT_EQ(R.rows(), 6);
  ASSERT_EQ(R.cols(), 4);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < std::min(i, 4); ++j) EXPECT_EQ(R(i, j), 0.0) << i << "," << j;
  }
  // A = Q R with Q orthogonal, so Rᵀ R = Aᵀ A.
  EXPECT_LT((R.transpose() * R - A.transpose() * A).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace vstcal
