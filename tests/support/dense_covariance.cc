#include "support/dense_covariance.h"

#include <Eigen/Cholesky>

#include "vstcal/estimators/reprojection_cost.h"
#include "vstcal/estimators/robust_loss.h"
#include "vstcal/geometry/linalg.h"

namespace vstcal::testing {
namespace {

using MatrixL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

template <typename Model>
void Accumulate(const Correspondences& c, const std::vector<double>& params, const std::vector<Rigid3d>& poses,
                const RefineOptions& options, const std::vector<double>& sigma, DenseCovariance* out, MatrixL* information) {
  const int g = out->free.size();
  const auto loss = MakeLoss(options);
  const Eigen::MatrixXd B = out->free.basis;
  for (size_t v = 0; v < c.views.size(); ++v) {
    const size_t pose = c.rig == Rig::kVolume ? 0 : v;
    const ReprojectionCost<Model> cost(c.views[v].observations, poses[pose]);
    for (size_t k = 0; k < cost.size(); ++k) {
      double r[2];
      Eigen::Matrix<double, 2, Model::kNumParams, Eigen::RowMajor> Jt;
      Eigen::Matrix<double, 2, 6, Eigen::RowMajor> Jp;
      if (!cost.EvaluatePointAtReference(k, params.data(), r, Jt.data(), Jp.data())) continue;
      double weight = 1.0 / (sigma[v] * sigma[v]);
      if (loss) {
        double rho[3];
        loss->Evaluate(r[0] * r[0] + r[1] * r[1], rho);
        weight *= rho[1];
      }
      // The point's rows touch the intrinsics and pose `pose`: their small Gram matrix, summed in
      // long double (the oracle's rounding must stay below what it is compared with, also where
      // the information is ill-conditioned: a rational lens's k1, k2, k4), is scattered into place.
      Eigen::MatrixXd J(2, g + 6);
      J.leftCols(g) = Jt * B;
      J.rightCols(6) = Jp;
      const MatrixL Jl = J.cast<long double>();
      const MatrixL gram = static_cast<long double>(weight) * Jl.transpose() * Jl;
      const Eigen::Index at = g + 6 * static_cast<Eigen::Index>(pose);
      information->topLeftCorner(g, g) += gram.topLeftCorner(g, g);
      information->block(0, at, g, 6) += gram.topRightCorner(g, 6);
      information->block(at, 0, 6, g) += gram.bottomLeftCorner(6, g);
      information->block(at, at, 6, 6) += gram.bottomRightCorner(6, 6);
    }
  }
}

}  // namespace

DenseCovariance DenseCovarianceAt(const Correspondences& c, const Camera& camera, const std::vector<Rigid3d>& poses,
                                  const RefineOptions& options, double sigma_px,
                                  const std::optional<std::vector<double>>& sigma_per_view) {
  DenseCovariance out;
  const AnyLensModel model = RefinedModel(camera.model, options);
  const std::vector<double> params = PromotedParams(camera, model);
  out.free = MakeFreeIntrinsics(model, options);
  const Eigen::Index n = out.free.size() + 6 * static_cast<Eigen::Index>(poses.size());
  out.information = Eigen::MatrixXd::Zero(n, n);
  const std::vector<double> sigma = sigma_per_view.value_or(std::vector<double>(c.views.size(), sigma_px));
  MatrixL M = MatrixL::Zero(n, n);
  std::visit([&](auto m) { Accumulate<decltype(m)>(c, params, poses, options, sigma, &out, &M); }, model);
  out.information = M.cast<double>();
  const Eigen::VectorXd eigenvalues = DecomposeSymmetric(out.information, /*with_vectors=*/false).values;
  out.unscaled_eigenvalue_ratio = eigenvalues.minCoeff() / eigenvalues.maxCoeff();
  // The inverse in long double (64-bit mantissa) on the Jacobi-scaled matrix: the oracle's own
  // rounding must stay far below the 1e-9 it is compared at. (The old refine.cc inverted the
  // unscaled matrix by a double eigen decomposition: on 12 planar views that was off by up to
  // 4e-7 relative from this.)
  const Eigen::Matrix<long double, Eigen::Dynamic, 1> s = M.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::LDLT<MatrixL> ldlt(s.asDiagonal() * M * s.asDiagonal());
  if (ldlt.info() != Eigen::Success) return out;
  const MatrixL inverse = s.asDiagonal() * ldlt.solve(MatrixL::Identity(n, n)) * s.asDiagonal();
  out.covariance = (0.5L * (inverse + inverse.transpose())).cast<double>();
  return out;
}

}  // namespace vstcal::testing
