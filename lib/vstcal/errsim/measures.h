// The error measures of one chain sample (docs/math/vst-chain.md#measures), per test point:
//  - image misregistration per eye: |q̂ − q|, px (the overlay against the video in the frame);
//  - misregistration: the overlay P̂' against the video image of the same point P', both as the
//    eyes see them through the display (Holloway's terms seen from the cyclopean eye);
//  - misperception: where the eyes see the point, P', against where it is, P, relative to the
//    error-free chain's systematic misperception (ChainEvaluator::systematic);
//  - the occlusion decision of the rendering source.
// Holloway's linear/lateral/depth/angular terms are geometry/registration_error.h's, shared with
// the reports.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "vstcal/core/simd_double.h"
#include "vstcal/errsim/chain.h"

namespace vstcal {

// T is double, or SimdDouble for four samples at once; the same code either way.
template <typename T>
struct PointErrorsOf {
  std::array<T, kNumEyes> pixel_px{};        // |q̂ − q|
  RegistrationErrorOf<T> misregistration{};  // of P̂' − P', angular in radians
  RegistrationErrorOf<T> misperception{};    // of P' − (P + systematic offset)
  // The depth test at the overlay's pixel drew the wrong layer (1) or the right one (0); −1 when
  // the test point has no surface_behind.
  std::array<T, kNumEyes> wrong_occlusion{T(-1), T(-1)};
};
using PointErrors = PointErrorsOf<double>;

// The errors of test point k of a sample where it is valid. With `full` false only the pixel
// errors, the linear terms and the occlusion decisions are computed (what the budget needs).
// The occlusion decision compares the virtual depth with the real surface's depth as a stereo
// matcher measures it: z_m = f·b / (f·b/z_s + δd), δd the sample's disparity error at the point,
// f the camera's fx, b the camera baseline.
template <typename T>
PointErrorsOf<T> MeasurePoint(const ChainEvaluator& chain, const ChainSample<T>& sample, const T* theta, size_t k,
                              bool full = true) {
  namespace fo = fixed_order;
  const PointSample<T>& s = sample.points[k];
  const ChainModel& model = chain.model();
  PointErrorsOf<T> e;
  for (int i = 0; i < kNumEyes; ++i) e.pixel_px[i] = fo::Norm(s.pixel_error[i]);
  const Vec3<T> misregistration = s.overlay - s.seen;
  const Vec3<T> reference = s.truth + chain.systematic(k).offset.template cast<T>();
  const Vec3<T> misperception = s.seen - reference;
  if (full) {
    const Vec3<T> cyclops = T(0.5) * (sample.eye[0] + sample.eye[1]);
    e.misregistration = RegistrationError(cyclops, s.seen, misregistration);
    e.misperception = RegistrationError(cyclops, reference, misperception);
  } else {
    e.misregistration.linear = fo::Norm(misregistration);
    e.misperception.linear = fo::Norm(misperception);
  }

  const auto& surface = model.geometry.test_points[k].surface_behind;
  if (surface) {
    const T disparity_error = theta[model.layout.Offset(Term::kDisparity) + static_cast<int>(k)];
    for (int i = 0; i < kNumEyes; ++i) {
      const double fb = chain.focal_baseline(i);
      const T disparity = T(chain.surface_disparity(i, k)) + disparity_error;
      // No positive disparity: the matcher sees the surface at infinity, and the overlay is drawn.
      const T measured = Select(disparity > T(0), T(fb) / disparity, T(std::numeric_limits<double>::infinity()));
      // Drawn when in front of the measured surface: wrong when that disagrees with the truth.
      const auto drawn = s.virtual_depth[i] < measured;
      e.wrong_occlusion[i] = *surface > 0 ? Select(drawn, T(0), T(1)) : Select(drawn, T(1), T(0));
    }
  }
  return e;
}

// Which outputs a Monte Carlo run keeps: every measure (the report's "all" scenario, Sobol), or
// only those the budget's totals need.
enum class OutputSet { kFull, kTotals };

// The scalar outputs of one sample, per test point "<name>." followed by (kFull)
//   image.left.pixel_px, image.right.pixel_px,
//   misregistration.{linear, lateral, depth, depth_abs, angular_deg},
//   misperception.{linear, lateral, depth, depth_abs, angular_deg},
// or (kTotals) image.left.pixel_px, image.right.pixel_px, misregistration.linear,
// misperception.linear; then, for points with surface_behind, occlusion.left.wrong,
// occlusion.right.wrong (1 wrong, 0 right).
class ErrorOutputs {
 public:
  ErrorOutputs(const ChainModel& model, OutputSet set = OutputSet::kFull);
  const std::vector<std::string>& names() const { return names_; }
  size_t size() const { return names_.size(); }
  OutputSet set() const { return set_; }
  // Fills y (size()) from a sample, and defined[k] for every test point (its outputs are
  // unspecified where false).
  template <typename T>
  void Measure(const ChainEvaluator& chain, const ChainSample<T>& sample, const T* theta, T* y, bool* defined) const;

  // Where test point k's outputs start, the offsets of its measures within them, and whether it
  // has occlusion outputs.
  size_t offset(size_t k) const { return offsets_[k]; }
  bool has_occlusion(size_t k) const { return occlusion_[k]; }
  size_t num_points() const { return offsets_.size(); }
  size_t point_of(size_t output) const { return point_of_[output]; }
  // Whether output k gets percentiles (a histogram): the magnitudes the report ranks by, each
  // eye's pixel error and the two measures' linear terms (kFull only).
  bool wants_percentiles(size_t output) const { return percentiles_[output]; }
  static constexpr size_t kPixel = 0;  // + eye
  size_t misregistration() const { return 2; }
  size_t misperception() const { return set_ == OutputSet::kFull ? 7 : 3; }
  size_t occlusion() const { return set_ == OutputSet::kFull ? 12 : 4; }  // + eye
  // Per measure (kFull): linear, lateral, depth, depth_abs, angular_deg.
  static constexpr size_t kLinear = 0, kLateral = 1, kDepth = 2, kDepthAbs = 3, kAngular = 4;

 private:
  OutputSet set_;
  std::vector<std::string> names_;
  std::vector<size_t> offsets_, point_of_;
  std::vector<bool> occlusion_, percentiles_;
};

template <typename T>
void ErrorOutputs::Measure(const ChainEvaluator& chain, const ChainSample<T>& sample, const T* theta, T* y,
                           bool* defined) const {
  using std::abs;
  constexpr double kDeg = 180.0 / kPi;
  const bool full = set_ == OutputSet::kFull;
  auto put = [&](T* out, const RegistrationErrorOf<T>& r) {
    out[kLinear] = r.linear;
    if (!full) return;
    out[kLateral] = r.lateral;
    out[kDepth] = r.depth;
    out[kDepthAbs] = abs(r.depth);
    out[kAngular] = kDeg * r.angular;
  };
  for (size_t k = 0; k < offsets_.size(); ++k) {
    defined[k] = sample.points[k].valid();
    if (!defined[k]) continue;
    const PointErrorsOf<T> e = MeasurePoint(chain, sample, theta, k, full);
    T* out = y + offsets_[k];
    out[kPixel] = e.pixel_px[0];
    out[kPixel + 1] = e.pixel_px[1];
    put(out + misregistration(), e.misregistration);
    put(out + misperception(), e.misperception);
    if (occlusion_[k]) {
      out[occlusion()] = e.wrong_occlusion[0];
      out[occlusion() + 1] = e.wrong_occlusion[1];
    }
  }
}

}  // namespace vstcal
