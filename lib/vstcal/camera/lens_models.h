// The one projection (DESIGN.md "One projection"): every solver, Ceres cost function, Monte Carlo
// engine and report projects through these templates, with double or ceres::Jet.
//
// Parameter layout shared by every model: [fx, fy, cx, cy, s, <distortion in the model's order>],
// pixels, with K = [[fx, s, cx], [0, fy, cy], [0, 0, 1]] (docs/conventions.md#intrinsics).
// A model is a struct with kName, kNumParams, kParamNames and a templated Distort(); Project()
// and Unproject() come from LensModel<Model> and are written once.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string_view>

#include <Eigen/Core>
#include <ceres/jet.h>

namespace vstcal {

inline constexpr int kNumIntrinsicParams = 5;  // fx, fy, cx, cy, s
// Where each shared intrinsic sits in every model's parameter vector; the distortion terms follow
// in the model's own order (kParamNames; Camera::Param reads one by name).
namespace intrinsic {
inline constexpr int kFx = 0, kFy = 1, kCx = 2, kCy = 3, kSkew = 4;
}  // namespace intrinsic

template <typename Model>
struct LensModel {
  // Projects p_cam (camera frame, any length unit) to pixels. Returns false, leaving px
  // untouched, when the point is not in front of the camera (z ≤ 0): callers count such
  // failures, they never turn them into zero residuals.
  template <typename T>
  static bool Project(const T* params, const T* p_cam, T* px) {
    if (!(p_cam[2] > T(0))) return false;
    const T x = p_cam[0] / p_cam[2];
    const T y = p_cam[1] / p_cam[2];
    T xd, yd;
    Model::Distort(params + kNumIntrinsicParams, x, y, &xd, &yd);
    px[0] = params[0] * xd + params[4] * yd + params[2];
    px[1] = params[1] * yd + params[3];
    return true;
  }

  // Project with its Jacobians, in double (Basalt's pattern): d_px_d_params is 2 × kNumParams and
  // d_px_d_p is 2 × 3, both row-major, either may be null. The distortion is differentiated by
  // ceres::Jet through the same Model::Distort (dimension 2 + number of distortion terms, or 2
  // when only d_px_d_p is asked for); the rest (division by z, K) analytically. Returns false,
  // writing nothing, when z ≤ 0.
  static bool ProjectWithJacobians(const double* params, const double* p_cam, double* px, double* d_px_d_params,
                                   double* d_px_d_p) {
    if (!d_px_d_params && !d_px_d_p) return Project(params, p_cam, px);  // no Jets needed
    if (!(p_cam[2] > 0)) return false;
    // Without d_px_d_params the coefficients are constants: a Jet of x and y alone is enough.
    if (!d_px_d_params) return ProjectWithJets<false>(params, p_cam, px, nullptr, d_px_d_p);
    return ProjectWithJets<true>(params, p_cam, px, d_px_d_params, d_px_d_p);
  }

 private:
  // ProjectWithJacobians with Jets of x, y and, kWithParams, the distortion coefficients.
  template <bool kWithParams>
  static bool ProjectWithJets(const double* params, const double* p_cam, double* px, double* d_px_d_params,
                              double* d_px_d_p) {
    constexpr int kDistortion = Model::kNumParams - kNumIntrinsicParams;
    using Jet = ceres::Jet<double, 2 + (kWithParams ? kDistortion : 0)>;
    const double inv_z = 1.0 / p_cam[2];
    const double x = p_cam[0] * inv_z, y = p_cam[1] * inv_z;
    Jet d[kDistortion > 0 ? kDistortion : 1];
    for (int i = 0; i < kDistortion; ++i) {
      if constexpr (kWithParams) {
        d[i] = Jet(params[kNumIntrinsicParams + i], 2 + i);
      } else {
        d[i] = Jet(params[kNumIntrinsicParams + i]);
      }
    }
    Jet xd, yd;
    Model::Distort(d, Jet(x, 0), Jet(y, 1), &xd, &yd);
    const double fx = params[0], fy = params[1], s = params[4];
    px[0] = fx * xd.a + s * yd.a + params[2];
    px[1] = fy * yd.a + params[3];
    if constexpr (kWithParams) {
      double* du = d_px_d_params;
      double* dv = d_px_d_params + Model::kNumParams;
      du[0] = xd.a, du[1] = 0, du[2] = 1, du[3] = 0, du[4] = yd.a;
      dv[0] = 0, dv[1] = yd.a, dv[2] = 0, dv[3] = 1, dv[4] = 0;
      for (int i = 0; i < kDistortion; ++i) {
        du[kNumIntrinsicParams + i] = fx * xd.v[2 + i] + s * yd.v[2 + i];
        dv[kNumIntrinsicParams + i] = fy * yd.v[2 + i];
      }
    }
    if (d_px_d_p) {
      // ∂(u, v)/∂(x, y), then ∂(x, y)/∂p = [[1/z, 0, −x/z], [0, 1/z, −y/z]].
      const double ux = fx * xd.v[0] + s * yd.v[0], uy = fx * xd.v[1] + s * yd.v[1];
      const double vx = fy * yd.v[0], vy = fy * yd.v[1];
      d_px_d_p[0] = ux * inv_z, d_px_d_p[1] = uy * inv_z, d_px_d_p[2] = -(ux * x + uy * y) * inv_z;
      d_px_d_p[3] = vx * inv_z, d_px_d_p[4] = vy * inv_z, d_px_d_p[5] = -(vx * x + vy * y) * inv_z;
    }
    return true;
  }

 public:
  // Inverse of Project in double: the ray (x, y, 1) in the camera frame whose projection is px.
  // The distortion is inverted by Newton's method with the Jacobian of Model::Distort taken by
  // ceres::Jet (the same code as the forward model). Returns nullopt where Newton does not
  // converge or the distortion folds over (Jacobian determinant ≤ 0): outside the model's
  // valid domain there is no unique ray.
  static std::optional<Eigen::Vector3d> Unproject(const double* params, const Eigen::Vector2d& px) {
    const double fx = params[0], fy = params[1], cx = params[2], cy = params[3], s = params[4];
    const double yd = (px.y() - cy) / fy;
    const double xd = (px.x() - cx - s * yd) / fx;
    if constexpr (Model::kNumParams == kNumIntrinsicParams) {
      return Eigen::Vector3d(xd, yd, 1.0);
    } else {
      return UndistortNewton(params + kNumIntrinsicParams, xd, yd);
    }
  }

 private:
  static std::optional<Eigen::Vector3d> UndistortNewton(const double* distortion, double xd, double yd) {
    using Jet2 = ceres::Jet<double, 2>;
    std::array<Jet2, Model::kNumParams - kNumIntrinsicParams> dist;
    for (size_t i = 0; i < dist.size(); ++i) dist[i] = Jet2(distortion[i]);
    double x = xd, y = yd;
    for (int iteration = 0; iteration < 50; ++iteration) {
      Jet2 jx, jy;
      Model::Distort(dist.data(), Jet2(x, 0), Jet2(y, 1), &jx, &jy);
      const double ex = jx.a - xd, ey = jy.a - yd;
      const double a = jx.v[0], b = jx.v[1], c = jy.v[0], d = jy.v[1];
      const double det = a * d - b * c;
      if (!(det > 0)) return std::nullopt;
      const double dx = (d * ex - b * ey) / det;
      const double dy = (a * ey - c * ex) / det;
      x -= dx;
      y -= dy;
      if (std::abs(dx) + std::abs(dy) <= 1e-15 * (1.0 + std::abs(x) + std::abs(y))) {
        return Eigen::Vector3d(x, y, 1.0);
      }
    }
    return std::nullopt;
  }
};

// Pure pinhole: no distortion. Name "none" in files.
struct PinholeModel : LensModel<PinholeModel> {
  static constexpr std::string_view kName = "none";
  static constexpr int kNumParams = kNumIntrinsicParams;
  static constexpr std::array<std::string_view, kNumParams> kParamNames = {"fx", "fy", "cx", "cy", "s"};

  template <typename T>
  static void Distort(const T* /*distortion*/, const T& x, const T& y, T* xd, T* yd) {
    *xd = x;
    *yd = y;
  }
};

// The tangential (decentering) term shared by the Brown–Conrady models, added to a radial
// scaling: x_d = x·radial + 2 p1 x y + p2 (r² + 2x²), y_d = y·radial + p1 (r² + 2y²) + 2 p2 x y.
template <typename T>
void ScaleAndDecenter(const T& x, const T& y, const T& r2, const T& radial, const T& p1, const T& p2, T* xd, T* yd) {
  const T xy = x * y;
  *xd = x * radial + T(2) * p1 * xy + p2 * (r2 + T(2) * x * x);
  *yd = y * radial + p1 * (r2 + T(2) * y * y) + T(2) * p2 * xy;
}

// Brown–Conrady radial–tangential on normalized coordinates, OpenCV's coefficient order
// (k1, k2, p1, p2, k3); mrcal's LENSMODEL_OPENCV5 (LENSMODEL_OPENCV4 when k3 = 0). Seed 001
// Eq. 15–17 in Heikkilä's notation is the same model in other units: docs/math/camera-model.md.
struct RadialTangentialModel : LensModel<RadialTangentialModel> {
  static constexpr std::string_view kName = "radial-tangential";
  static constexpr int kNumParams = kNumIntrinsicParams + 5;
  static constexpr std::array<std::string_view, kNumParams> kParamNames = {
      "fx", "fy", "cx", "cy", "s", "k1", "k2", "p1", "p2", "k3"};

  template <typename T>
  static void Distort(const T* d, const T& x, const T& y, T* xd, T* yd) {
    const T& k1 = d[0];
    const T& k2 = d[1];
    const T& p1 = d[2];
    const T& p2 = d[3];
    const T& k3 = d[4];
    const T r2 = x * x + y * y;
    const T radial = T(1) + r2 * (k1 + r2 * (k2 + r2 * k3));
    ScaleAndDecenter(x, y, r2, radial, p1, p2, xd, yd);
  }
};

// OpenCV's rational model (CALIB_RATIONAL_MODEL; mrcal's LENSMODEL_OPENCV8), OpenCV's coefficient
// order (k1, k2, p1, p2, k3, k4, k5, k6): the radial scaling is a ratio of two cubics in r²,
// (1 + k1 r² + k2 r⁴ + k3 r⁶) / (1 + k4 r² + k5 r⁴ + k6 r⁶), which follows wide-angle lenses
// further out than one polynomial can. With k4 = k5 = k6 = 0 it is "radial-tangential".
// Where the denominator reaches 0 the pixel is not finite: calibrated lenses keep it positive
// over the image (docs/math/camera-model.md#rational).
struct RationalModel : LensModel<RationalModel> {
  static constexpr std::string_view kName = "rational";
  static constexpr int kNumParams = kNumIntrinsicParams + 8;
  static constexpr std::array<std::string_view, kNumParams> kParamNames = {
      "fx", "fy", "cx", "cy", "s", "k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6"};

  template <typename T>
  static void Distort(const T* d, const T& x, const T& y, T* xd, T* yd) {
    const T& k1 = d[0];
    const T& k2 = d[1];
    const T& p1 = d[2];
    const T& p2 = d[3];
    const T& k3 = d[4];
    const T& k4 = d[5];
    const T& k5 = d[6];
    const T& k6 = d[7];
    const T r2 = x * x + y * y;
    const T radial = (T(1) + r2 * (k1 + r2 * (k2 + r2 * k3))) / (T(1) + r2 * (k4 + r2 * (k5 + r2 * k6)));
    ScaleAndDecenter(x, y, r2, radial, p1, p2, xd, yd);
  }
};

}  // namespace vstcal
