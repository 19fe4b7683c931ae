// A camera at runtime: image size, a lens model chosen by name, and its parameters.
//
// The model is a std::variant over the structs of lens_models.h; Project/Unproject dispatch with
// std::visit to the one templated projection. Parameters follow the shared layout
// [fx, fy, cx, cy, s, <distortion>] (docs/conventions.md#intrinsics).
#pragma once

#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "vstcal/camera/lens_models.h"
#include "vstcal/core/image_size.h"

namespace vstcal {

// The Brown–Conrady chain first, in increasing number of parameters, each layout a prefix of the
// next (code that picks "the smallest model that holds these terms" relies on this order), then
// models of other families (their layouts extend only "none": LensModelExtends).
using AnyLensModel = std::variant<PinholeModel, RadialTangentialModel, RationalModel, KannalaBrandtModel>;

// Calls f(Model{}) for every alternative of AnyLensModel, in declaration order.
template <typename F>
constexpr void ForEachLensModel(F&& f) {
  [&]<size_t... I>(std::index_sequence<I...>) {
    (f(std::variant_alternative_t<I, AnyLensModel>{}), ...);
  }(std::make_index_sequence<std::variant_size_v<AnyLensModel>>{});
}

// Model by its file name ("none", "radial-tangential", "rational"); nullopt for an unknown name.
std::optional<AnyLensModel> LensModelFromName(std::string_view name);
// The known names, comma-separated, for error messages.
std::string KnownLensModelNames();
std::string_view LensModelName(const AnyLensModel& model);
int LensModelNumParams(const AnyLensModel& model);
std::vector<std::string_view> LensModelParamNames(const AnyLensModel& model);
// True when `larger`'s parameter names start with all of `smaller`'s (so its parameters, zeros
// appended, are the same camera): "rational" extends "radial-tangential", "kannala-brandt"
// extends only "none" and itself.
bool LensModelExtends(const AnyLensModel& larger, const AnyLensModel& smaller);
// Index of a parameter in the model's layout by its name ("fx", "k1", …); nullopt when the model
// has no such parameter.
std::optional<int> LensModelParamIndex(const AnyLensModel& model, std::string_view name);

struct Camera {
  ImageSize image_size;
  AnyLensModel model = PinholeModel{};
  std::vector<double> params;  // size LensModelNumParams(model)

  // A camera with intrinsic matrix K (upper triangular, K(2,2) = 1) and the model's distortion
  // coefficients (empty = all zero).
  static Camera FromK(const Eigen::Matrix3d& K, ImageSize image_size, AnyLensModel model = PinholeModel{},
                      std::span<const double> distortion = {});

  Eigen::Matrix3d K() const;
  // A parameter by its name in the model's layout; a name the model lacks is a bug (InternalError).
  double Param(std::string_view name) const;
  std::span<const double> distortion() const;

  // Pixel of a camera-frame point; nullopt outside the model's domain: behind the camera (z ≤ 0)
  // for a plane model, past its valid angle off the axis for a ray model (lens_models.h).
  std::optional<Eigen::Vector2d> Project(const Eigen::Vector3d& p_cam) const;
  // Ray (x, y, 1) in the camera frame through a pixel; nullopt outside the model's domain, and for
  // a fisheye pixel whose ray is 90° or more off the axis (it has no such form: UnprojectRay).
  std::optional<Eigen::Vector3d> Unproject(const Eigen::Vector2d& px) const;
  // A direction of the ray through a pixel, for callers that take any direction: (x, y, 1) as
  // Unproject for a plane model, a unit vector for a ray model (beyond 90° too); nullopt outside
  // the model's domain.
  std::optional<Eigen::Vector3d> UnprojectRay(const Eigen::Vector2d& px) const;
  // True when px lies on the sensor: u ∈ [−0.5, W − 0.5], v ∈ [−0.5, H − 0.5].
  bool InImage(const Eigen::Vector2d& px) const;
  // The lens's valid domain, as the squared normalized radius r² = x² + y² of the largest disc
  // around the axis on which the distortion's Jacobian determinant is positive: there the lens maps
  // rays to pixels one to one and Unproject's Newton iteration finds the ray; beyond it the image
  // folds over (a ray far outside the field of view can land back inside the image). Checked
  // along 64 directions, found by bisection to 1e-9 relative; +∞ for a lens without distortion or
  // one that does not fold within r = 100 (89.4° off axis). A ray model's domain is an angle
  // (MaxTheta): tan² of it below 90°, +∞ when every ray in front of the camera is inside it.
  double ValidRadiusSquared() const;
};

// Project through any lens model of the variant, templated on the scalar (double, ceres::Jet,
// SimdDouble): the one projection, dispatched on the model. A switch of direct calls rather than
// std::visit, so that the chosen Project inlines into the caller (the err-sim chain's AVX2 clone).
// False outside the model's domain (lens_models.h).
template <typename T>
bool ProjectWith(const AnyLensModel& model, const T* params, const T* p_cam, T* px) {
  return [&]<size_t... I>(std::index_sequence<I...>) {
    bool ok = false;
    (void)((model.index() == I && (ok = std::variant_alternative_t<I, AnyLensModel>::Project(params, p_cam, px), true)) || ...);
    return ok;
  }(std::make_index_sequence<std::variant_size_v<AnyLensModel>>{});
}

// The most parameters any lens model has.
inline constexpr int kMaxLensParams = [] {
  int n = 0;
  ForEachLensModel([&](auto model) { n = std::max(n, decltype(model)::kNumParams); });
  return n;
}();

}  // namespace vstcal
