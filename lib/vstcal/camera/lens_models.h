// The one projection (DESIGN.md "One projection"): every solver, Ceres cost function, Monte Carlo
// engine and report projects through these templates, with double or ceres::Jet.
//
// Parameter layout shared by every model: [fx, fy, cx, cy, s, <distortion in the model's order>],
// pixels, with K = [[fx, s, cx], [0, fy, cy], [0, 0, 1]] (docs/conventions.md#intrinsics).
// A model is a struct with kName, kNumParams, kParamNames and either
// - a templated Distort() of the normalized point (x, y) = (X/Z, Y/Z): a "plane" model, defined in
//   front of the camera (Z > 0) only; or
// - kOnRay = true and a templated DistortAngle(θ) (with its slope AngleSlope): a "ray" model, whose
//   normalized image radius is a function of the angle θ = atan2(√(X²+Y²), Z) between the ray and
//   the optical axis, so rays at and beyond 90° project; its valid domain is θ < MaxTheta().
// Project() and Unproject() come from LensModel<Model> and are written once.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
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
  // A ray model declares kOnRay = true (see the header comment); plane models inherit false.
  static constexpr bool kOnRay = false;

  // Projects p_cam (camera frame, any length unit) to pixels. Returns false, leaving px
  // untouched, when the point is outside the model's domain: not in front of the camera (z ≤ 0)
  // for a plane model, θ past the valid domain for a ray model (DistortRay). Callers count such
  // failures, they never turn them into zero residuals.
  template <typename T>
  static bool Project(const T* params, const T* p_cam, T* px) {
    T xd, yd;
    if constexpr (Model::kOnRay) {
      if (!DistortRay(params + kNumIntrinsicParams, p_cam[0], p_cam[1], p_cam[2], &xd, &yd)) return false;
    } else {
      if (!(p_cam[2] > T(0))) return false;
      const T x = p_cam[0] / p_cam[2];
      const T y = p_cam[1] / p_cam[2];
      Model::Distort(params + kNumIntrinsicParams, x, y, &xd, &yd);
    }
    px[0] = params[0] * xd + params[4] * yd + params[2];
    px[1] = params[1] * yd + params[3];
    return true;
  }

  // A ray model's distorted normalized point (x_d, y_d) = θd(θ)·(X, Y)/r, r = √(X² + Y²). False
  // where θd stops growing with θ (AngleSlope ≤ 0: past the domain, where the image folds back)
  // or on the axis behind the camera. Near the axis (r/Z < 1e-8) θd/r → 1/Z: the first-order form
  // X/Z, Y/Z is exact in double there (θd = θ(1 + O(θ²)), atan t = t(1 + O(t²))), and keeps
  // values and Jets finite where √ has no derivative (r = 0). docs/math/fisheye.md.
  template <typename T>
  static bool DistortRay(const T* distortion, const T& X, const T& Y, const T& Z, T* xd, T* yd) {
    using std::atan2;
    using std::sqrt;
    const T r2 = X * X + Y * Y;
    if (r2 <= T(1e-16) * (Z * Z)) {
      if (!(Z > T(0))) return false;
      *xd = X / Z;
      *yd = Y / Z;
      return true;
    }
    const T r = sqrt(r2);
    const T theta = atan2(r, Z);
    if (!(Model::AngleSlope(distortion, theta) > T(0))) return false;
    const T scale = Model::DistortAngle(distortion, theta) / r;
    *xd = scale * X;
    *yd = scale * Y;
    return true;
  }

  // A ray model's valid domain: the largest θ ≤ π such that θd grows on all of [0, θ) (AngleSlope
  // > 0), found by steps of π/2000 from the axis and bisection to 1e-12 rad. Project checks the
  // slope at the point's own θ, which is the same condition unless the slope, once negative,
  // turns positive again before π (a lens that folds and unfolds, which no lens is).
  // The last answer is kept per thread: Unproject asks it for every pixel of one lens.
  static double MaxTheta(const double* distortion) {
    static_assert(Model::kOnRay, "MaxTheta is a ray model's domain");
    constexpr int kDistortion = Model::kNumParams - kNumIntrinsicParams;
    thread_local std::array<double, kDistortion> last_distortion;
    thread_local double last = -1;
    if (last >= 0 && std::equal(last_distortion.begin(), last_distortion.end(), distortion)) return last;
    std::copy(distortion, distortion + kDistortion, last_distortion.begin());
    return last = SearchMaxTheta(distortion);
  }

 private:
  static double SearchMaxTheta(const double* distortion) {
    constexpr int kSteps = 2000;
    double good = 0;
    for (int i = 1; i <= kSteps; ++i) {
      const double theta = std::numbers::pi * i / kSteps;
      if (!(Model::AngleSlope(distortion, theta) > 0)) {
        double bad = theta;
        while (bad - good > 1e-12) {
          const double mid = 0.5 * (good + bad);
          (Model::AngleSlope(distortion, mid) > 0 ? good : bad) = mid;
        }
        return good;
      }
      good = theta;
    }
    return std::numbers::pi;
  }

 public:

  // Project with its Jacobians, in double (Basalt's pattern): d_px_d_params is 2 × kNumParams and
  // d_px_d_p is 2 × 3, both row-major, either may be null. The distortion is differentiated by
  // ceres::Jet through the same Model::Distort (dimension 2 + number of distortion terms, or 2
  // when only d_px_d_p is asked for); the rest (division by z, K) analytically. A ray model's
  // Jets are of the point (X, Y, Z) itself, through DistortRay. Returns false, writing nothing,
  // outside the domain (as Project).
  static bool ProjectWithJacobians(const double* params, const double* p_cam, double* px, double* d_px_d_params,
                                   double* d_px_d_p) {
    if (!d_px_d_params && !d_px_d_p) return Project(params, p_cam, px);  // no Jets needed
    if constexpr (!Model::kOnRay) {
      if (!(p_cam[2] > 0)) return false;
    }
    // Without d_px_d_params the coefficients are constants: a Jet of x and y alone is enough.
    if (!d_px_d_params) return ProjectWithJets<false>(params, p_cam, px, nullptr, d_px_d_p);
    return ProjectWithJets<true>(params, p_cam, px, d_px_d_params, d_px_d_p);
  }

 private:
  // ProjectWithJacobians with Jets of the point (x, y for a plane model, X, Y, Z for a ray model)
  // and, kWithParams, the distortion coefficients.
  template <bool kWithParams>
  static bool ProjectWithJets(const double* params, const double* p_cam, double* px, double* d_px_d_params,
                              double* d_px_d_p) {
    constexpr int kDistortion = Model::kNumParams - kNumIntrinsicParams;
    constexpr int kPoint = Model::kOnRay ? 3 : 2;
    using Jet = ceres::Jet<double, kPoint + (kWithParams ? kDistortion : 0)>;
    Jet d[kDistortion > 0 ? kDistortion : 1];
    for (int i = 0; i < kDistortion; ++i) {
      if constexpr (kWithParams) {
        d[i] = Jet(params[kNumIntrinsicParams + i], kPoint + i);
      } else {
        d[i] = Jet(params[kNumIntrinsicParams + i]);
      }
    }
    Jet xd, yd;
    [[maybe_unused]] double inv_z = 0, x = 0, y = 0;
    if constexpr (Model::kOnRay) {
      if (!DistortRay(d, Jet(p_cam[0], 0), Jet(p_cam[1], 1), Jet(p_cam[2], 2), &xd, &yd)) return false;
    } else {
      inv_z = 1.0 / p_cam[2];
      x = p_cam[0] * inv_z, y = p_cam[1] * inv_z;
      Model::Distort(d, Jet(x, 0), Jet(y, 1), &xd, &yd);
    }
    const double fx = params[0], fy = params[1], s = params[4];
    px[0] = fx * xd.a + s * yd.a + params[2];
    px[1] = fy * yd.a + params[3];
    if constexpr (kWithParams) {
      double* du = d_px_d_params;
      double* dv = d_px_d_params + Model::kNumParams;
      du[0] = xd.a, du[1] = 0, du[2] = 1, du[3] = 0, du[4] = yd.a;
      dv[0] = 0, dv[1] = yd.a, dv[2] = 0, dv[3] = 1, dv[4] = 0;
      for (int i = 0; i < kDistortion; ++i) {
        du[kNumIntrinsicParams + i] = fx * xd.v[kPoint + i] + s * yd.v[kPoint + i];
        dv[kNumIntrinsicParams + i] = fy * yd.v[kPoint + i];
      }
    }
    if constexpr (Model::kOnRay) {
      if (d_px_d_p) {
        for (int k = 0; k < 3; ++k) {
          d_px_d_p[k] = fx * xd.v[k] + s * yd.v[k];
          d_px_d_p[3 + k] = fy * yd.v[k];
        }
      }
      return true;
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
  // valid domain there is no unique ray. A ray model's pixel whose ray is 90° or more off the
  // axis has no (x, y, 1) form: nullopt there too (UnprojectRay gives it).
  static std::optional<Eigen::Vector3d> Unproject(const double* params, const Eigen::Vector2d& px) {
    if constexpr (Model::kOnRay) {
      const auto ray = UnprojectRay(params, px);
      if (!ray || !(ray->z() > 0)) return std::nullopt;
      return Eigen::Vector3d(ray->x() / ray->z(), ray->y() / ray->z(), 1.0);
    } else {
      const double fx = params[0], fy = params[1], cx = params[2], cy = params[3], s = params[4];
      const double yd = (px.y() - cy) / fy;
      const double xd = (px.x() - cx - s * yd) / fx;
      if constexpr (Model::kNumParams == kNumIntrinsicParams) {
        return Eigen::Vector3d(xd, yd, 1.0);
      } else {
        return UndistortNewton(params + kNumIntrinsicParams, xd, yd);
      }
    }
  }

  // The direction of the ray through px, for callers that accept any direction (rays beyond 90°
  // included): a plane model's (x, y, 1) as Unproject; a ray model's unit vector
  // (sin θ·x_d/θd, sin θ·y_d/θd, cos θ), θ from θd = √(x_d² + y_d²) by Newton's method (the slope
  // by Jet through DistortAngle) kept inside [0, MaxTheta], where θd(θ) is monotone: nullopt
  // when θd is beyond θd(MaxTheta), the edge of the valid domain.
  static std::optional<Eigen::Vector3d> UnprojectRay(const double* params, const Eigen::Vector2d& px) {
    if constexpr (!Model::kOnRay) {
      return Unproject(params, px);
    } else {
      const double fx = params[0], fy = params[1], cx = params[2], cy = params[3], s = params[4];
      const double yd = (px.y() - cy) / fy;
      const double xd = (px.x() - cx - s * yd) / fx;
      const double* distortion = params + kNumIntrinsicParams;
      const double theta_d = std::sqrt(xd * xd + yd * yd);
      if (theta_d == 0) return Eigen::Vector3d(0, 0, 1);
      const double max_theta = MaxTheta(distortion);
      if (!(theta_d < Model::DistortAngle(distortion, max_theta))) return std::nullopt;
      using Jet1 = ceres::Jet<double, 1>;
      std::array<Jet1, Model::kNumParams - kNumIntrinsicParams> dist;
      for (size_t i = 0; i < dist.size(); ++i) dist[i] = Jet1(distortion[i]);
      // θd(θ) − θd_target is increasing on [lo, hi]: Newton steps, replaced by bisection when one
      // leaves the bracket, converge from any start.
      double lo = 0, hi = max_theta, theta = std::min(theta_d, 0.5 * max_theta);
      for (int iteration = 0; iteration < 100; ++iteration) {
        const Jet1 f = Model::DistortAngle(dist.data(), Jet1(theta, 0));
        const double e = f.a - theta_d;
        if (e == 0) break;
        (e > 0 ? hi : lo) = theta;
        double next = theta - e / f.v[0];
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        const double step = std::abs(next - theta);
        theta = next;
        if (step <= 1e-15 * (1.0 + theta)) break;
        if (iteration == 99) return std::nullopt;
      }
      const double along = std::sin(theta) / theta_d;
      return Eigen::Vector3d(along * xd, along * yd, std::cos(theta));
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

// Kannala–Brandt's equidistant fisheye (Kannala & Brandt 2006; OpenCV's cv::fisheye, Kalibr's
// and ROS's "equidistant"): a ray model whose normalized image radius is a polynomial in the
// angle off the axis, θd = θ(1 + k1 θ² + k2 θ⁴ + k3 θ⁶ + k4 θ⁸), so a lens of 180° and more
// projects. Valid where θd grows with θ (MaxTheta), never past π: docs/math/fisheye.md. Its k1…k4
// are not the Brown–Conrady k's: no other model's layout extends this one.
struct KannalaBrandtModel : LensModel<KannalaBrandtModel> {
  static constexpr std::string_view kName = "kannala-brandt";
  static constexpr int kNumParams = kNumIntrinsicParams + 4;
  static constexpr std::array<std::string_view, kNumParams> kParamNames = {"fx", "fy", "cx", "cy", "s",
                                                                           "k1", "k2", "k3", "k4"};
  static constexpr bool kOnRay = true;

  template <typename T>
  static T DistortAngle(const T* d, const T& theta) {
    const T t2 = theta * theta;
    return theta * (T(1) + t2 * (d[0] + t2 * (d[1] + t2 * (d[2] + t2 * d[3]))));
  }
  // dθd/dθ, written out because the domain check needs it for every scalar type (double, Jet,
  // SimdDouble); the unit test checks it against DistortAngle's Jet derivative.
  template <typename T>
  static T AngleSlope(const T* d, const T& theta) {
    const T t2 = theta * theta;
    return T(1) + t2 * (T(3) * d[0] + t2 * (T(5) * d[1] + t2 * (T(7) * d[2] + t2 * (T(9) * d[3]))));
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
