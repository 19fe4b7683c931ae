// Tsai's two-stage camera calibration (R. Y. Tsai, "A versatile camera calibration technique for
// high-accuracy 3D machine vision metrology using off-the-shelf TV cameras and lenses", IEEE J.
// Robotics and Automation 3(4), 1987; R. Willson's v3 implementation is the classic reference),
// seed 000 §4.2's comparison method. Derivation and the conversion of Tsai's κ₁ to the
// radial-tangential model: docs/math/tsai.md.
//
// Units: pixels throughout. With the principal point (Cx, Cy) known, a pixel gives the distorted
// sensor coordinates Xd = (u − Cx)/sx, Yd = v − Cy (Tsai's dx = dy = 1 px): f is then K's fy and
// f·sx its fx. Tsai's radial model maps distorted to undistorted sensor coordinates,
// X_u = X_d (1 + κ₁ r²), r² = X_d² + Y_d², and the pinhole gives X_u = f x/z, Y_u = f y/z.
#pragma once

#include <optional>
#include <span>
#include <string>

#include "vstcal/scene/correspondences.h"
#include "vstcal/camera/camera.h"
#include "vstcal/core/error.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/core/enum_names.h"

namespace vstcal {

struct TsaiOptions {
  enum class Variant {
    kAuto,         // coplanar when the points' thickness/extent is below min_extent_ratio
    kCoplanar,     // points on one plane (any plane: it is moved to Z = 0 first); sx fixed
    kNonCoplanar,  // a 3-D volume; sx estimated
  };
  static constexpr EnumNames<Variant, 3> kVariantNames = {{{Variant::kAuto, "auto"}, {Variant::kCoplanar, "coplanar"}, {Variant::kNonCoplanar, "non-coplanar"}}};
  Variant variant = Variant::kAuto;
  std::optional<Eigen::Vector2d> principal_point;  // default: the image centre ((W − 1)/2, (H − 1)/2)
  double sx = 1.0;                                 // the coplanar variant's fixed scale factor
  double min_extent_ratio = 1e-2;                  // planarity decision, as DLT's
  // f is told apart from Tz only by the points' depth differences: refuse (kDegenerate) when its
  // standard error exceeds this fraction of f (a plane nearly parallel to the image; Tsai
  // recommends tilting a plane by 30° or more).
  double max_focal_relative_sigma = 0.1;
};

enum class TsaiStatus {
  kOk,
  kTooFewPoints,       // fewer than 7 (non-coplanar) or 5 (coplanar) points
  kCoplanarForced,     // kNonCoplanar asked for coplanar data
  kDegenerate,         // no unique solution (e.g. a plane parallel to the image: f undetermined)
  kPointsBehind,       // points behind the camera the others define (wrong coordinates)
  kMirrored,           // the world frame is left-handed relative to the image
  kNotConverged,       // the nonlinear stage did not converge
};

struct TsaiResult {
  TsaiStatus status = TsaiStatus::kOk;
  std::string message;
  TsaiOptions::Variant variant = TsaiOptions::Variant::kNonCoplanar;  // the one used

  // Tsai's own parameters.
  double f = 0;       // px
  double f_sigma = 0;  // px: f's standard error at stage 3, from the residuals (0 for exact data)
  double sx = 1;      // horizontal scale factor
  double kappa1 = 0;  // px⁻², on distorted sensor coordinates
  Eigen::Vector2d principal_point = Eigen::Vector2d::Zero();
  Rigid3d camera_from_world;
  int nonlinear_iterations = 0;
  size_t n_behind = 0;        // kPointsBehind: points with depth ≤ 0 after the linear stages
  size_t deepest_behind = 0;  // kPointsBehind: index of the deepest of them
  double plane_rms = 0;  // coplanar variant: RMS distance of the points from their plane

  // The same camera in vstcal's model: K = [[f·sx, 0, Cx], [0, f, Cy], [0, 0, 1]] and
  // radial-tangential k1, k2, k3 fitted to κ₁ over the image (p1 = p2 = 0), with the largest
  // pixel error that conversion makes anywhere in the image.
  Camera camera;
  double conversion_max_error_px = 0;
};

TsaiResult SolveTsai(std::span<const Observation> observations, ImageSize image_size, const TsaiOptions& options = {});

ExitCode TsaiStatusExitCode(TsaiStatus status);

// Radial-tangential (k1, k2, k3) closest, in the least-squares sense over normalized radii up to
// r_max, to Tsai's model with K = κ₁ f² in normalized units (x_n = x_d (1 + K r_d²)); returns the
// coefficients and the largest radial error in normalized units over [0, r_max].
struct KappaConversion {
  double k1 = 0, k2 = 0, k3 = 0;
  double max_error = 0;
};
KappaConversion ConvertTsaiKappa(double kappa_normalized, double r_max);

// Tsai's coplanar Ty² from stage 1's block C = [[a1, a2], [a4, a5]] = [[r1, r2], [r4, r5]] / Ty:
// the smaller root of D² Ty⁴ − S Ty² + 1 = 0 (S = ‖C‖_F², D = det C; docs/math/tsai.md#coplanar),
// evaluated as 2 / (S + √(S² − 4D²)). The textbook (S − √(S² − 4D²)) / (2D²) cancels as the target
// turns edge-on (D → 0); this form does not, and at D = 0 it is Tsai's 1/S.
double CoplanarTySquared(double a1, double a2, double a4, double a5);

}  // namespace vstcal
