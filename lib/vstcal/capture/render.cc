#include "vstcal/capture/render.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "vstcal/core/error.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

// Separable Gaussian blur of a W × H image of doubles, border pixels replicated.
void GaussianBlur(std::vector<double>* image, int w, int h, double sigma) {
  const int radius = static_cast<int>(std::ceil(4 * sigma));
  std::vector<double> kernel(2 * radius + 1);
  double sum = 0;
  for (int k = -radius; k <= radius; ++k) sum += kernel[k + radius] = std::exp(-0.5 * k * k / (sigma * sigma));
  for (double& k : kernel) k /= sum;
  std::vector<double> tmp(image->size());
  const std::vector<double>& in = *image;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      double acc = 0;
      for (int k = -radius; k <= radius; ++k) acc += kernel[k + radius] * in[static_cast<size_t>(v) * w + std::clamp(u + k, 0, w - 1)];
      tmp[static_cast<size_t>(v) * w + u] = acc;
    }
  }
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      double acc = 0;
      for (int k = -radius; k <= radius; ++k) acc += kernel[k + radius] * tmp[static_cast<size_t>(std::clamp(v + k, 0, h - 1)) * w + u];
      (*image)[static_cast<size_t>(v) * w + u] = acc;
    }
  }
}

}  // namespace

PixelCornerRays::PixelCornerRays(const Camera& camera) : width_(camera.image_size.width), height_(camera.image_size.height) {
  VSTCAL_CHECK(width_ > 0 && height_ > 0, "empty image");
  rays_.resize(static_cast<size_t>(width_ + 1) * (height_ + 1));
  valid_.resize(rays_.size());
  for (int j = 0; j <= height_; ++j) {
    for (int i = 0; i <= width_; ++i) {
      const auto ray = camera.UnprojectRay(Eigen::Vector2d(i - 0.5, j - 0.5));  // a fisheye sees past 90°
      valid_[Index(i, j)] = ray.has_value();
      rays_[Index(i, j)] = ray.value_or(Eigen::Vector3d::Zero());
    }
  }
}

std::vector<double> RenderCoverage(const PixelCornerRays& rays, const Pattern& pattern, const Rigid3d& camera_from_board,
                                   const RenderOptions& options) {
  const int w = rays.width(), h = rays.height();
  // Each pixel corner's ray meets the board plane Z_board = 0 where n·(λ r − t) = 0, n = R e_z the
  // board normal in the camera frame: λ = n·t / n·r, in front of the camera when λ > 0.
  const Eigen::Matrix3d& R = camera_from_board.R;
  const Eigen::Vector3d& t = camera_from_board.t;
  const Eigen::Vector3d n = R.col(2);
  const double nt = n.dot(t);
  std::vector<Eigen::Vector2d> on_board(static_cast<size_t>(w + 1) * (h + 1));
  std::vector<uint8_t> hit(on_board.size());
  for (int j = 0; j <= h; ++j) {
    for (int i = 0; i <= w; ++i) {
      const size_t k = static_cast<size_t>(j) * (w + 1) + i;
      if (!rays.valid(i, j)) continue;
      const Eigen::Vector3d& r = rays.ray(i, j);
      const double nr = n.dot(r);
      const double lambda = nt / nr;
      if (!(nr != 0 && lambda > 0 && std::isfinite(lambda))) continue;
      const Eigen::Vector3d b = R.transpose() * (lambda * r - t);
      on_board[k] = b.head<2>();
      hit[k] = 1;
    }
  }
  std::vector<double> image(static_cast<size_t>(w) * h, options.background);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const size_t k00 = static_cast<size_t>(v) * (w + 1) + u, k01 = k00 + w + 1;
      if (!hit[k00] || !hit[k00 + 1] || !hit[k01] || !hit[k01 + 1]) continue;  // the plane's horizon: background
      const std::array<Eigen::Vector2d, 4> quad = {on_board[k00], on_board[k00 + 1], on_board[k01 + 1], on_board[k01]};
      const double area = std::abs(SignedArea(quad));
      if (!(area > 0)) continue;
      const double sheet = std::min(1.0, pattern.SheetArea(quad) / area);
      if (sheet == 0) continue;
      const double black = std::min(sheet, pattern.BlackArea(quad) / area);
      image[static_cast<size_t>(v) * w + u] =
          options.background * (1 - sheet) + options.white * (sheet - black) + options.black * black;
    }
  }
  return image;
}

GrayImage RenderView(const PixelCornerRays& rays, const Pattern& pattern, const Rigid3d& camera_from_board,
                     const RenderOptions& options, uint32_t view) {
  const int w = rays.width(), h = rays.height();
  std::vector<double> image = RenderCoverage(rays, pattern, camera_from_board, options);
  if (options.lighting > 0) {
    const double phi = DegToRad(options.lighting_direction_deg);
    const double c = std::cos(phi), s = std::sin(phi), norm = std::abs(c) + std::abs(s);
    for (int v = 0; v < h; ++v) {
      for (int u = 0; u < w; ++u) {
        const double un = w > 1 ? 2.0 * u / (w - 1) - 1 : 0, vn = h > 1 ? 2.0 * v / (h - 1) - 1 : 0;
        const double ramp = 0.5 * ((un * c + vn * s) / norm + 1);  // 0 … 1 across the image
        image[static_cast<size_t>(v) * w + u] *= 1 - options.lighting * ramp;
      }
    }
  }
  if (options.blur_px > 0) GaussianBlur(&image, w, h, options.blur_px);
  GrayImage out(w, h);
  const CounterRng rng(options.seed, view);
  for (size_t k = 0; k < image.size(); ++k) {
    double value = image[k];
    if (options.noise > 0) value += options.noise * rng.Normal2(k / 2, 0)[k % 2];
    out.pixels[k] = static_cast<uint8_t>(std::lround(std::clamp(value, 0.0, 255.0)));
  }
  return out;
}

}  // namespace vstcal
