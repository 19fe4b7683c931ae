// The Ceres manifold of a refinement's free intrinsics (estimators/free_intrinsics.h), shared by every
// problem that moves a lens: the single-camera refinement and the stereo solve.
#pragma once

#include <ceres/manifold.h>

#include <Eigen/Core>
#include <Eigen/QR>

namespace vstcal {

// θ ⊞ β = θ + B β over the free intrinsics' basis B (estimators/free_intrinsics.h): what a
// ceres::SubsetManifold does when B only selects, and also a tie (one coordinate moving fx and fy).
class LinearManifold final : public ceres::Manifold {
 public:
  explicit LinearManifold(const Eigen::MatrixXd& basis)
      : B_(basis), B_pseudo_inverse_(basis.completeOrthogonalDecomposition().pseudoInverse()) {}
  int AmbientSize() const override { return static_cast<int>(B_.rows()); }
  int TangentSize() const override { return static_cast<int>(B_.cols()); }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    Eigen::Map<Eigen::VectorXd>(x_plus_delta, B_.rows()) =
        Eigen::Map<const Eigen::VectorXd>(x, B_.rows()) + B_ * Eigen::Map<const Eigen::VectorXd>(delta, B_.cols());
    return true;
  }
  bool PlusJacobian(const double* /*x*/, double* jacobian) const override {
    Eigen::Map<RowMajor>(jacobian, B_.rows(), B_.cols()) = B_;
    return true;
  }
  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    Eigen::Map<Eigen::VectorXd>(y_minus_x, B_.cols()) =
        B_pseudo_inverse_ * (Eigen::Map<const Eigen::VectorXd>(y, B_.rows()) - Eigen::Map<const Eigen::VectorXd>(x, B_.rows()));
    return true;
  }
  bool MinusJacobian(const double* /*x*/, double* jacobian) const override {
    Eigen::Map<RowMajor>(jacobian, B_.cols(), B_.rows()) = B_pseudo_inverse_;
    return true;
  }

 private:
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  Eigen::MatrixXd B_, B_pseudo_inverse_;
};

}  // namespace vstcal
