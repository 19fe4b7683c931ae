// The weighted reprojection residual shared by every reprojection cost (reprojection_cost.h for
// one camera, chained_reprojection_cost.h for a rig's second camera): for an observation (X, q, w)
// whose point has been carried to the camera frame as p,
//
//   r = √w (project(θ, p) − q),   ∂r/∂θ = √w ∂q/∂θ,
//
// so a point of weight w counts as w points of weight 1 (docs/formats.md#weights). The costs chain
// ∂q/∂p (returned unweighted, with √w) into their own pose Jacobians.
#pragma once

#include <cmath>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "vstcal/geometry/rigid3.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal {

using RowMajor2x3 = Eigen::Matrix<double, 2, 3, Eigen::RowMajor>;

// A residual block's observations: each point in the block's reference frame (frame_from_points ·
// X, computed once), its measured pixel and √w.
class WeightedObservations {
 public:
  WeightedObservations(std::span<const Observation> observations, const Rigid3d& frame_from_points) {
    for (const Observation& o : observations) {
      y_.push_back(frame_from_points * o.point);
      pixels_.push_back(o.pixel);
      sqrt_weights_.push_back(std::sqrt(o.weight));
    }
  }

  size_t size() const { return y_.size(); }
  const Eigen::Vector3d& point(size_t i) const { return y_[i]; }

  // Observation i's 2 weighted residuals for its point at p in the camera frame, with √w in
  // *sqrt_weight; when asked, d_params (2 × kNumParams, row-major, weighted) and the unweighted
  // ∂q/∂p. False, with nothing written, when p is behind the camera (z ≤ 0).
  template <typename Model>
  bool Residual(size_t i, const double* params, const Eigen::Vector3d& p, double* residual, double* d_params,
                RowMajor2x3* d_q_d_p, double* sqrt_weight) const {
    double q[2];
    if (!Model::ProjectWithJacobians(params, p.data(), q, d_params, d_q_d_p ? d_q_d_p->data() : nullptr)) return false;
    const double w = sqrt_weights_[i];
    residual[0] = w * (q[0] - pixels_[i].x());
    residual[1] = w * (q[1] - pixels_[i].y());
    if (d_params && w != 1.0) {
      for (int k = 0; k < 2 * Model::kNumParams; ++k) d_params[k] *= w;
    }
    *sqrt_weight = w;
    return true;
  }

 private:
  std::vector<Eigen::Vector3d> y_;
  std::vector<Eigen::Vector2d> pixels_;
  std::vector<double> sqrt_weights_;
};

}  // namespace vstcal
