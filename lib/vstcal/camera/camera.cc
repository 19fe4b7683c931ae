#include "vstcal/camera/camera.h"

#include "vstcal/core/error.h"

namespace vstcal {

std::optional<AnyLensModel> LensModelFromName(std::string_view name) {
  std::optional<AnyLensModel> found;
  ForEachLensModel([&](auto model) {
    if (decltype(model)::kName == name) found = model;
  });
  return found;
}

std::string KnownLensModelNames() {
  std::string names;
  ForEachLensModel([&](auto model) {
    if (!names.empty()) names += ", ";
    names += '"' + std::string(decltype(model)::kName) + '"';
  });
  return names;
}

std::string_view LensModelName(const AnyLensModel& model) {
  return std::visit([](const auto& m) { return std::decay_t<decltype(m)>::kName; }, model);
}

int LensModelNumParams(const AnyLensModel& model) {
  return std::visit([](const auto& m) { return std::decay_t<decltype(m)>::kNumParams; }, model);
}

std::vector<std::string_view> LensModelParamNames(const AnyLensModel& model) {
  return std::visit(
      [](const auto& m) {
        const auto& names = std::decay_t<decltype(m)>::kParamNames;
        return std::vector<std::string_view>(names.begin(), names.end());
      },
      model);
}

Camera Camera::FromK(const Eigen::Matrix3d& K, ImageSize image_size, AnyLensModel model,
                     std::span<const double> distortion) {
  Camera camera;
  camera.image_size = image_size;
  camera.model = model;
  const int n = LensModelNumParams(model);
  VSTCAL_CHECK(distortion.empty() || static_cast<int>(distortion.size()) == n - kNumIntrinsicParams,
               "distortion coefficient count does not match the lens model");
  camera.params.assign(n, 0.0);
  camera.params[0] = K(0, 0);
  camera.params[1] = K(1, 1);
  camera.params[2] = K(0, 2);
  camera.params[3] = K(1, 2);
  camera.params[4] = K(0, 1);
  for (size_t i = 0; i < distortion.size(); ++i) camera.params[kNumIntrinsicParams + i] = distortion[i];
  return camera;
}

Eigen::Matrix3d Camera::K() const {
  Eigen::Matrix3d K;
  K << params[0], params[4], params[2], 0, params[1], params[3], 0, 0, 1;
  return K;
}

std::span<const double> Camera::distortion() const {
  return std::span<const double>(params).subspan(kNumIntrinsicParams);
}

std::optional<Eigen::Vector2d> Camera::Project(const Eigen::Vector3d& p_cam) const {
  VSTCAL_CHECK(static_cast<int>(params.size()) == LensModelNumParams(model), "parameter count mismatch");
  Eigen::Vector2d px;
  const bool ok = std::visit([&](const auto& m) { return m.Project(params.data(), p_cam.data(), px.data()); }, model);
  if (!ok) return std::nullopt;
  return px;
}

std::optional<Eigen::Vector3d> Camera::Unproject(const Eigen::Vector2d& px) const {
  VSTCAL_CHECK(static_cast<int>(params.size()) == LensModelNumParams(model), "parameter count mismatch");
  return std::visit([&](const auto& m) { return m.Unproject(params.data(), px); }, model);
}

bool Camera::InImage(const Eigen::Vector2d& px) const {
  return px.x() >= -0.5 && px.y() >= -0.5 && px.x() <= image_size.width - 0.5 && px.y() <= image_size.height - 0.5;
}

}  // namespace vstcal
