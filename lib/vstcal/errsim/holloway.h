// Registration-error measures of one chain sample (double only): image misregistration per eye,
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
#include <string>
#include <vector>

#include "vstcal/errsim/chain.h"

namespace vstcal::errsim {

struct PointErrors {
  std::array<double, kNumEyes> pixel_px{};     // |q_virt − q_real|
  std::array<double, kNumEyes> angular_deg{};  // at each eye
  double linear = 0, lateral = 0, depth = 0, angular_deg_cyclopean = 0;  // length unit, degrees
  // The depth test at the overlay's pixel drew the wrong layer (1) or the right one (0); −1 when
  // the test point has no surface_behind.
  std::array<int, kNumEyes> wrong_occlusion{-1, -1};
};

// Angle between two non-zero vectors, radians, accurate for tiny angles (atan2 of |a×b| and a·b;
// a series below 0.1 rad, where it is exact to rounding and 5× cheaper).
// Inline: a sample needs 15 of them, and the compiler interleaves their sqrt/div latencies.
inline double AngleBetweenVectors(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double s = a.cross(b).norm();
  const double c = a.dot(b);
  if (c > 0 && s < 0.1 * c) {
    // atan x = x (1 − x²/3 + x⁴/5 − …), truncated where the first omitted term is below rounding:
    // through x⁷ for x < 0.01 (x⁸/9 < 1.2e-17), through x¹⁵ for x < 0.1 (x¹⁶/17 < 6e-18).
    const double x = s / c, x2 = x * x, x4 = x2 * x2;
    constexpr double k3 = 1.0 / 3, k5 = 1.0 / 5, k7 = 1.0 / 7, k9 = 1.0 / 9, k11 = 1.0 / 11, k13 = 1.0 / 13,
                     k15 = 1.0 / 15;
    // Estrin's scheme: pairs of terms evaluated independently, to shorten the dependency chain.
    const double low = (1 - k3 * x2) + x4 * (k5 - k7 * x2);
    if (x < 0.01) return x * low;
    const double high = (k9 - k11 * x2) + x4 * (k13 - k15 * x2);
    return x * (low + (x4 * x4) * high);
  }
  return std::atan2(s, c);
}


// The errors of test point k of a valid sample. The occlusion decision compares the virtual depth
// with the real surface's depth as a stereo matcher measures it: z_m = f·b / (f·b/z_s + δd), with
// δd the sample's disparity error (rendering block of θ), f the camera's fx, b the camera baseline.
PointErrors MeasurePoint(const ChainEvaluator& chain, const ChainSample<double>& sample, const double* theta, size_t k);

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
  bool Measure(const ChainEvaluator& chain, const ChainSample<double>& sample, const double* theta, double* y) const;
  // Offset of test point k's first output and whether it has occlusion outputs.
  size_t offset(size_t k) const { return offsets_[k]; }
  bool has_occlusion(size_t k) const { return occlusion_[k]; }
  static constexpr size_t kPerPoint = 9;

 private:
  std::vector<std::string> names_;
  std::vector<size_t> offsets_;
  std::vector<bool> occlusion_;
};

}  // namespace vstcal::errsim
