#include "vstcal/errsim/chain.h"

#include "vstcal/core/error.h"

namespace vstcal::errsim {

ChainEvaluator::ChainEvaluator(const ChainModel& model) : model_(model), layout_(model.layout) {
  const ChainGeometry& g = model_.geometry;
  VSTCAL_CHECK(static_cast<int>(model_.parameters.size()) == layout_.size, "θ layout and parameter list disagree");
  tracker_from_virtual_ = g.tracker_from_world * g.world_from_virtual;
  virtual_from_object_ = g.world_from_virtual.inverse() * g.world_from_object;
  hmd_from_tracker_ = g.hmd_from_tracker;
  const Rigid3d object_from_world = g.world_from_object.inverse();
  const Rigid3d hmd_from_world = g.hmd_from_tracker * g.tracker_from_world;

  // Baseline error Δb moves the estimated left centre by −Δb/2 and the right by +Δb/2 along the
  // baseline e_b: a left perturbation ρ moves a camera centre by −Rᵀρ, so ρ_e = ±(Δb/2)·R_e·e_b.
  const Eigen::Vector3d left_centre = g.camera_from_hmd[0].inverse().t;
  const Eigen::Vector3d right_centre = g.camera_from_hmd[1].inverse().t;
  const double baseline = (right_centre - left_centre).norm();
  VSTCAL_CHECK(baseline > 0, "the two cameras coincide");
  camera_baseline_ = baseline;
  const Eigen::Vector3d baseline_direction = (right_centre - left_centre) / baseline;

  for (int e = 0; e < kNumEyes; ++e) {
    camera_from_hmd_[e] = g.camera_from_hmd[e];
    baseline_step_[e] = (e == 0 ? 0.5 : -0.5) * (g.camera_from_hmd[e].R * baseline_direction);
    lens_[e].fill(0.0);
    const std::vector<double>& params = g.cameras[e].params;
    for (size_t i = 0; i < params.size(); ++i) lens_[e][i] = params[i];
    mixing_is_identity_[e] = model_.intrinsic_mixing[e].isIdentity(0.0);
    display_[e] = {lens_[e][2], lens_[e][3], lens_[e][4], 1.0 / lens_[e][0], 1.0 / lens_[e][1],
                   g.camera_from_hmd[e].R.transpose()};
  }
  for (const TestPoint& tp : g.test_points) {
    point_in_object_.push_back(object_from_world * tp.point_in_world);
    point_in_hmd_.push_back(hmd_from_world * tp.point_in_world);
    for (int e = 0; e < kNumEyes; ++e) {
      const Eigen::Vector3d x = g.camera_from_hmd[e] * point_in_hmd_.back();
      const auto q = g.cameras[e].Project(x);
      VSTCAL_CHECK(q.has_value(), "test point \"" + tp.name + "\" is behind a camera");
      real_pixel_[e].push_back(*q);
      real_depth_[e].push_back(x.z());
    }
  }
  if (!model_.fiducials_in_object.empty()) {
    fiducials_ = RegistrationFrame::For(model_.fiducials_in_object);
    VSTCAL_CHECK(fiducials_.has_value(), "the fiducial layout is collinear");
    for (const auto& f : model_.fiducials_in_object) fiducials_in_virtual_.push_back(virtual_from_object_ * f);
  }
}

}  // namespace vstcal::errsim
