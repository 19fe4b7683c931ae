#include "vstcal/scene/parameter_covariance.h"

#include "vstcal/core/error.h"
#include "vstcal/geometry/linalg.h"

namespace vstcal {
namespace {

// A generalized inverse X of a PSD Σ (Σ X Σ = Σ): D^{-1/2} C⁺ D^{-1/2} with C = D^{-1/2} Σ D^{-1/2}
// its correlation matrix, eigenvalues below kObservabilityFloor × the largest taken as 0.
Eigen::MatrixXd GeneralizedInverse(const Eigen::MatrixXd& sigma) {
  const Eigen::Index n = sigma.rows();
  Eigen::VectorXd s(n);
  for (Eigen::Index i = 0; i < n; ++i) s(i) = sigma(i, i) > 0 ? 1.0 / std::sqrt(sigma(i, i)) : 1.0;
  const SymmetricEigen eig = DecomposeSymmetric(s.asDiagonal() * sigma * s.asDiagonal());
  const double largest = n > 0 ? eig.values.cwiseAbs().maxCoeff() : 0.0;
  Eigen::VectorXd inverse(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double l = eig.values(i);
    inverse(i) = l > kObservabilityFloor * largest ? 1.0 / l : 0.0;
  }
  return s.asDiagonal() * eig.vectors * inverse.asDiagonal() * eig.vectors.transpose() * s.asDiagonal();
}

}  // namespace

std::optional<size_t> ParameterCovariance::Find(std::string_view name) const {
  for (size_t i = 0; i < parameters.size(); ++i) {
    if (parameters[i] == name) return i;
  }
  return std::nullopt;
}

std::optional<size_t> ParameterCovariance::FindPose(std::string_view pose) const {
  for (size_t i = 0; i < poses.size(); ++i) {
    if (poses[i].pose == pose) return i;
  }
  return std::nullopt;
}

Eigen::MatrixXd PropagateCovariance(const ParameterCovariance& cov, const Eigen::MatrixXd& J,
                                    std::span<const PoseJacobian> pose_jacobians) {
  VSTCAL_CHECK(J.cols() == static_cast<Eigen::Index>(cov.parameters.size()), "one column per named parameter");
  Eigen::MatrixXd out = J * cov.matrix * J.transpose();
  if (pose_jacobians.empty()) return out;
  // A_k = J_k Σ_kg (rows × g): each pose's coupling to the named parameters.
  Eigen::MatrixXd sum_A = Eigen::MatrixXd::Zero(J.rows(), J.cols());
  Eigen::MatrixXd own = Eigen::MatrixXd::Zero(J.rows(), J.rows());  // Σ_k A_k X A_kᵀ, removed below
  const Eigen::MatrixXd X = pose_jacobians.size() > 1 ? GeneralizedInverse(cov.matrix) : Eigen::MatrixXd();
  for (const PoseJacobian& pj : pose_jacobians) {
    VSTCAL_CHECK(pj.pose < cov.poses.size() && pj.J.rows() == J.rows() && pj.J.cols() == 6, "pose Jacobian shape");
    const PoseCovariance& p = cov.poses[pj.pose];
    const Eigen::MatrixXd A = pj.J * p.with_parameters;
    out += J * A.transpose() + A * J.transpose() + pj.J * p.matrix * pj.J.transpose();
    sum_A += A;
    if (X.size() > 0) own += A * X * A.transpose();
  }
  if (X.size() > 0) out += sum_A * X * sum_A.transpose() - own;
  return 0.5 * (out + out.transpose());
}

}  // namespace vstcal
