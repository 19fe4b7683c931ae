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

#include "vstcal/core/error.h"
#include "vstcal/core/simd_double.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/outputs.h"

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

// The scalar outputs of one sample: per test point, kMeasures' rows (outputs.h) that `set` keeps,
// named "<point>.<group>[.<eye>].<name>" (misregistration.linear, image.left.pixel_px); the rows
// that need a surface only at test points with surface_behind.
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

  // Where test point k's outputs start, and whether it has the outputs that need a surface.
  size_t offset(size_t k) const { return offsets_[k]; }
  bool has_surface(size_t k) const { return surface_[k]; }
  size_t num_points() const { return offsets_.size(); }
  size_t point_of(size_t output) const { return point_of_[output]; }
  // The output of measure m (of `eye`) at test point k; the set must keep m.
  size_t at(size_t k, ErrorMeasure m, int eye = 0) const {
    VSTCAL_CHECK(slot_[static_cast<int>(m)][eye] >= 0, "the output set keeps the measure");
    return offsets_[k] + static_cast<size_t>(slot_[static_cast<int>(m)][eye]);
  }
  // Whether output k is a headline magnitude (kMeasures' headline, under kFull only): it gets
  // percentiles (a histogram) in Monte Carlo and a row in sobol's summary.
  bool is_headline(size_t output) const { return headline_[output]; }

 private:
  OutputSet set_;
  // MeasureOffset(set_, m, eye), looked up once: the sample loop reads it for every output.
  std::array<std::array<int, kNumEyes>, kNumMeasures> slot_{};
  std::vector<std::string> names_;
  std::vector<size_t> offsets_, point_of_;
  std::vector<bool> surface_, headline_;
};

template <typename T>
void ErrorOutputs::Measure(const ChainEvaluator& chain, const ChainSample<T>& sample, const T* theta, T* y,
                           bool* defined) const {
  using std::abs;
  using M = ErrorMeasure;
  constexpr double kDeg = 180.0 / kPi;
  const bool full = set_ == OutputSet::kFull;
  for (size_t k = 0; k < offsets_.size(); ++k) {
    defined[k] = sample.points[k].valid();
    if (!defined[k]) continue;
    const PointErrorsOf<T> e = MeasurePoint(chain, sample, theta, k, full);
    T* out = y + offsets_[k];
    // Each measure into its slot, where the set keeps it.
    auto put = [&](M m, int eye, const T& value) {
      const int slot = slot_[static_cast<int>(m)][eye];
      if (slot >= 0) out[slot] = value;
    };
    for (int i = 0; i < kNumEyes; ++i) put(M::kImagePixel, i, e.pixel_px[i]);
    put(M::kMisregistrationLinear, 0, e.misregistration.linear);
    put(M::kMisperceptionLinear, 0, e.misperception.linear);
    if (full) {
      put(M::kMisregistrationLateral, 0, e.misregistration.lateral);
      put(M::kMisregistrationDepth, 0, e.misregistration.depth);
      put(M::kMisregistrationDepthAbs, 0, abs(e.misregistration.depth));
      put(M::kMisregistrationAngular, 0, kDeg * e.misregistration.angular);
      put(M::kMisperceptionLateral, 0, e.misperception.lateral);
      put(M::kMisperceptionDepth, 0, e.misperception.depth);
      put(M::kMisperceptionDepthAbs, 0, abs(e.misperception.depth));
      put(M::kMisperceptionAngular, 0, kDeg * e.misperception.angular);
    }
    if (surface_[k]) {
      for (int i = 0; i < kNumEyes; ++i) put(M::kWrongOcclusion, i, e.wrong_occlusion[i]);
    }
  }
}

}  // namespace vstcal
