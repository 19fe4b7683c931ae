#include "vstcal/geometry/linalg.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

namespace vstcal {

SymmetricEigen DecomposeSymmetric(const Eigen::MatrixXd& A, bool with_vectors) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, with_vectors ? Eigen::ComputeEigenvectors
                                                                           : Eigen::EigenvaluesOnly);
  SymmetricEigen out;
  out.values = eig.eigenvalues();
  if (with_vectors) out.vectors = eig.eigenvectors();
  return out;
}

SymmetricEigen12 DecomposeSymmetric12(const Eigen::Matrix<double, 12, 12>& A) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>> eig(A);
  return {eig.eigenvalues(), eig.eigenvectors()};
}

SingularValueDecomposition DecomposeSvd(const Eigen::MatrixXd& A, unsigned options) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, options);
  SingularValueDecomposition out;
  out.singular_values = svd.singularValues();
  if (svd.computeU()) out.U = svd.matrixU();
  if (svd.computeV()) out.V = svd.matrixV();
  return out;
}

LeastSquaresSolution SolveLeastSquares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                       std::optional<double> rank_threshold) {
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (rank_threshold) qr.setThreshold(*rank_threshold);
  return {qr.solve(b), qr.rank()};
}

Eigen::MatrixXd SolveLeastSquares(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(A).solve(B);
}

Eigen::MatrixXd HouseholderR(const Eigen::MatrixXd& A) {
  return Eigen::HouseholderQR<Eigen::MatrixXd>(A).matrixQR().triangularView<Eigen::Upper>();
}

}  // namespace vstcal
