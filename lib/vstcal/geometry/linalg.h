// Eigen's heavy decompositions behind plain functions over dynamic-size matrices, so that each is
// compiled once, here, rather than again in every translation unit that uses it: one instantiation
// of SelfAdjointEigenSolver, JacobiSVD or ColPivHouseholderQR costs 5–10 CPU-s of GCC's front end
// (docs/performance.md#build, stop 35). Each function is Eigen's algorithm on `Eigen::MatrixXd`,
// unchanged: a caller that used the same decomposition on the dynamic type gets the same bits.
#pragma once

#include <optional>

#include <Eigen/Core>

namespace vstcal {

// A = V diag(λ) Vᵀ for a symmetric A (its lower triangle is read): λ increasing, V's columns the
// unit eigenvectors (empty unless `with_vectors`). Eigen's SelfAdjointEigenSolver: Householder
// tridiagonalisation, then implicit symmetric QR steps.
struct SymmetricEigen {
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
};
SymmetricEigen DecomposeSymmetric(const Eigen::MatrixXd& A, bool with_vectors = true);

// The same on Eigen's fixed 12 × 12 type (DLT's AᵀA, EPnP's MᵀM), whose vectorised arithmetic
// rounds differently from the dynamic type's: 4,443 of 5,000 random matrices differed in some
// bit, so these two keep their type. A 9 × 9 gave the dynamic type's bits in all 5,000, and so did
// hand-eye's 6 × 6 whitening (stop 36: values and vectors; a product with the vectors must keep
// its fixed type); other sizes were not probed (Eigen solves a 3 × 3's tridiagonal form by a
// closed form of its own).
struct SymmetricEigen12 {
  Eigen::Matrix<double, 12, 1> values;
  Eigen::Matrix<double, 12, 12> vectors;
};
SymmetricEigen12 DecomposeSymmetric12(const Eigen::Matrix<double, 12, 12>& A);

// A = U diag(σ) Vᵀ, σ decreasing (min(rows, cols) of them), by two-sided Jacobi rotations after a
// column-pivoting QR when A is not square (Eigen's JacobiSVD). `options` is Eigen's
// (Eigen::ComputeThinU | ComputeFullV …; 0 for the singular values alone); U and V are empty
// unless asked for.
struct SingularValueDecomposition {
  Eigen::VectorXd singular_values;
  Eigen::MatrixXd U, V;
};
SingularValueDecomposition DecomposeSvd(const Eigen::MatrixXd& A, unsigned options);

// min ‖A x − b‖ by column-pivoting Householder QR (Eigen's ColPivHouseholderQR). `rank` counts the
// pivots above `rank_threshold` × the largest (Eigen's default threshold, about n ε, when none);
// x does not depend on it.
struct LeastSquaresSolution {
  Eigen::VectorXd x;
  Eigen::Index rank = 0;
};
LeastSquaresSolution SolveLeastSquares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                       std::optional<double> rank_threshold = std::nullopt);
// The same for several right-hand sides at once (a column of X for each column of B).
Eigen::MatrixXd SolveLeastSquares(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);

// R of A = Q R by unpivoted Householder QR (Eigen's HouseholderQR): rows × cols, zero below the
// diagonal.
Eigen::MatrixXd HouseholderR(const Eigen::MatrixXd& A);

}  // namespace vstcal
