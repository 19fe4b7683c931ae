#include "vstcal/camera/intrinsics.h"

#include <cmath>

namespace vstcal {

SkewForm SkewFormFromK(const Eigen::Matrix3d& K) {
  SkewForm f;
  f.fu = K(0, 0);
  f.theta_rad = std::atan2(K(0, 0), -K(0, 1));  // cot θ = −s/fu, θ ∈ (0, π) for fu > 0
  f.fv = K(1, 1) * std::sin(f.theta_rad);
  f.u0 = K(0, 2);
  f.v0 = K(1, 2);
  return f;
}

Eigen::Matrix3d KFromSkewForm(const SkewForm& f) {
  Eigen::Matrix3d K;
  // θ = 90° exactly gives s = 0 exactly (cos(π/2) rounds to 6e-17, not 0).
  const bool square = f.theta_rad == 0.5 * 3.14159265358979323846;
  const double c = square ? 0.0 : std::cos(f.theta_rad), s = square ? 1.0 : std::sin(f.theta_rad);
  K << f.fu, -f.fu * c / s, f.u0, 0, f.fv / s, f.v0, 0, 0, 1;
  return K;
}

}  // namespace vstcal

namespace vstcal {

double FocalFromHorizontalFov(int width, double hfov_rad) { return 0.5 * width / std::tan(0.5 * hfov_rad); }

}  // namespace vstcal
