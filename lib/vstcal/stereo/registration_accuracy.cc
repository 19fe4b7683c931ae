#include "vstcal/stereo/registration_accuracy.h"

#include <algorithm>
#include <cmath>

namespace vstcal {

std::optional<FrameAccuracy> AccuracyOf(const StereoRig& rig, const TrackedFrame& frame, const FrameRegistration& registration,
                                        std::span<const NamedPoint> virtual_points) {
  if (!frame.truth_left_from_world || registration.status != PoseStatus::kOk) return std::nullopt;
  const Rigid3d truth[2] = {*frame.truth_left_from_world, rig.right_from_left * *frame.truth_left_from_world};
  const Rigid3d estimate[2] = {registration.left_from_world, registration.right_from_world};
  const Camera* cameras[2] = {&rig.left.camera, &rig.right.camera};
  FrameAccuracy a;
  for (int e = 0; e < 2; ++e) {
    a.rotation_deg[e] = RadToDeg(AngleBetween(estimate[e].R, truth[e].R));
    a.centre_error[e] = (estimate[e].inverse().t - truth[e].inverse().t).norm();
    std::vector<Eigen::Vector2d> residuals;
    for (const NamedPoint& p : virtual_points) {
      const auto seen = cameras[e]->Project(estimate[e] * p.point_in_world);
      const auto real = cameras[e]->Project(truth[e] * p.point_in_world);
      if (seen && real) residuals.push_back(*seen - *real);
    }
    a.virtual_px[e] = Summarize(residuals);
  }
  return a;
}

namespace {

// RMS and max of one number per frame.
struct Accumulator {
  double sum2 = 0, max = 0;
  size_t n = 0;
  void Add(double v) {
    sum2 += v * v;
    max = std::max(max, v);
    ++n;
  }
  ResidualStats Stats() const { return {n ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0, max, n}; }
};

}  // namespace

std::optional<SequenceAccuracy> SummarizeAccuracy(std::span<const std::optional<FrameAccuracy>> frames) {
  std::array<Accumulator, 2> rotation, centre, pixels;
  SequenceAccuracy s;
  for (const auto& f : frames) {
    if (!f) continue;
    ++s.frames;
    for (int e = 0; e < 2; ++e) {
      rotation[e].Add(f->rotation_deg[e]);
      centre[e].Add(f->centre_error[e]);
      // Every virtual point of every frame counts once: the pooled RMS of the overlay error.
      pixels[e].sum2 += f->virtual_px[e].rms_px * f->virtual_px[e].rms_px * static_cast<double>(f->virtual_px[e].n_points);
      pixels[e].max = std::max(pixels[e].max, f->virtual_px[e].max_px);
      pixels[e].n += f->virtual_px[e].n_points;
    }
  }
  if (s.frames == 0) return std::nullopt;
  for (int e = 0; e < 2; ++e) {
    s.rotation_deg[e] = rotation[e].Stats();
    s.centre_error[e] = centre[e].Stats();
    s.virtual_px[e] = pixels[e].Stats();
  }
  return s;
}

}  // namespace vstcal
