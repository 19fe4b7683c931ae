#include "vstcal/geometry/point_registration.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace vstcal {
namespace {

Eigen::Vector3d Centroid(std::span<const Eigen::Vector3d> points) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : points) c += p;
  return c / static_cast<double>(points.size());
}

}  // namespace

std::optional<RegistrationFrame> RegistrationFrame::For(std::span<const Eigen::Vector3d> points_in_a) {
  if (points_in_a.size() < 3) return std::nullopt;
  RegistrationFrame f;
  f.centroid = Centroid(points_in_a);
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  double spread = 0;
  for (const auto& a : points_in_a) {
    const Eigen::Vector3d c = a - f.centroid;
    f.centred.push_back(c);
    C += c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose();
    spread += c.squaredNorm();
  }
  // Collinear points leave C singular (no moment about their line): the rotation about it is free.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C);
  if (!(eig.eigenvalues()(0) > 1e-12 * spread)) return std::nullopt;
  f.inverse_inertia = C.inverse();
  return f;
}

std::optional<Rigid3d> RegisterPointsHorn(std::span<const Eigen::Vector3d> points_in_a,
                                          std::span<const Eigen::Vector3d> points_in_b) {
  if (points_in_a.size() != points_in_b.size() || !RegistrationFrame::For(points_in_a)) return std::nullopt;
  const Eigen::Vector3d ca = Centroid(points_in_a), cb = Centroid(points_in_b);
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();  // M(i, j) = Σ ã_i b̃_j (Horn's S_ij)
  for (size_t k = 0; k < points_in_a.size(); ++k) M += (points_in_a[k] - ca) * (points_in_b[k] - cb).transpose();
  const double Sxx = M(0, 0), Sxy = M(0, 1), Sxz = M(0, 2), Syx = M(1, 0), Syy = M(1, 1), Syz = M(1, 2),
               Szx = M(2, 0), Szy = M(2, 1), Szz = M(2, 2);
  Eigen::Matrix4d N;  // Horn 1987 Eq. for N, quaternion order (w, x, y, z)
  N << Sxx + Syy + Szz, Syz - Szy, Szx - Sxz, Sxy - Syx,  //
      Syz - Szy, Sxx - Syy - Szz, Sxy + Syx, Szx + Sxz,   //
      Szx - Sxz, Sxy + Syx, -Sxx + Syy - Szz, Syz + Szy,  //
      Sxy - Syx, Szx + Sxz, Syz + Szy, -Sxx - Syy + Szz;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(N);
  const Eigen::Vector4d q = eig.eigenvectors().col(3);  // largest eigenvalue (ascending order)
  const Eigen::Matrix3d R = Eigen::Quaterniond(q(0), q(1), q(2), q(3)).normalized().toRotationMatrix();
  return Rigid3d{R, cb - R * ca};
}

}  // namespace vstcal
