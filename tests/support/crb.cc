#include "support/crb.h"

#include <Eigen/Cholesky>
#include <ceres/jet.h>

namespace vstcal::testing {

Matrix11d PinholeCrb(const Camera& camera, const Rigid3d& camera_from_world, std::span<const Observation> observations,
                     double sigma_px) {
  using Jet = ceres::Jet<double, 11>;
  Jet params[5];
  for (int i = 0; i < 5; ++i) params[i] = Jet(camera.params[i], i);
  const Vec3<Jet> omega(Jet(0.0, 5), Jet(0.0, 6), Jet(0.0, 7));
  const Vec3<Jet> rho(Jet(0.0, 8), Jet(0.0, 9), Jet(0.0, 10));
  const Rigid3<Jet> pose = PerturbLeft(camera_from_world.cast<Jet>(), omega, rho);
  Matrix11d information = Matrix11d::Zero();
  for (const Observation& o : observations) {
    const Vec3<Jet> p_cam = pose * o.point.cast<Jet>();
    Jet px[2];
    if (!PinholeModel::Project(params, p_cam.data(), px)) continue;
    for (const Jet& j : px) information += j.v * j.v.transpose();
  }
  return sigma_px * sigma_px * information.ldlt().solve(Matrix11d::Identity());
}

}  // namespace vstcal::testing
