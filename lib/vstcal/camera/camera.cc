#include "vstcal/camera/camera.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"

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

bool LensModelExtends(const AnyLensModel& larger, const AnyLensModel& smaller) {
  const auto big = LensModelParamNames(larger), small = LensModelParamNames(smaller);
  return small.size() <= big.size() && std::equal(small.begin(), small.end(), big.begin());
}

std::optional<int> LensModelParamIndex(const AnyLensModel& model, std::string_view name) {
  const auto names = LensModelParamNames(model);
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) return std::nullopt;
  return static_cast<int>(it - names.begin());
}

double Camera::Param(std::string_view name) const {
  const std::optional<int> index = LensModelParamIndex(model, name);
  VSTCAL_CHECK(index && *index < static_cast<int>(params.size()), "no such camera parameter");
  return params[*index];
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

std::optional<Eigen::Vector3d> Camera::UnprojectRay(const Eigen::Vector2d& px) const {
  VSTCAL_CHECK(static_cast<int>(params.size()) == LensModelNumParams(model), "parameter count mismatch");
  return std::visit([&](const auto& m) { return m.UnprojectRay(params.data(), px); }, model);
}

bool Camera::InImage(const Eigen::Vector2d& px) const {
  return px.x() >= -0.5 && px.y() >= -0.5 && px.x() <= image_size.width - 0.5 && px.y() <= image_size.height - 0.5;
}

namespace {

// det ∂(x_d, y_d)/∂(x, y) of the distortion at (x, y), by ceres::Jet through Model::Distort.
template <typename Model>
double DistortionJacobianDeterminant(const double* distortion, double x, double y) {
  using Jet = ceres::Jet<double, 2>;
  constexpr int kDistortion = Model::kNumParams - kNumIntrinsicParams;
  std::array<Jet, kDistortion> d;
  for (int i = 0; i < kDistortion; ++i) d[i] = Jet(distortion[i]);
  Jet xd, yd;
  Model::Distort(d.data(), Jet(x, 0), Jet(y, 1), &xd, &yd);
  return xd.v[0] * yd.v[1] - xd.v[1] * yd.v[0];
}

double SearchValidRadiusSquared(const AnyLensModel& model, const std::vector<double>& params) {
  return std::visit(
      [&](const auto& m) -> double {
        using Model = std::decay_t<decltype(m)>;
        if constexpr (Model::kOnRay) {
          const double max_theta = Model::MaxTheta(params.data() + kNumIntrinsicParams);
          if (max_theta >= kPi / 2) return std::numeric_limits<double>::infinity();
          return std::tan(max_theta) * std::tan(max_theta);
        } else if constexpr (Model::kNumParams == kNumIntrinsicParams) {
          return std::numeric_limits<double>::infinity();
        } else {
          const double* distortion = params.data() + kNumIntrinsicParams;
          constexpr int kDirections = 64;
          auto folds = [&](double r) {
            for (int k = 0; k < kDirections; ++k) {
              const double a = 2 * kPi * k / kDirections;
              if (!(DistortionJacobianDeterminant<Model>(distortion, r * std::cos(a), r * std::sin(a)) > 0)) return true;
            }
            return false;
          };
          constexpr double kMaxRadius = 100;
          // Outward in steps of 1 % until the determinant is no longer positive somewhere, then bisect.
          double good = 0, bad = 0;
          for (double r = 1e-3; r <= kMaxRadius; r *= 1.01) {
            if (folds(r)) {
              bad = r;
              break;
            }
            good = r;
          }
          if (bad == 0) return std::numeric_limits<double>::infinity();
          while (bad - good > 1e-9 * bad) {
            const double mid = 0.5 * (good + bad);
            (folds(mid) ? bad : good) = mid;
          }
          return good * good;
        }
      },
      model);
}

}  // namespace

double Camera::ValidRadiusSquared() const {
  // The search below evaluates some 74,000 Jacobians when the lens never folds, and reading a
  // chain asks it of the same lens several times (each eye, the test points' check, the renderer):
  // the last answer is kept, per thread (a pure function of the model and its parameters).
  struct Answer {
    size_t model = 0;
    std::vector<double> params;
    double r2 = 0;
  };
  static thread_local std::optional<Answer> last;
  if (last && last->model == model.index() && last->params == params) return last->r2;
  last = Answer{model.index(), params, SearchValidRadiusSquared(model, params)};
  return last->r2;
}

}  // namespace vstcal
