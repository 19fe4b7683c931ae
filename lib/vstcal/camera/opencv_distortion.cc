#include "vstcal/camera/opencv_distortion.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

bool IsOpenCvLength(int n) {
  return std::find(std::begin(kOpenCvDistortionLengths), std::end(kOpenCvDistortionLengths), n) !=
         std::end(kOpenCvDistortionLengths);
}

// Whether the model's distortion terms are OpenCV's first ones, in OpenCV's order.
template <typename Model>
bool InOpenCvOrder() {
  constexpr int n = Model::kNumParams - kNumIntrinsicParams;
  if (n > static_cast<int>(std::size(kOpenCvDistortionNames))) return false;
  return std::equal(Model::kParamNames.begin() + kNumIntrinsicParams, Model::kParamNames.end(),
                    std::begin(kOpenCvDistortionNames));
}

}  // namespace

std::optional<AnyLensModel> LensModelForOpenCvLength(int n) {
  if (!IsOpenCvLength(n)) return std::nullopt;
  std::optional<AnyLensModel> found;
  ForEachLensModel([&](auto model) {
    using Model = decltype(model);
    if (!found && InOpenCvOrder<Model>() && Model::kNumParams - kNumIntrinsicParams >= n) found = model;
  });
  return found;
}

Camera CameraFromOpenCv(const Eigen::Matrix3d& K, ImageSize image_size, std::span<const double> coefficients) {
  const auto model = LensModelForOpenCvLength(static_cast<int>(coefficients.size()));
  VSTCAL_CHECK(model.has_value(), "no lens model holds this many OpenCV coefficients");
  std::vector<double> distortion(coefficients.begin(), coefficients.end());
  distortion.resize(LensModelNumParams(*model) - kNumIntrinsicParams, 0.0);
  return Camera::FromK(K, image_size, *model, distortion);
}

bool HasOpenCvDistortion(const Camera& camera) {
  return std::visit([](const auto& m) { return InOpenCvOrder<std::decay_t<decltype(m)>>(); }, camera.model);
}

void RefuseNonOpenCvModel(const Camera& camera, std::string_view source, std::string_view peer, std::string_view fix) {
  if (HasOpenCvDistortion(camera)) return;
  throw InputError(std::string(source) + ": model: \"" + std::string(LensModelName(camera.model)) + "\" (cv::fisheye's model) has no equivalent in " +
                   std::string(peer) + "; " + std::string(fix));
}

std::optional<int> FirstCoefficientBeyond(const Camera& camera, int n) {
  VSTCAL_CHECK(HasOpenCvDistortion(camera), "a fisheye camera has no OpenCV distortion vector");
  const std::span<const double> d = camera.distortion();
  for (int i = n; i < static_cast<int>(d.size()); ++i) {
    if (d[i] != 0) return i;
  }
  return std::nullopt;
}

std::vector<double> OpenCvDistortion(const Camera& camera, int n) {
  VSTCAL_CHECK(HasOpenCvDistortion(camera), "a fisheye camera has no OpenCV distortion vector");
  VSTCAL_CHECK(!FirstCoefficientBeyond(camera, n), "a non-zero coefficient does not fit in the OpenCV vector");
  const std::span<const double> d = camera.distortion();
  std::vector<double> v(d.begin(), d.begin() + std::min<size_t>(n, d.size()));
  v.resize(n, 0.0);
  return v;
}

int ShortestOpenCvLength(const Camera& camera) {
  for (const int n : kOpenCvDistortionLengths) {
    const auto model = LensModelForOpenCvLength(n);
    if (model && model->index() == camera.model.index() && !FirstCoefficientBeyond(camera, n)) return n;
  }
  VSTCAL_CHECK(false, "the camera's own coefficient count is not an OpenCV length");
  return 0;
}

void RefuseSkew(const Camera& camera, std::string_view source, std::string_view peer) {
  const Eigen::Matrix3d K = camera.K();
  const double s = K(0, 1);
  if (s == 0) return;
  // u moves by s·y_d, and y_d = (v − cy)/fy exactly: the largest move is at the top or bottom row.
  const double rows = std::max(std::abs(-0.5 - K(1, 2)), std::abs(camera.image_size.height - 0.5 - K(1, 2)));
  const double shift = std::abs(s) * rows / K(1, 1);
  throw InputError(std::string(source) + ": K[0][1]: the camera has skew " + MessageNumber(s) + " px, and " +
                   std::string(peer) + " has no skew term: written without it, pixels would move by up to " +
                   MessageNumber(shift) +
                   " px; solve the camera without skew, or set K[0][1] to 0 (and delete \"intrinsics\") "
                   "in a copy if that error is acceptable");
}

}  // namespace vstcal
