// K ↔ seed 001's Eq. 5 form (Forsyth & Ponce): fu, fv, u0, v0 and the skew angle θ between the
// pixel axes. K = [[fu, −fu·cot θ, u0], [0, fv/sin θ, v0], [0, 0, 1]]; θ = 90° means no skew.
// Derivation: docs/math/camera-model.md.
#pragma once

#include <Eigen/Core>

namespace vstcal {

struct SkewForm {
  double fu = 0;         // px
  double fv = 0;         // px
  double u0 = 0;         // px
  double v0 = 0;         // px
  double theta_rad = 0;  // angle between the pixel axes, (0, π)
};

// K must be upper triangular with K(2,2) = 1 and fx, fy > 0.
SkewForm SkewFormFromK(const Eigen::Matrix3d& K);
Eigen::Matrix3d KFromSkewForm(const SkewForm& form);

}  // namespace vstcal

namespace vstcal {

// Focal length in px that gives a pinhole camera `width` px wide the horizontal field of view
// `hfov_rad` across the whole sensor (from the left edge −0.5 to the right edge W − 0.5 px):
// f = (W/2) / tan(hfov/2).
double FocalFromHorizontalFov(int width, double hfov_rad);

}  // namespace vstcal
