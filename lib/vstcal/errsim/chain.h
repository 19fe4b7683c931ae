// The VST registration chain, written once and templated on the scalar: Monte Carlo runs it with
// double, linear propagation with ceres::Jet (docs/math/vst-chain.md).
//
// For each test point p (world frame) and each eye e:
//   real path     q_real = project(K_e, x),  x = camera_from_hmd_e · hmd_from_tracker · tracker_from_world · p
//   virtual path  q_virt = project(K̂_e, x̂), x̂ = ĉamera_from_hmd_e · ĥmd_from_tracker · t̂racker_from_virtual
//                                                · v̂irtual_from_object · p_object
// with p_object = object_from_world · p (the virtual twin has the physical object's nominal
// coordinates). Every hat is the nominal transform perturbed by its source's block of θ
// (chain_model.h). Image misregistration is q_virt − q_real, per eye. The viewer then sees each
// eye's composited pixel through the display (screen mapping, lens residual) from the true eye
// position; the perceived overlay is the midpoint of the two eyes' rays, compared with the physical
// point in the head frame at display time (display latency) — Holloway's errors (holloway.h).
//
// The same code runs with double, ceres::Jet and SimdDouble (four samples at once,
// sample_measurer.h). Products and sums go through fixed_order.h, so double and SimdDouble give
// the same bits for every sample.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/errsim/point_registration.h"
#include "vstcal/geometry/fixed_order.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal::errsim {

template <typename T>
using Vec2 = Eigen::Matrix<T, 2, 1>;

template <typename T>
struct PointSample {
  bool valid = false;                   // false: behind a virtual camera, or the eyes' rays are parallel
  std::array<Vec2<T>, kNumEyes> pixel_error;  // q_virt − q_real, px
  std::array<T, kNumEyes> virtual_depth;      // z of the virtual point in each virtual camera (occlusion)
  std::array<Vec3<T>, kNumEyes> ray;          // perceived direction from each eye, hmd frame, not unit
  Vec3<T> perceived;                          // the perceived overlay, hmd frame
  Vec3<T> truth;                              // the physical point, hmd frame at display time
};

template <typename T>
struct ChainSample {
  explicit ChainSample(size_t num_points) : points(num_points) {}
  std::array<Vec3<T>, kNumEyes> eye;  // the viewer's eyes, hmd frame
  std::vector<PointSample<T>> points;
};

class ChainEvaluator {
 public:
  // Requires every test point in front of both cameras (chain_io checks and names the point) and,
  // with fiducials, a non-collinear layout; InternalError otherwise.
  explicit ChainEvaluator(const ChainModel& model);

  const ChainModel& model() const { return model_; }
  size_t num_points() const { return point_in_object_.size(); }
  const Eigen::Vector2d& real_pixel(int eye, size_t point) const { return real_pixel_[eye][point]; }
  double real_depth(int eye, size_t point) const { return real_depth_[eye][point]; }
  double camera_baseline() const { return camera_baseline_; }

  template <typename T>
  void Evaluate(const T* theta, ChainSample<T>* out) const;

  // Vector outputs for linear propagation (sensitivity::Model::Templated): per test point
  // [du_left, dv_left, du_right, dv_right, dx, dy, dz] (px, then perceived − true in the hmd frame).
  static constexpr int kOutputsPerPoint = 7;
  size_t num_vector_outputs() const { return kOutputsPerPoint * num_points(); }
  template <typename T>
  bool operator()(const T* theta, T* y) const;

 private:
  template <typename T>
  Rigid3<T> VirtualFromObject(const T* block) const;
  template <typename T>
  Vec3<T> DisplayedRay(int eye, const Vec2<T>& pixel, const T* display_block) const;

  ChainModel model_;
  ParameterLayout layout_;
  double camera_baseline_ = 0;
  Rigid3d tracker_from_virtual_, virtual_from_object_, hmd_from_tracker_;
  std::array<Rigid3d, kNumEyes> camera_from_hmd_;
  std::array<Eigen::Vector3d, kNumEyes> baseline_step_;  // ρ per unit of baseline error, camera frame
  std::array<std::array<double, kNumLensParams>, kNumEyes> lens_;
  std::array<bool, kNumEyes> mixing_is_identity_;
  std::vector<Eigen::Vector3d> point_in_object_, point_in_hmd_;
  std::array<std::vector<Eigen::Vector2d>, kNumEyes> real_pixel_;
  std::array<std::vector<double>, kNumEyes> real_depth_;
  struct DisplayConstants {
    double cx, cy, s, inverse_fx, inverse_fy;
    Eigen::Matrix3d hmd_from_camera;  // nominal rotation: the eye looks along its camera's axes
  };
  std::array<DisplayConstants, kNumEyes> display_;
  std::optional<RegistrationFrame> fiducials_;
  std::vector<Eigen::Vector3d> fiducials_in_virtual_;  // nominal measured positions
};

// ---------------------------------------------------------------------------------------------

template <typename T>
Rigid3<T> ChainEvaluator::VirtualFromObject(const T* block) const {
  if (!fiducials_) {
    return fixed_order::PerturbLeft(virtual_from_object_, Vec3<T>(block[0], block[1], block[2]),
                                    Vec3<T>(block[3], block[4], block[5]));
  }
  // The fiducials as measured in the virtual world (true position + localization error), then the
  // least-squares registration of the object-frame layout onto them.
  const size_t n = fiducials_in_virtual_.size();
  std::array<Vec3<T>, 64> measured_small;
  std::vector<Vec3<T>> measured_large;
  Vec3<T>* measured = measured_small.data();
  if (n > measured_small.size()) {
    measured_large.resize(n);
    measured = measured_large.data();
  }
  for (size_t k = 0; k < n; ++k) {
    measured[k] = fiducials_in_virtual_[k].cast<T>() + Vec3<T>(block[3 * k], block[3 * k + 1], block[3 * k + 2]);
  }
  return RefineRegistration<T>(*fiducials_, virtual_from_object_.R.cast<T>(), measured);
}

template <typename T>
Vec3<T> ChainEvaluator::DisplayedRay(int eye, const Vec2<T>& pixel, const T* d) const {
  // d: this eye's display block [eyepoint(3), shift u, shift v, magnification, lens k1]. The display
  // shows the image with the true camera's field of view (K⁻¹ of the true K), about its principal point.
  const DisplayConstants& c = display_[eye];
  const T du = (T(1) + d[5]) * (pixel(0) - T(c.cx)) + d[3];
  const T dv = (T(1) + d[5]) * (pixel(1) - T(c.cy)) + d[4];
  const T yn = dv * T(c.inverse_fy);
  const T xn = (du - T(c.s) * yn) * T(c.inverse_fx);
  // The HMD lens's uncorrected radial term scales the direction by 1 + k1·r².
  const T radial = T(1) + d[6] * (xn * xn + yn * yn);
  const Vec3<T> direction(xn * radial, yn * radial, T(1));
  return fixed_order::Times(c.hmd_from_camera, direction);
}

template <typename T>
void ChainEvaluator::Evaluate(const T* theta, ChainSample<T>* out) const {
  namespace fo = fixed_order;
  const ParameterLayout& L = layout_;
  const T* ta = theta + L.tracker_alignment;
  const Rigid3<T> tracker_from_virtual =
      fo::PerturbLeft(tracker_from_virtual_, Vec3<T>(ta[0], ta[1], ta[2]), Vec3<T>(ta[3], ta[4], ta[5]));
  const Rigid3<T> virtual_from_object = VirtualFromObject(theta + L.virtual_object_alignment);

  // The renderer's pose is older than the video frame by the tracking and render latencies: the
  // head moved by (ω·age, v·age) in between (hmd(t − age)_from_hmd(t), first order in the motion).
  const T* tr = theta + L.tracking;
  const T age = tr[6] + theta[L.rendering];
  const Eigen::Vector3d& w = model_.geometry.head_angular_velocity;
  const Eigen::Vector3d& v = model_.geometry.head_linear_velocity;
  const Rigid3<T> lagged = fo::PerturbLeft(hmd_from_tracker_, Vec3<T>(w.cast<T>() * age), Vec3<T>(v.cast<T>() * age));
  const Rigid3<T> hmd_from_tracker =
      fo::PerturbLeft(lagged, Vec3<T>(tr[0], tr[1], tr[2]), Vec3<T>(tr[3], tr[4], tr[5]));
  // The stereo rig's mount error is common to both eyes: camera_from_hmd_e · (Exp(ω), ρ) · hmd_from_object.
  const T* rig = theta + L.camera_extrinsic + 13;
  const Rigid3<T> hmd_from_object =
      fo::PerturbLeft(fo::Compose(hmd_from_tracker, fo::Compose(tracker_from_virtual, virtual_from_object)),
                      Vec3<T>(rig[0], rig[1], rig[2]), Vec3<T>(rig[3], rig[4], rig[5]));

  auto camera_from_object_of = [&](int e) {
    const T* ce = theta + L.camera_extrinsic + 6 * e;
    const T baseline = theta[L.camera_extrinsic + 12];
    const Vec3<T> rho = Vec3<T>(ce[3], ce[4], ce[5]) + baseline_step_[e].cast<T>() * baseline;
    return fo::Compose(fo::PerturbLeft(camera_from_hmd_[e], Vec3<T>(ce[0], ce[1], ce[2]), rho), hmd_from_object);
  };
  // Built in place: a default Rigid3 would first be written as the identity.
  const std::array<Rigid3<T>, kNumEyes> camera_from_object = {camera_from_object_of(0), camera_from_object_of(1)};
  std::array<std::array<T, kNumLensParams>, kNumEyes> lens;
  const T* ds = theta + L.display;
  const T ipd = T(model_.geometry.ipd) + ds[2 * ParameterLayout::kDisplayPerEye];
  for (int e = 0; e < kNumEyes; ++e) {
    const T* ci = theta + L.camera_intrinsic + kNumLensParams * e;
    for (int i = 0; i < kNumLensParams; ++i) {
      T delta = ci[i];
      if (!mixing_is_identity_[e]) {
        delta = T(0);
        for (int j = 0; j < kNumLensParams; ++j) delta += model_.intrinsic_mixing[e](i, j) * ci[j];
      }
      lens[e][i] = T(lens_[e][i]) + delta;
    }
    const T* de = ds + ParameterLayout::kDisplayPerEye * e;
    const T side = T(e == 0 ? -0.5 : 0.5);
    out->eye[e] = model_.geometry.eye_centre_in_hmd.cast<T>() + Vec3<T>(side * ipd, T(0), T(0)) + Vec3<T>(de[0], de[1], de[2]);
  }

  // What the eyes see now was captured display_latency ago: the physical point, in the head frame
  // at display time, is hmd(t)_from_hmd(t − τ) · p = δ⁻¹ · p with δ = (Exp(ω τ), v τ).
  const T display_latency = ds[2 * ParameterLayout::kDisplayPerEye + 1];
  const Rigid3<T> motion{fo::Exp(Vec3<T>(w.cast<T>() * display_latency)), Vec3<T>(v.cast<T>() * display_latency)};
  const Rigid3<T> now_from_captured = fo::Inverse(motion);

  // Point by point in three passes (the truth, each eye's path, the perceived point) rather than
  // one: the iterations of a pass are independent, short enough for the processor to overlap them
  // (each eye's path waits on two divisions), and the numbers are the same.
  const size_t num_points = point_in_object_.size();
  for (size_t k = 0; k < num_points; ++k) {
    PointSample<T>& s = out->points[k];
    s.valid = true;
    s.truth = fo::Apply(now_from_captured, Vec3<T>(point_in_hmd_[k].cast<T>()));
  }
  for (size_t k = 0; k < num_points; ++k) {
    PointSample<T>& s = out->points[k];
    for (int e = 0; e < kNumEyes && s.valid; ++e) {
      const Vec3<T> x = fo::Apply(camera_from_object[e], Vec3<T>(point_in_object_[k].cast<T>()));
      Vec2<T> q;
      if (!VirtualLens::Project(lens[e].data(), x.data(), q.data())) {
        s.valid = false;
        break;
      }
      s.pixel_error[e] = q - real_pixel_[e][k].cast<T>();
      s.virtual_depth[e] = x(2);
      s.ray[e] = DisplayedRay(e, q, ds + ParameterLayout::kDisplayPerEye * e);
    }
  }
  const Vec3<T> between = out->eye[1] - out->eye[0];
  for (size_t k = 0; k < num_points; ++k) {
    PointSample<T>& s = out->points[k];
    if (!s.valid) continue;
    // Midpoint of the closest approach of eye_l + s0·ray_l and eye_r + s1·ray_r. With n = d0 × d1,
    // s0 = ((e1 − e0) × d1)·n/|n|² and s1 = ((e1 − e0) × d0)·n/|n|²: unlike the textbook
    // (a c − b²) form these do not cancel catastrophically when the rays are nearly parallel
    // (vergence 0.02 rad at 3 m with a 63 mm baseline).
    const Vec3<T>& d0 = s.ray[0];
    const Vec3<T>& d1 = s.ray[1];
    const Vec3<T> n = fo::Cross(d0, d1);
    const T n2 = fo::SquaredNorm(n);
    if (!(n2 > T(1e-24) * fo::SquaredNorm(d0) * fo::SquaredNorm(d1))) {
      s.valid = false;
      continue;
    }
    const T inverse_n2 = T(1) / n2;
    const T s0 = fo::Dot(fo::Cross(between, d1), n) * inverse_n2;
    const T s1 = fo::Dot(fo::Cross(between, d0), n) * inverse_n2;
    s.perceived = T(0.5) * (out->eye[0] + s0 * d0 + out->eye[1] + s1 * d1);
  }
}

template <typename T>
bool ChainEvaluator::operator()(const T* theta, T* y) const {
  ChainSample<T> sample(num_points());
  Evaluate(theta, &sample);
  for (size_t k = 0; k < sample.points.size(); ++k) {
    const PointSample<T>& s = sample.points[k];
    if (!s.valid) return false;
    T* out = y + kOutputsPerPoint * k;
    out[0] = s.pixel_error[0](0);
    out[1] = s.pixel_error[0](1);
    out[2] = s.pixel_error[1](0);
    out[3] = s.pixel_error[1](1);
    const Vec3<T> delta = s.perceived - s.truth;
    out[4] = delta(0);
    out[5] = delta(1);
    out[6] = delta(2);
  }
  return true;
}

}  // namespace vstcal::errsim
