#include "vstcal/estimators/arrow_information.h"

#include <cmath>

#include "vstcal/core/error.h"
#include "vstcal/geometry/linalg.h"

namespace vstcal {
namespace {

// 1/√d for a diagonal entry; 0 marks an entry without information (d ≤ 0 or not finite).
double InverseRoot(double d) { return d > 0 && std::isfinite(d) ? 1.0 / std::sqrt(d) : 0.0; }

Eigen::VectorXd Unit(Eigen::Index n, Eigen::Index i) {
  Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
  e(i) = 1;
  return e;
}

// The upper-triangular factor of a QR decomposition of `rows`, `keep` rows of it (the rest are
// zero when rows.rows() ≥ keep, or are padded with zeros).
Eigen::MatrixXd TriangularFactor(const Eigen::MatrixXd& rows, Eigen::Index keep) {
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(keep, rows.cols());
  if (rows.rows() == 0) return R;
  const Eigen::Index n = std::min(keep, rows.rows());
  R.topRows(n) = HouseholderR(rows).topRows(n);
  return R;
}

// Smallest singular value of a square matrix and its right singular vector.
std::pair<double, Eigen::VectorXd> SmallestSingular(const Eigen::MatrixXd& A) {
  const SingularValueDecomposition svd = DecomposeSvd(A, Eigen::ComputeFullV);
  const Eigen::Index last = A.cols() - 1;
  return {svd.singular_values(last), svd.V.col(last)};
}

// X = R⁻¹ R⁻ᵀ for an upper-triangular R: (R⁻ᵀ)ᵀ R⁻ᵀ, symmetric by construction.
template <typename Matrix>
Eigen::MatrixXd InverseGram(const Matrix& R) {
  const Eigen::MatrixXd Rt_inverse =
      R.transpose().template triangularView<Eigen::Lower>().solve(Eigen::MatrixXd::Identity(R.rows(), R.cols()));
  return Rt_inverse.transpose() * Rt_inverse;
}

}  // namespace

ArrowInformation::ArrowInformation(int num_global, int num_poses)
    : R_global_(Eigen::MatrixXd::Zero(num_global, num_global)),
      R_pose_(static_cast<size_t>(num_poses), Matrix6Xd::Zero(6, 6 + num_global)),
      diagonal_global_(Eigen::VectorXd::Zero(num_global)),
      diagonal_pose_(static_cast<size_t>(num_poses), Vector6d::Zero()) {}

void ArrowInformation::AddRows(std::span<const int> global_columns, int pose, const Eigen::Ref<const Eigen::MatrixXd>& J) {
  const Eigen::Index k = static_cast<Eigen::Index>(global_columns.size());
  const Eigen::Index g = num_global();
  VSTCAL_CHECK(J.cols() == k + 6, "rows span the listed globals and one pose");
  VSTCAL_CHECK(pose >= 0 && pose < num_poses(), "pose index");
  // [R_v R_vg] stacked on the new rows, pose columns first: one QR eliminates the pose from all of
  // them; the rows below its 6 touch the globals only and fold into R_g.
  Eigen::MatrixXd stacked = Eigen::MatrixXd::Zero(6 + J.rows(), 6 + g);
  stacked.topRows(6) = R_pose_[pose];
  stacked.bottomLeftCorner(J.rows(), 6) = J.rightCols(6);
  for (Eigen::Index a = 0; a < k; ++a) stacked.col(6 + global_columns[a]).tail(J.rows()) = J.col(a);
  diagonal_pose_[pose] += J.rightCols(6).colwise().squaredNorm().transpose();
  for (Eigen::Index a = 0; a < k; ++a) diagonal_global_(global_columns[a]) += J.col(a).squaredNorm();
  const Eigen::MatrixXd R = TriangularFactor(stacked, 6 + g);
  R_pose_[pose] = R.topRows(6);
  if (g == 0) return;
  Eigen::MatrixXd globals(2 * g, g);
  globals << R_global_, R.bottomRightCorner(g, g);
  R_global_ = TriangularFactor(globals, g);
}

ArrowInverse InvertArrow(const ArrowInformation& M, double scale) {
  const Eigen::Index g = M.num_global();
  const int P = M.num_poses();
  ArrowInverse out;
  ArrowObservability& verdict = out.observability;

  // Jacobi scaling: D^{-1/2} from the diagonal of M, applied to the roots' columns (R D^{-1/2} is
  // the root of D^{-1/2} M D^{-1/2}). A zero diagonal entry is a parameter no residual moves.
  Eigen::VectorXd sg(g);
  for (Eigen::Index i = 0; i < g; ++i) {
    sg(i) = InverseRoot(M.global_diagonal()(i));
    if (sg(i) == 0) {
      verdict.weakest_direction = Unit(g, i);
      return out;
    }
  }
  std::vector<Vector6d> sp(static_cast<size_t>(P));
  std::vector<Matrix6d> Rv(static_cast<size_t>(P));
  std::vector<Matrix6Xd> G(static_cast<size_t>(P));  // R̂_v⁻¹ R̂_vg = V̂_v⁻¹ Ŵ_vᵀ
  for (int v = 0; v < P; ++v) {
    for (int i = 0; i < 6; ++i) {
      sp[v](i) = InverseRoot(M.pose_diagonal(v)(i));
      if (sp[v](i) == 0) {
        verdict.singular_pose = v;
        verdict.weakest_direction = Unit(6, i);
        return out;
      }
    }
    Rv[v] = M.pose_root(v).leftCols<6>() * sp[v].asDiagonal();
    const auto [smallest, direction] = SmallestSingular(Rv[v]);
    if (!(smallest * smallest > kObservabilityFloor)) {
      verdict.smallest_eigenvalue = smallest * smallest;
      verdict.singular_pose = v;
      verdict.weakest_direction = direction;
      return out;
    }
    G[v] = Rv[v].triangularView<Eigen::Upper>().solve(Matrix6Xd(M.pose_root(v).rightCols(g) * sg.asDiagonal()));
  }
  Eigen::MatrixXd S_inverse(g, g);
  if (g > 0) {
    const Eigen::MatrixXd Rg = M.global_root() * sg.asDiagonal();
    const auto [smallest, direction] = SmallestSingular(Rg);
    verdict.smallest_eigenvalue = smallest * smallest;
    verdict.weakest_direction = direction;
    if (!(verdict.smallest_eigenvalue > kObservabilityFloor)) return out;
    S_inverse = InverseGram(Rg);
  }
  verdict.observable = true;

  // Blocks of the scaled inverse, then back to the parameters' units:
  //   Σ̂_gg = Ŝ⁻¹,  Σ̂_vg = −G_v Ŝ⁻¹,  Σ̂_vv = R̂_v⁻¹ R̂_v⁻ᵀ + G_v Ŝ⁻¹ G_vᵀ.
  ArrowCovariance& cov = out.covariance;
  // D^{-1/2} X D^{-1/2} is symmetric only to rounding ((s_i x_ij) s_j vs (s_j x_ji) s_i): the
  // files promise symmetric matrices, bit for bit.
  auto symmetric = [](const auto& m) { return (0.5 * (m + m.transpose())).eval(); };
  cov.global = symmetric(scale * sg.asDiagonal() * S_inverse * sg.asDiagonal());
  cov.pose.resize(static_cast<size_t>(P));
  cov.pose_global.resize(static_cast<size_t>(P));
  for (int v = 0; v < P; ++v) {
    const Matrix6Xd cross = -G[v] * S_inverse;
    const Matrix6d pose = InverseGram(Rv[v]) - cross * G[v].transpose();
    cov.pose[v] = symmetric(Matrix6d(scale * sp[v].asDiagonal() * pose * sp[v].asDiagonal()));
    cov.pose_global[v] = scale * sp[v].asDiagonal() * cross * sg.asDiagonal();
  }
  return out;
}

}  // namespace vstcal
