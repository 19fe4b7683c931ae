// Registration-error measures of one chain sample: image misregistration per eye,
// and Holloway's perceived-space errors (Holloway 1997, "Registration error analysis for augmented
// reality", Presence 6(4); seed 001 Fig. 2), plus the occlusion decision of the rendering source.
//
// With the cyclopean eye c (midpoint of the eyes), the true point P, the perceived overlay P' and
// the line of sight ℓ = (P − c)/|P − c|, Δ = P' − P:
//   linear  = |Δ|                       lateral = |Δ − (Δ·ℓ) ℓ|
//   depth   = Δ·ℓ (signed, > 0 farther)  angular = ∠(P − c, P' − c)
// and per eye the angle at that eye between the perceived ray and the direction to P.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "vstcal/core/simd_double.h"
#include "vstcal/errsim/chain.h"

namespace vstcal::errsim {

// T is double, or SimdDouble for four samples at once (engine.h); the same code either way.
template <typename T>
struct PointErrorsOf {
  std::array<T, kNumEyes> pixel_px{};     // |q_virt − q_real|
  std::array<T, kNumEyes> angular_deg{};  // at each eye
  T linear{}, lateral{}, depth{}, angular_deg_cyclopean{};  // length unit, degrees
  // The depth test at the overlay's pixel drew the wrong layer (1) or the right one (0); −1 when
  // the test point has no surface_behind.
  std::array<T, kNumEyes> wrong_occlusion{T(-1), T(-1)};
};
using PointErrors = PointErrorsOf<double>;

// The angle θ in [0, π] with sin θ ∝ s ≥ 0 and cos θ ∝ c (atan2(s, c)), for s = |a × b|, c = a·b:
// accurate for tiny angles, unlike acos. Below 0.1 rad a series replaces atan2, exact to rounding
// and 5× cheaper.
template <typename T>
T AngleFromSinCos(const T& s, const T& c) {
  using std::atan2;
  if (c > T(0) && s < T(0.1) * c) {
    // atan x = x (1 − x²/3 + x⁴/5 − …) through x¹⁵: the first omitted term x¹⁷/17 is below
    // 6e-18·x for x < 0.1, under rounding. One polynomial for the whole range (no shorter one for
    // tiny x), so that four samples evaluated together never need different paths.
    const T x = s / c, x2 = x * x, x4 = x2 * x2;
    constexpr double k3 = 1.0 / 3, k5 = 1.0 / 5, k7 = 1.0 / 7, k9 = 1.0 / 9, k11 = 1.0 / 11, k13 = 1.0 / 13,
                     k15 = 1.0 / 15;
    // Estrin's scheme: pairs of terms evaluated independently, to shorten the dependency chain.
    const T low = (T(1) - k3 * x2) + x4 * (T(k5) - k7 * x2);
    const T high = (T(k9) - k11 * x2) + x4 * (T(k13) - k15 * x2);
    return x * (low + (x4 * x4) * high);
  }
  return atan2(s, c);
}

// Angle between two non-zero vectors, radians.
template <typename T>
T AngleBetweenVectors(const Vec3<T>& a, const Vec3<T>& b) {
  return AngleFromSinCos(fixed_order::Norm(fixed_order::Cross(a, b)), fixed_order::Dot(a, b));
}

// The errors of test point k of a valid sample. The occlusion decision compares the virtual depth
// with the real surface's depth as a stereo matcher measures it: z_m = f·b / (f·b/z_s + δd), with
// δd the sample's disparity error (rendering block of θ), f the camera's fx, b the camera baseline.
template <typename T>
PointErrorsOf<T> MeasurePoint(const ChainEvaluator& chain, const ChainSample<T>& sample, const T* theta, size_t k) {
  using std::sqrt;
  namespace fo = fixed_order;
  constexpr double kDeg = 180.0 / kPi;
  const PointSample<T>& s = sample.points[k];
  const ChainModel& model = chain.model();
  PointErrorsOf<T> e;
  for (int i = 0; i < kNumEyes; ++i) {
    e.pixel_px[i] = fo::Norm(s.pixel_error[i]);
    e.angular_deg[i] = kDeg * AngleBetweenVectors<T>(s.ray[i], s.truth - sample.eye[i]);
  }
  const Vec3<T> cyclops = T(0.5) * (sample.eye[0] + sample.eye[1]);
  const Vec3<T> sight = s.truth - cyclops;  // not normalized: depth = Δ·s/|s|, lateral = |Δ × s|/|s|
  const T distance2 = fo::SquaredNorm(sight);
  const T inverse_distance = T(1) / sqrt(distance2);
  const Vec3<T> delta = s.perceived - s.truth;
  const T along = fo::Dot(delta, sight);
  const T across = fo::Norm(fo::Cross(delta, sight));
  e.linear = fo::Norm(delta);
  e.depth = along * inverse_distance;
  e.lateral = across * inverse_distance;
  // ∠(s, s + Δ): |s × (s + Δ)| = |Δ × s| and s·(s + Δ) = |s|² + Δ·s, from what is at hand.
  e.angular_deg_cyclopean = kDeg * AngleFromSinCos(across, distance2 + along);

  const auto& surface = model.geometry.test_points[k].surface_behind;
  if (surface) {
    const T disparity_error = theta[model.layout.rendering + 1 + k];
    const double baseline = chain.camera_baseline();
    for (int i = 0; i < kNumEyes; ++i) {
      const double fb = model.geometry.cameras[i].params[0] * baseline;
      const double z_surface = chain.real_depth(i, k) + *surface;
      const T disparity = T(fb / z_surface) + disparity_error;
      // No positive disparity: the matcher sees the surface at infinity, and the overlay is drawn.
      const T measured = Select(disparity > T(0), T(fb) / disparity, T(std::numeric_limits<double>::infinity()));
      // Drawn when in front of the measured surface: wrong when that disagrees with the truth.
      const auto drawn = s.virtual_depth[i] < measured;
      e.wrong_occlusion[i] = *surface > 0 ? Select(drawn, T(0), T(1)) : Select(drawn, T(1), T(0));
    }
  }
  return e;
}

// The scalar outputs of one sample, for Monte Carlo statistics: per test point, in this order,
//   <name>.left.pixel_px, <name>.left.angular_deg, <name>.right.pixel_px, <name>.right.angular_deg,
//   <name>.linear, <name>.lateral, <name>.depth, <name>.depth_abs, <name>.angular_deg,
// then, for points with surface_behind, <name>.left.wrong_occlusion, <name>.right.wrong_occlusion.
class ErrorOutputs {
 public:
  explicit ErrorOutputs(const ChainModel& model);
  const std::vector<std::string>& names() const { return names_; }
  size_t size() const { return names_.size(); }
  // Fills y (size()) from a sample; false when the sample is undefined (some point invalid).
  template <typename T>
  bool Measure(const ChainEvaluator& chain, const ChainSample<T>& sample, const T* theta, T* y) const;
  // Offset of test point k's first output and whether it has occlusion outputs.
  size_t offset(size_t k) const { return offsets_[k]; }
  bool has_occlusion(size_t k) const { return occlusion_[k]; }
  static constexpr size_t kPerPoint = 9;

 private:
  std::vector<std::string> names_;
  std::vector<size_t> offsets_;
  std::vector<bool> occlusion_;
};

template <typename T>
bool ErrorOutputs::Measure(const ChainEvaluator& chain, const ChainSample<T>& sample, const T* theta, T* y) const {
  using std::abs;
  for (size_t k = 0; k < offsets_.size(); ++k) {
    if (!sample.points[k].valid) return false;
    const PointErrorsOf<T> e = MeasurePoint(chain, sample, theta, k);
    T* out = y + offsets_[k];
    out[0] = e.pixel_px[0];
    out[1] = e.angular_deg[0];
    out[2] = e.pixel_px[1];
    out[3] = e.angular_deg[1];
    out[4] = e.linear;
    out[5] = e.lateral;
    out[6] = e.depth;
    out[7] = abs(e.depth);
    out[8] = e.angular_deg_cyclopean;
    if (occlusion_[k]) {
      out[9] = e.wrong_occlusion[0];
      out[10] = e.wrong_occlusion[1];
    }
  }
  return true;
}

}  // namespace vstcal::errsim
