#include "vstcal/errsim/chain.h"

#include "vstcal/core/error.h"

namespace vstcal {

const char* UndefinedName(Undefined why) {
  switch (why) {
    case Undefined::kNone: return "defined";
    case Undefined::kBehindCamera: return "behind a camera";
    case Undefined::kOutsideLensDomain: return "outside the lens's valid domain";
    case Undefined::kOutsideImage: return "outside the image";
    case Undefined::kParallelRays: return "the eyes' rays are parallel";
  }
  return "?";
}

ChainEvaluator::ChainEvaluator(const ChainModel& model) : model_(model), layout_(model.layout) {
  const ChainGeometry& g = model_.geometry;
  VSTCAL_CHECK(static_cast<int>(model_.parameters.size()) == layout_.size(), "θ layout and parameter list disagree");
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
    const Camera& camera = g.cameras[e];
    VSTCAL_CHECK(model_.intrinsic_mixing[e].rows() == static_cast<int>(model_.renderer[e].params.size()) &&
                     model_.intrinsic_mixing[e].cols() == model_.intrinsic_mixing[e].rows(),
                 "intrinsic mixing and renderer lens disagree");
    VSTCAL_CHECK(layout_.Size(Term::kLens, e) == static_cast<int>(model_.renderer[e].params.size()),
                 "θ's lens block and renderer lens disagree");
    camera_from_hmd_[e] = g.camera_from_hmd[e];
    baseline_step_[e] = (e == 0 ? 0.5 : -0.5) * (g.camera_from_hmd[e].R * baseline_direction);
    design_eyepoint_[e] = g.display.DesignEyepoint(e);
    focal_baseline_[e] = camera.params[intrinsic::kFx] * baseline;
    mixing_is_identity_[e] = model_.intrinsic_mixing[e].isIdentity(0.0);
    extrinsic_mixing_is_identity_[e] = model_.extrinsic_mixing[e].isIdentity(0.0);
    const std::vector<double>& p = camera.params;
    using namespace intrinsic;
    // The display's focal lengths: its own when its field of view is given, else the camera's.
    const Eigen::Vector2d focal = g.display.focal_px[e].value_or(Eigen::Vector2d(p[kFx], p[kFy]));
    display_[e] = {p[kCx], p[kCy], p[kSkew] * focal.x() / p[kFx], 1.0 / focal.x(), 1.0 / focal.y(), g.camera_from_hmd[e].R.transpose(),
                   g.camera_from_hmd[e].R == Eigen::Matrix3d::Identity(), -0.5, camera.image_size.width - 0.5, -0.5,
                   camera.image_size.height - 0.5};
  }
  mount_mixing_is_identity_ = model_.mount_mixing.isIdentity(0.0);
  tracker_alignment_mixing_is_identity_ = model_.tracker_alignment_mixing.isIdentity(0.0);
  for (const ChainTestPoint& tp : g.test_points) {
    point_in_object_.push_back(object_from_world * tp.point_in_world);
    point_in_hmd_.push_back(hmd_from_world * tp.point_in_world);
    for (int e = 0; e < kNumEyes; ++e) {
      const Eigen::Vector3d x = g.camera_from_hmd[e] * point_in_hmd_.back();
      const auto q = g.cameras[e].Project(x);
      VSTCAL_CHECK(q.has_value(), "test point \"" + tp.name + "\" is behind a camera");
      real_pixel_[e].push_back(*q);
      real_centred_[e].push_back(*q - Eigen::Vector2d(display_[e].cx, display_[e].cy));
      real_depth_[e].push_back(x.z());
      surface_disparity_[e].push_back(tp.surface_behind ? focal_baseline_[e] / (x.z() + *tp.surface_behind) : 0.0);
    }
  }
  if (!model_.fiducials_in_object.empty()) {
    fiducials_ = RegistrationFrame::For(model_.fiducials_in_object);
    VSTCAL_CHECK(fiducials_.has_value(), "the fiducial layout is collinear");
    for (const auto& f : model_.fiducials_in_object) fiducials_in_virtual_.push_back(virtual_from_object_ * f);
  }

  // The error-free chain: every θ at 0 (not the mean — a bias is an error).
  systematic_.assign(num_points(), Systematic{});
  const std::vector<double> zero(layout_.size(), 0.0);
  ChainSample<double> nominal(num_points());
  Evaluate(zero.data(), &nominal);
  const Eigen::Vector3d cyclops = 0.5 * (nominal.eye[0] + nominal.eye[1]);
  nominal_undefined_.resize(num_points());
  for (size_t k = 0; k < num_points(); ++k) {
    const PointSample<double>& s = nominal.points[k];
    nominal_undefined_[k] = s.undefined;
    if (!s.valid()) continue;
    systematic_[k].offset = s.seen - s.truth;
    systematic_[k].error = RegistrationError<double>(cyclops, s.truth, systematic_[k].offset);
  }
}

}  // namespace vstcal
