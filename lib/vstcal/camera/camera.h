// A camera at runtime: image size, a lens model chosen by name, and its parameters.
//
// The model is a std::variant over the structs of lens_models.h; Project/Unproject dispatch with
// std::visit to the one templated projection. Parameters follow the shared layout
// [fx, fy, cx, cy, s, <distortion>] (docs/conventions.md#intrinsics).
#pragma once

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

// Alternatives in increasing number of parameters: code that picks "the smallest model that can
// hold n coefficients" relies on this order.
using AnyLensModel = std::variant<PinholeModel, RadialTangentialModel, RationalModel>;

// Calls f(Model{}) for every alternative of AnyLensModel, in declaration order.
template <typename F>
void ForEachLensModel(F&& f) {
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

struct Camera {
  ImageSize image_size;
  AnyLensModel model = PinholeModel{};
  std::vector<double> params;  // size LensModelNumParams(model)

  // A camera with intrinsic matrix K (upper triangular, K(2,2) = 1) and the model's distortion
  // coefficients (empty = all zero).
  static Camera FromK(const Eigen::Matrix3d& K, ImageSize image_size, AnyLensModel model = PinholeModel{},
                      std::span<const double> distortion = {});

  Eigen::Matrix3d K() const;
  std::span<const double> distortion() const;

  // Pixel of a camera-frame point; nullopt behind the camera (z ≤ 0).
  std::optional<Eigen::Vector2d> Project(const Eigen::Vector3d& p_cam) const;
  // Ray (x, y, 1) in the camera frame through a pixel; nullopt outside the model's domain.
  std::optional<Eigen::Vector3d> Unproject(const Eigen::Vector2d& px) const;
  // True when px lies on the sensor: u ∈ [−0.5, W − 0.5], v ∈ [−0.5, H − 0.5].
  bool InImage(const Eigen::Vector2d& px) const;
};

}  // namespace vstcal
