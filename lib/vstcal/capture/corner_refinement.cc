#include "vstcal/capture/corner_refinement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "vstcal/image/image_sampling.h"

namespace vstcal {
namespace {

constexpr int kMaxIterations = 12;
constexpr double kConvergedPx = 1e-3;
// The patch is smoothed first by the binomial kernel [1 2 1]/4 along each axis (variance ½ px²,
// the discrete Gaussian of σ = 0.71 px): the point symmetry is untouched (the kernel is itself
// symmetric) and bilinear interpolation, exact to first order only, meets a smooth surface
// instead of the kinks of a sharp edge (docs/math/corners.md#presmoothing).
constexpr int kKernelRadius = 1;

// A window of the image smoothed by the Gaussian above, as doubles, with bilinear reads.
class SmoothedPatch {
 public:
  // The square of pixels within `half` of `centre` (clipped to the image).
  SmoothedPatch(const GrayImage& image, const Eigen::Vector2d& centre, int half) {
    x0_ = std::max(0, static_cast<int>(std::floor(centre.x())) - half);
    y0_ = std::max(0, static_cast<int>(std::floor(centre.y())) - half);
    const int x1 = std::min(image.width - 1, static_cast<int>(std::floor(centre.x())) + half + 1);
    const int y1 = std::min(image.height - 1, static_cast<int>(std::floor(centre.y())) + half + 1);
    w_ = x1 - x0_ + 1;
    h_ = y1 - y0_ + 1;
    if (w_ < 2 || h_ < 2) {
      w_ = h_ = 0;
      return;
    }
    // [1 2 1] along rows, then along columns, in integers (exact), divided by 16 at the end.
    // Rows first over the patch's rows plus the kernel's reach (the image's border replicated).
    const int ty0 = y0_ - kKernelRadius, th = h_ + 2 * kKernelRadius;
    const bool inside = x0_ - kKernelRadius >= 0 && x1 + kKernelRadius < image.width;
    std::vector<int> rows(static_cast<size_t>(w_) * th);
    for (int j = 0; j < th; ++j) {
      const int v = std::clamp(ty0 + j, 0, image.height - 1);
      const uint8_t* line = &image.pixels[static_cast<size_t>(v) * image.width];
      int* out = &rows[static_cast<size_t>(j) * w_];
      for (int i = 0; i < w_; ++i) {
        const int u = x0_ + i;
        out[i] = inside ? line[u - 1] + 2 * line[u] + line[u + 1]
                        : line[std::max(u - 1, 0)] + 2 * line[u] + line[std::min(u + 1, image.width - 1)];
      }
    }
    values_.resize(static_cast<size_t>(w_) * h_);
    for (int j = 0; j < h_; ++j) {
      const int* up = &rows[static_cast<size_t>(j) * w_];
      const int* mid = up + w_;
      const int* down = mid + w_;
      for (int i = 0; i < w_; ++i) values_[static_cast<size_t>(j) * w_ + i] = (up[i] + 2 * mid[i] + down[i]) * (1.0 / 16);
    }
  }

  int x0() const { return x0_; }
  int y0() const { return y0_; }
  int width() const { return w_; }
  const double* data() const { return values_.data(); }

  // True when the square of half-size r around c can be read (bilinear reads the next pixel too).
  bool Holds(const Eigen::Vector2d& c, double r) const {
    return w_ > 0 && c.x() - r >= x0_ && c.y() - r >= y0_ && c.x() + r < x0_ + w_ - 1 && c.y() + r < y0_ + h_ - 1;
  }

  struct Sample {
    double value, dx, dy;
  };
  // Bilinear value and gradient at image point (x, y), which Holds.
  Sample At(double x, double y) const {
    const double px = x - x0_, py = y - y0_;
    const int u = std::min(static_cast<int>(px), w_ - 2), v = std::min(static_cast<int>(py), h_ - 2);
    const double fx = px - u, fy = py - v;
    const double* row0 = &values_[static_cast<size_t>(v) * w_ + u];
    const double* row1 = row0 + w_;
    const double a = row0[0], b = row0[1], c = row1[0], d = row1[1];
    return {(1 - fy) * ((1 - fx) * a + fx * b) + fy * ((1 - fx) * c + fx * d), (1 - fy) * (b - a) + fy * (d - c),
            (1 - fx) * (c - a) + fx * (d - b)};
  }

 private:
  int x0_ = 0, y0_ = 0, w_ = 0, h_ = 0;
  std::vector<double> values_;
};

// Half the disc of integer offsets of radius r ((y > 0) or (y = 0 and x > 0); the other half are
// their mirrors) with Gaussian weights of σ = r / 2. Built once per radius.
struct Offset {
  int x, y;
  double w;
};
constexpr int kMaxRadius = 8;
const std::vector<Offset>& HalfDisc(int r) {
  static const std::array<std::vector<Offset>, kMaxRadius + 1> discs = [] {
    std::array<std::vector<Offset>, kMaxRadius + 1> all;
    for (int radius = 2; radius <= kMaxRadius; ++radius) {
      const double inv_two_sigma2 = 2.0 / (radius * radius);
      for (int y = 0; y <= radius; ++y) {
        for (int x = -radius; x <= radius; ++x) {
          if ((y == 0 && x <= 0) || x * x + y * y > radius * radius) continue;
          all[radius].push_back({x, y, std::exp(-(x * x + y * y) * inv_two_sigma2)});
        }
      }
    }
    return all;
  }();
  return discs[std::min(r, kMaxRadius)];
}

// How far the estimate may move before the smoothed patch is cut again around it, px.
constexpr int kSlack = 1;

}  // namespace

std::optional<SymmetryRefinement> RefineCornerBySymmetry(const GrayImage& image, const Eigen::Vector2d& start, double radius) {
  const int r = std::min(static_cast<int>(std::floor(radius)), kMaxRadius);
  if (r < 2 || image.width < 2 || image.height < 2) return std::nullopt;
  const std::vector<Offset>& offsets = HalfDisc(r);
  std::optional<SmoothedPatch> patch;
  Eigen::Vector2d centre = start, c = start;
  for (int iteration = 1; iteration <= kMaxIterations; ++iteration) {
    // c ± p stays within r + kSlack of the patch's centre while c stays within kSlack of it.
    if (!patch || (c - centre).cwiseAbs().maxCoeff() > kSlack) {
      centre = c;
      patch.emplace(image, centre, r + kSlack + 1);
    }
    if (!patch->Holds(c, r)) return std::nullopt;
    Eigen::Matrix2d JtJ = Eigen::Matrix2d::Zero();
    Eigen::Vector2d Jtr = Eigen::Vector2d::Zero();
    // c + p and c − p have the same fractional part as c (p is integer): one set of bilinear
    // weights for every sample of the iteration.
    const double px = c.x() - patch->x0(), py = c.y() - patch->y0();
    const int bx = static_cast<int>(std::floor(px)), by = static_cast<int>(std::floor(py));
    const double fx = px - bx, fy = py - by;
    const int w = patch->width();
    const double* base = patch->data() + static_cast<ptrdiff_t>(by) * w + bx;
    auto sample = [&](int ox, int oy, double* value, double* dx, double* dy) {
      const double* p0 = base + static_cast<ptrdiff_t>(oy) * w + ox;
      const double a = p0[0], b = p0[1], cc = p0[w], d = p0[w + 1];
      *value = (1 - fy) * ((1 - fx) * a + fx * b) + fy * ((1 - fx) * cc + fx * d);
      *dx = (1 - fy) * (b - a) + fy * (d - cc);
      *dy = (1 - fx) * (cc - a) + fx * (d - b);
    };
    for (const Offset& o : offsets) {
      double vp, dxp, dyp, vm, dxm, dym;
      sample(o.x, o.y, &vp, &dxp, &dyp);
      sample(-o.x, -o.y, &vm, &dxm, &dym);
      const double residual = vp - vm;
      const double jx = dxp - dxm, jy = dyp - dym;
      JtJ(0, 0) += o.w * jx * jx;
      JtJ(0, 1) += o.w * jx * jy;
      JtJ(1, 1) += o.w * jy * jy;
      Jtr(0) += o.w * residual * jx;
      Jtr(1) += o.w * residual * jy;
    }
    JtJ(1, 0) = JtJ(0, 1);
    const double det = JtJ(0, 0) * JtJ(1, 1) - JtJ(0, 1) * JtJ(0, 1);
    if (!(det > 1e-12 * JtJ.squaredNorm())) return std::nullopt;
    const Eigen::Vector2d step(-(JtJ(1, 1) * Jtr(0) - JtJ(0, 1) * Jtr(1)) / det, -(JtJ(0, 0) * Jtr(1) - JtJ(0, 1) * Jtr(0)) / det);
    c += step;
    if (!(step.norm() < r) || !c.allFinite() || (c - start).norm() > r) return std::nullopt;
    if (step.norm() < kConvergedPx) return SymmetryRefinement{c, iteration};
  }
  return SymmetryRefinement{c, kMaxIterations};
}

std::optional<double> Asymmetry(const GrayImage& image, const Eigen::Vector2d& c, double radius) {
  const int r = std::min(static_cast<int>(std::floor(radius)), kMaxRadius);
  if (r < 2 || image.width < 2 || image.height < 2) return std::nullopt;
  const SmoothedPatch patch(image, c, r + 1);
  if (!patch.Holds(c, r)) return std::nullopt;
  double sum = 0, weights = 0, lo = 255, hi = 0;
  for (const Offset& o : HalfDisc(r)) {
    const double plus = patch.At(c.x() + o.x, c.y() + o.y).value;
    const double minus = patch.At(c.x() - o.x, c.y() - o.y).value;
    sum += o.w * (plus - minus) * (plus - minus);
    weights += o.w;
    lo = std::min({lo, plus, minus});
    hi = std::max({hi, plus, minus});
  }
  if (!(hi - lo > 0)) return std::nullopt;
  return std::sqrt(sum / weights) / (hi - lo);
}

std::optional<double> EdgeBlur(const GrayImage& image, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double reach) {
  const Eigen::Vector2d along = b - a;
  if (!(along.norm() > 0)) return std::nullopt;
  const Eigen::Vector2d mid = 0.5 * (a + b), normal = Eigen::Vector2d(-along.y(), along.x()).normalized();
  const int n = static_cast<int>(std::floor(4 * reach));
  if (n < 4) return std::nullopt;
  std::vector<double> profile(2 * n + 1);
  for (int k = -n; k <= n; ++k) {
    const Eigen::Vector2d p = mid + 0.25 * k * normal;
    if (p.x() < 0 || p.y() < 0 || p.x() > image.width - 1 || p.y() > image.height - 1) return std::nullopt;
    profile[k + n] = SampleBilinear(image, p);
  }
  const auto [lo_it, hi_it] = std::minmax_element(profile.begin(), profile.end());
  const double lo = *lo_it, hi = *hi_it;
  if (hi - lo < 16) return std::nullopt;
  // Orient the profile to rise, then find where it first crosses 10 % and last crosses 90 %.
  if (profile.front() > profile.back()) std::reverse(profile.begin(), profile.end());
  auto crossing = [&](double level, bool first) -> std::optional<double> {
    for (int i = 0; i + 1 < static_cast<int>(profile.size()); ++i) {
      const int k = first ? i : static_cast<int>(profile.size()) - 2 - i;
      const double p0 = profile[k], p1 = profile[k + 1];
      if ((p0 - level) * (p1 - level) <= 0 && p0 != p1) return 0.25 * (k + (level - p0) / (p1 - p0));
    }
    return std::nullopt;
  };
  const auto x10 = crossing(lo + 0.1 * (hi - lo), true), x90 = crossing(lo + 0.9 * (hi - lo), false);
  if (!x10 || !x90 || *x90 <= *x10) return std::nullopt;
  // The profile's spread is the optics' σ² plus the pixel's box (1/12 px²) plus the bilinear
  // reading of the samples (a triangle kernel, 1/6 px²): report the optics' part.
  const double spread = (*x90 - *x10) / 2.5631031310892007;  // 2·Φ⁻¹(0.9)
  return std::sqrt(std::max(0.0, spread * spread - 0.25));
}

}  // namespace vstcal
