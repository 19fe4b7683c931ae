#include "support/interop_cameras.h"

namespace vstcal::testing {

std::vector<CalibratedCamera> InteropCameras(bool with_pose) {
  Eigen::Matrix3d K;
  K << 1234.5678901234567, 0, 640.1000000000001, 0, 1230.000000001, 359.9, 0, 0, 1;
  const double rt[5] = {-0.1, 0.01, 1e-12, -2.5e-12, 3e-5};
  const double rt_k3_zero[5] = {-0.2, 0.03, 7e-4, -1e-12, 0.0};
  const double rational[8] = {0.412, -0.083, 6e-4, -3e-4, 4.2e-3, 0.645, -1e-12, 9.3e-3};
  std::vector<CalibratedCamera> cameras;
  for (const Camera& camera :
       {Camera::FromK(K, ImageSize{1280, 720}), Camera::FromK(K, ImageSize{1280, 720}, RadialTangentialModel{}, rt),
        Camera::FromK(K, ImageSize{1280, 720}, RadialTangentialModel{}, rt_k3_zero),
        Camera::FromK(K, ImageSize{1280, 720}, RationalModel{}, rational)}) {
    CalibratedCamera c;
    c.camera = camera;
    c.method = "synthetic";
    if (with_pose) {
      c.camera_from_world =
          Rigid3d::FromRotvec(Eigen::Vector3d(0.1, -0.2, 0.3), Eigen::Vector3d(10.5, -20.25, 3000.125));
    }
    cameras.push_back(c);
  }
  return cameras;
}

}  // namespace vstcal::testing
