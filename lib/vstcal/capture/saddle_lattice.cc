#include "vstcal/capture/saddle_lattice.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "vstcal/capture/search_image.h"

namespace vstcal {
namespace {

constexpr double kSmoothingPx = 1.0;
// √(−det H), grey levels a px²: a sharp X-junction of contrast C is about C / (π σ_t²), σ_t ≈ 1.2 px
// here (the smoothing, the pixel and a little blur): 3 keeps boards of contrast ≥ 40 blurred to
// σ ≈ 2 px, and leaves out sensor noise (σ 2 grey levels gives ≈ 0.3).
constexpr double kMinSaddle = 3;
constexpr double kMinLinkContrast = 20;   // grey levels between the squares on the two sides of a link
constexpr double kMaxAlongEdge = 0.35;    // |uᵀHu| over H's largest |eigenvalue|: u along a zero line
constexpr double kMaxOffMiddle = 0.25;    // the middle's grey off the mean of the two sides, over their difference
constexpr double kMinBalance = 0.2;       // H's eigenvalues' smaller |λ| over the larger: an X-junction whose edges meet at ≥ 48°
                                          // (1 at 90°); a straight edge with noise along it is ≪ 0.1
constexpr double kMinLinksPerCorner = 1.2;  // a lattice of n corners has ≈ 2n links (≈ 1.7n for 9 × 6); a chain or tree of chance links, n − 1
constexpr size_t kNeighbours = 8;         // nearest saddles tried as links (a tilted board's long-axis neighbour is 2nd after the short axis's)

struct Saddle {
  float x, y;
  float hxx, hyy, hxy;
};

float Sample(const cv::Mat& m, double x, double y) {
  x = std::clamp(x, 0.0, m.cols - 1.001);
  y = std::clamp(y, 0.0, m.rows - 1.001);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
  const float* r0 = m.ptr<float>(y0);
  const float* r1 = m.ptr<float>(y0 + 1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) + fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]);
}

double Form(const Saddle& s, double ux, double uy, double vx, double vy) { return ux * (s.hxx * vx + s.hxy * vy) + uy * (s.hxy * vx + s.hyy * vy); }

double LargestEigenvalue(const Saddle& s) {
  return std::abs(0.5 * (s.hxx + s.hyy)) + std::hypot(0.5 * (s.hxx - s.hyy), static_cast<double>(s.hxy));
}

// Whether saddles p and q are neighbouring corners of one board (saddle_lattice.h).
bool Linked(const cv::Mat& smooth, const Saddle& p, const Saddle& q) {
  const double dx = q.x - p.x, dy = q.y - p.y, d = std::hypot(dx, dy);
  if (d < 2) return false;
  const double ux = dx / d, uy = dy / d, nx = -uy, ny = ux;
  if (std::abs(Form(p, ux, uy, ux, uy)) > kMaxAlongEdge * LargestEigenvalue(p)) return false;
  if (std::abs(Form(q, ux, uy, ux, uy)) > kMaxAlongEdge * LargestEigenvalue(q)) return false;
  if (Form(p, ux, uy, nx, ny) * Form(q, ux, uy, nx, ny) >= 0) return false;
  const double mx = 0.5 * (p.x + q.x), my = 0.5 * (p.y + q.y);
  const double a = Sample(smooth, mx + 0.25 * d * nx, my + 0.25 * d * ny), b = Sample(smooth, mx - 0.25 * d * nx, my - 0.25 * d * ny);
  const double contrast = std::abs(a - b), mean = 0.5 * (a + b);
  if (contrast < kMinLinkContrast) return false;
  return std::abs(Sample(smooth, mx, my) - mean) <= kMaxOffMiddle * contrast;
}

// Whether a pixel before (x, y) in raster order within the 5 × 5 window has the same strength: of
// a plateau of equal maxima (a corner between pixels of a drawn board) only the first is kept.
bool TiedEarlier(const cv::Mat& strength, int x, int y) {
  const float v = strength.at<float>(y, x);
  for (int yy = y - 2; yy <= y; ++yy) {
    for (int xx = x - 2; xx <= x + 2; ++xx) {
      if (yy == y && xx >= x) return false;
      if (strength.at<float>(yy, xx) == v) return true;
    }
  }
  return false;
}

int Root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

std::optional<SaddleLattice> FindSaddleLattice(const GrayImage& image, double max_link_px) {
  const cv::Mat gray(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
  const SearchImage search = ReduceForSearch(gray);
  const double reach = max_link_px / search.factor;
  if (reach < 2 || search.image.cols < 8 || search.image.rows < 8) return std::nullopt;
  cv::Mat smooth, hxx, hyy, hxy;
  search.image.convertTo(smooth, CV_32F);
  cv::GaussianBlur(smooth, smooth, cv::Size(0, 0), kSmoothingPx);
  // 3×3 Sobel second derivatives: ¼ makes each the derivative per px².
  cv::Sobel(smooth, hxx, CV_32F, 2, 0, 3, 0.25);
  cv::Sobel(smooth, hyy, CV_32F, 0, 2, 3, 0.25);
  cv::Sobel(smooth, hxy, CV_32F, 1, 1, 3, 0.25);
  cv::Mat gx, gy;  // ⅛: grey levels a px
  cv::Sobel(smooth, gx, CV_32F, 1, 0, 3, 0.125);
  cv::Sobel(smooth, gy, CV_32F, 0, 1, 3, 0.125);
  const cv::Mat strength = hxy.mul(hxy) - hxx.mul(hyy);  // −det H: positive at saddles
  cv::Mat peak;
  // Local maxima over 5 × 5: the corners of squares of 3 px or more stay apart.
  cv::dilate(strength, peak, cv::Mat::ones(5, 5, CV_8U));
  std::vector<Saddle> saddles;
  const float floor = static_cast<float>(kMinSaddle * kMinSaddle);
  for (int y = 2; y + 2 < strength.rows; ++y) {
    const float* s = strength.ptr<float>(y);
    const float* m = peak.ptr<float>(y);
    for (int x = 2; x + 2 < strength.cols; ++x) {
      if (s[x] < floor || s[x] != m[x] || TiedEarlier(strength, x, y)) continue;
      Saddle saddle{static_cast<float>(x), static_cast<float>(y), hxx.at<float>(y, x), hyy.at<float>(y, x), hxy.at<float>(y, x)};
      // Where the gradient vanishes, −H⁻¹g from the pixel: a corner between pixels is half a pixel
      // off its best pixel, a tenth of a small square, and the links' directions need better.
      const double det = static_cast<double>(saddle.hxx) * saddle.hyy - static_cast<double>(saddle.hxy) * saddle.hxy;
      const double g0 = gx.at<float>(y, x), g1 = gy.at<float>(y, x);
      const double dx = -(saddle.hyy * g0 - saddle.hxy * g1) / det, dy = -(saddle.hxx * g1 - saddle.hxy * g0) / det;
      if (std::abs(dx) <= 1 && std::abs(dy) <= 1) {
        saddle.x += static_cast<float>(dx);
        saddle.y += static_cast<float>(dy);
      }
      // −det H = |λ₁ λ₂|: the smaller |λ| is −det H over the larger.
      const double large = LargestEigenvalue(saddle);
      if (s[x] >= kMinBalance * large * large) saddles.push_back(saddle);
    }
  }
  if (saddles.size() < static_cast<size_t>(kMinLatticeCorners)) return std::nullopt;
  // Buckets of `reach` a side: a saddle's links lie in its own and the eight around it.
  const int cell = static_cast<int>(std::ceil(reach)), bx = search.image.cols / cell + 1, by = search.image.rows / cell + 1;
  std::vector<std::vector<int>> buckets(static_cast<size_t>(bx * by));
  for (size_t i = 0; i < saddles.size(); ++i) {
    buckets[static_cast<size_t>(static_cast<int>(saddles[i].y) / cell * bx + static_cast<int>(saddles[i].x) / cell)].push_back(static_cast<int>(i));
  }
  std::vector<int> parent(saddles.size());
  std::iota(parent.begin(), parent.end(), 0);
  struct Link {
    int a, b;
    float length;
  };
  std::vector<Link> links;
  std::vector<std::pair<float, int>> near;
  for (size_t i = 0; i < saddles.size(); ++i) {
    const Saddle& p = saddles[i];
    const int cx = static_cast<int>(p.x) / cell, cy = static_cast<int>(p.y) / cell;
    near.clear();
    for (int yy = std::max(0, cy - 1); yy <= std::min(by - 1, cy + 1); ++yy) {
      for (int xx = std::max(0, cx - 1); xx <= std::min(bx - 1, cx + 1); ++xx) {
        for (const int j : buckets[static_cast<size_t>(yy * bx + xx)]) {
          const float d = std::hypot(saddles[j].x - p.x, saddles[j].y - p.y);
          if (j != static_cast<int>(i) && d <= reach) near.emplace_back(d, j);
        }
      }
    }
    const size_t k = std::min(kNeighbours, near.size());
    std::partial_sort(near.begin(), near.begin() + static_cast<long>(k), near.end());
    for (size_t n = 0; n < k; ++n) {
      const int j = near[n].second;
      // A pair is tried from both ends when each is among the other's nearest; kept once below.
      if (!Linked(smooth, p, saddles[j])) continue;
      links.push_back({std::min(static_cast<int>(i), j), std::max(static_cast<int>(i), j), near[n].first});
      parent[Root(parent, j)] = Root(parent, static_cast<int>(i));
    }
  }
  std::sort(links.begin(), links.end(), [](const Link& x, const Link& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  links.erase(std::unique(links.begin(), links.end(), [](const Link& x, const Link& y) { return x.a == y.a && x.b == y.b; }), links.end());
  std::vector<int> corners(saddles.size(), 0), linked(saddles.size(), 0);
  for (size_t i = 0; i < saddles.size(); ++i) ++corners[static_cast<size_t>(Root(parent, static_cast<int>(i)))];
  for (const Link& l : links) ++linked[static_cast<size_t>(Root(parent, l.a))];
  // The largest component knit as a lattice (chance links form chains and trees).
  int best = -1;
  for (size_t r = 0; r < saddles.size(); ++r) {
    if (corners[r] >= kMinLatticeCorners && linked[r] >= kMinLinksPerCorner * corners[r] && (best < 0 || corners[r] > corners[static_cast<size_t>(best)])) {
      best = static_cast<int>(r);
    }
  }
  if (best < 0) return std::nullopt;
  std::vector<float> lengths;
  for (const Link& l : links) {
    if (Root(parent, l.a) == best) lengths.push_back(l.length);
  }
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<long>(lengths.size() / 2), lengths.end());
  return SaddleLattice{corners[static_cast<size_t>(best)], search.factor * static_cast<double>(lengths[lengths.size() / 2]), search.factor};
}

}  // namespace vstcal
