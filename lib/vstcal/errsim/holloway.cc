#include "vstcal/errsim/holloway.h"

#include <cmath>
#include <limits>

namespace vstcal::errsim {

PointErrors MeasurePoint(const ChainEvaluator& chain, const ChainSample<double>& sample, const double* theta, size_t k) {
  constexpr double kDeg = 180.0 / kPi;
  const PointSample<double>& s = sample.points[k];
  const ChainModel& model = chain.model();
  PointErrors e;
  for (int i = 0; i < kNumEyes; ++i) {
    e.pixel_px[i] = s.pixel_error[i].norm();
    e.angular_deg[i] = kDeg * AngleBetweenVectors(s.ray[i], s.truth - sample.eye[i]);
  }
  const Eigen::Vector3d cyclops = 0.5 * (sample.eye[0] + sample.eye[1]);
  const Eigen::Vector3d sight = s.truth - cyclops;  // not normalized: depth = Δ·s/|s|, lateral = |Δ × s|/|s|
  const double inverse_distance = 1.0 / sight.norm();
  const Eigen::Vector3d delta = s.perceived - s.truth;
  e.linear = delta.norm();
  e.depth = delta.dot(sight) * inverse_distance;
  e.lateral = delta.cross(sight).norm() * inverse_distance;
  e.angular_deg_cyclopean = kDeg * AngleBetweenVectors(s.truth - cyclops, s.perceived - cyclops);

  const auto& surface = model.geometry.test_points[k].surface_behind;
  if (surface) {
    const double disparity_error = theta[model.layout.rendering + 1 + k];
    const double baseline = chain.camera_baseline();
    for (int i = 0; i < kNumEyes; ++i) {
      const double fb = model.geometry.cameras[i].params[0] * baseline;
      const double z_surface = chain.real_depth(i, k) + *surface;
      const double disparity = fb / z_surface + disparity_error;
      // No positive disparity: the matcher sees the surface at infinity, and the overlay is drawn.
      const double measured = disparity > 0 ? fb / disparity : std::numeric_limits<double>::infinity();
      const bool drawn = s.virtual_depth[i] < measured;
      e.wrong_occlusion[i] = drawn != (*surface > 0) ? 1 : 0;
    }
  }
  return e;
}

ErrorOutputs::ErrorOutputs(const ChainModel& model) {
  for (const TestPoint& tp : model.geometry.test_points) {
    offsets_.push_back(names_.size());
    occlusion_.push_back(tp.surface_behind.has_value());
    for (const char* name : {".left.pixel_px", ".left.angular_deg", ".right.pixel_px", ".right.angular_deg", ".linear",
                             ".lateral", ".depth", ".depth_abs", ".angular_deg"}) {
      names_.push_back(tp.name + name);
    }
    if (tp.surface_behind) {
      names_.push_back(tp.name + ".left.wrong_occlusion");
      names_.push_back(tp.name + ".right.wrong_occlusion");
    }
  }
}

bool ErrorOutputs::Measure(const ChainEvaluator& chain, const ChainSample<double>& sample, const double* theta,
                           double* y) const {
  for (size_t k = 0; k < offsets_.size(); ++k) {
    if (!sample.points[k].valid) return false;
    const PointErrors e = MeasurePoint(chain, sample, theta, k);
    double* out = y + offsets_[k];
    out[0] = e.pixel_px[0];
    out[1] = e.angular_deg[0];
    out[2] = e.pixel_px[1];
    out[3] = e.angular_deg[1];
    out[4] = e.linear;
    out[5] = e.lateral;
    out[6] = e.depth;
    out[7] = std::abs(e.depth);
    out[8] = e.angular_deg_cyclopean;
    if (occlusion_[k]) {
      out[9] = e.wrong_occlusion[0];
      out[10] = e.wrong_occlusion[1];
    }
  }
  return true;
}

}  // namespace vstcal::errsim
