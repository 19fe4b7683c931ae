// The VST registration chain, written once and templated on the scalar: Monte Carlo runs it with
// double and SimdDouble (four samples at once, sample_measurer.h), linear propagation and sweep
// slopes with ceres::Jet (docs/math/vst-chain.md).
//
// For each test point p (world frame) and each eye e:
//   real path     q_e = project(camera_e, x),  x = camera_from_hmd_e · hmd_from_tracker · tracker_from_world · p
//   virtual path  q̂_e = project(renderer_e, x̂), x̂ = ĉamera_from_hmd_e · ĥmd_from_tracker · t̂racker_from_virtual
//                                                    · v̂irtual_from_object · p_object
// with p_object = object_from_world · p. Every hat is the nominal transform perturbed by its
// term of θ (schema.h). The display shows eye e its composited video: pixel q on a virtual image
// plane at distance D (chain_model.h, DisplayGeometry), seen from the eye's actual eyepoint E_e. So
// the eyes see the overlay along the rays through q̂_l, q̂_r and the video image of the physical
// point along the rays through q_l, q_r; each pair is triangulated (geometry/registration_error.h):
//   overlay P̂' and seen P' — misregistration = P̂' − P' (what the user sees as misalignment; the
//   display moves both together), misperception = P' − P (where the user perceives the point
//   against where it is at display time), measured relative to the error-free chain's own
//   (systematic) misperception.
//
// Products and sums go through fixed_order.h, so double and SimdDouble give the same bits for every
// sample.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/errsim/outputs.h"
#include "vstcal/geometry/point_registration.h"
#include "vstcal/geometry/fixed_order.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/geometry/registration_error.h"

namespace vstcal {

template <typename T>
using Vec2 = Eigen::Matrix<T, 2, 1>;

// Why a test point of a sample is undefined (docs/math/vst-chain.md#undefined). Such a point is
// counted and left out of every statistic, never zeroed.
enum class Undefined : uint8_t {
  kNone = 0,
  kBehindCamera,       // the virtual point is not in front of the renderer's camera
  kOutsideLensDomain,  // beyond the lens's valid domain (Camera::ValidRadiusSquared)
  kOutsideImage,       // the overlay pixel leaves the image
  kParallelRays,       // the eyes' rays do not meet: no point is seen
};
const char* UndefinedName(Undefined why);

template <typename T>
struct PointSample {
  Undefined undefined = Undefined::kNone;  // SimdDouble: the lanes agree, else the group is redone
  int undefined_eye = 0;                   // the eye it happened in (kBehindCamera … kOutsideImage)
  std::array<Vec2<T>, kNumEyes> pixel_error;  // q̂ − q, px
  std::array<T, kNumEyes> virtual_depth;      // z of the virtual point in each renderer camera (occlusion)
  std::array<Vec3<T>, kNumEyes> overlay_ray, seen_ray;  // from each eye, hmd frame, not unit
  Vec3<T> overlay;  // where the eyes see the overlay, hmd frame
  Vec3<T> seen;     // where the eyes see the video image of the physical point, hmd frame
  Vec3<T> truth;    // the physical point, hmd frame at display time
  bool valid() const { return undefined == Undefined::kNone; }
};

template <typename T>
struct ChainSample {
  explicit ChainSample(size_t num_points) : points(num_points) {}
  std::array<Vec3<T>, kNumEyes> eye;  // the viewer's eyepoints, hmd frame
  std::vector<PointSample<T>> points;
};

// The error-free chain's misperception of a test point: the camera–eye offset, an IPD other than
// the camera baseline and a distorting camera shown undistorted-as-pinhole make the viewer see the
// world displaced even with every error at 0. Reported on its own; the misperception of every
// sample is measured relative to it.
struct Systematic {
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // seen − truth at θ = 0, hmd frame
  RegistrationErrorOf<double> error{};               // Holloway's terms of it (angular in radians)
};

class ChainEvaluator {
 public:
  // Requires every test point in front of both cameras (the chain reader checks and names the
  // point) and, with fiducials, a non-collinear layout; InternalError otherwise.
  explicit ChainEvaluator(const ChainModel& model);

  const ChainModel& model() const { return model_; }
  size_t num_points() const { return point_in_object_.size(); }
  const Eigen::Vector2d& real_pixel(int eye, size_t point) const { return real_pixel_[eye][point]; }
  double real_depth(int eye, size_t point) const { return real_depth_[eye][point]; }
  double camera_baseline() const { return camera_baseline_; }
  // For the occlusion decision: f·b of eye e's camera (fx times the baseline), and the disparity
  // f·b/z_s of the real surface behind test point k (0 without surface_behind).
  double focal_baseline(int eye) const { return focal_baseline_[eye]; }
  double surface_disparity(int eye, size_t point) const { return surface_disparity_[eye][point]; }
  const Systematic& systematic(size_t point) const { return systematic_[point]; }
  // Why the error-free chain cannot see test point k (kNone when it can; the chain reader refuses
  // such a chain, naming the point).
  Undefined nominal_undefined(size_t point) const { return nominal_undefined_[point]; }

  // The chain at θ; shared and correlated terms (model().couplings) are applied first.
  template <typename T>
  void Evaluate(const T* theta, ChainSample<T>* out) const;

  // Vector outputs for linear propagation (Model::Templated): per test point kVectorOutputs
  // (outputs.h) — each eye's q̂ − q (px), the misregistration P̂' − P' and the misperception
  // relative to the systematic one (hmd frame). False when a point is undefined.
  size_t num_vector_outputs() const { return kVectorOutputsPerPoint * num_points(); }
  template <typename T>
  bool operator()(const T* theta, T* y) const;

 private:
  template <typename T>
  const T* At(const T* theta, Term term, int eye = 0) const {
    return theta + layout_.Offset(term, eye);
  }
  template <typename T>
  static Vec3<T> Vec(const T* p) {
    return Vec3<T>(p[0], p[1], p[2]);
  }
  template <typename T>
  Rigid3<T> VirtualFromObject(const T* theta) const;
  // The chain at θ whose slots are read as they are (no coupling between slots).
  template <typename T>
  void EvaluateUncoupled(const T* theta, ChainSample<T>* out) const;
  // (ω, ρ) ← M·(ω, ρ): standard normals to a measured covariance's correlated pose error (a rig's
  // right_from_left, a hand-eye X or Z). Summed in j order, so every scalar type gives the same bits.
  template <typename T>
  static void MixPose(const ChainModel::Matrix6d& m, Vec3<T>* omega, Vec3<T>* rho) {
    const std::array<T, 6> z = {(*omega)(0), (*omega)(1), (*omega)(2), (*rho)(0), (*rho)(1), (*rho)(2)};
    for (int i = 0; i < 6; ++i) {
      T sum = m(i, 0) * z[0];
      for (int j = 1; j < 6; ++j) sum += m(i, j) * z[j];
      (i < 3 ? (*omega)(i) : (*rho)(i - 3)) = sum;
    }
  }
  template <typename T>
  Vec3<T> DisplayedDirection(int eye, const Vec2<T>& centred, const T* shift, const T& scale, const T& lens_k1) const;

  ChainModel model_;
  ParameterLayout layout_;
  double camera_baseline_ = 0;
  Rigid3d tracker_from_virtual_, virtual_from_object_, hmd_from_tracker_;
  std::array<Rigid3d, kNumEyes> camera_from_hmd_;
  std::array<Eigen::Vector3d, kNumEyes> baseline_step_;  // ρ per unit of baseline error, camera frame
  std::array<Eigen::Vector3d, kNumEyes> design_eyepoint_;
  std::array<bool, kNumEyes> mixing_is_identity_, extrinsic_mixing_is_identity_;
  bool mount_mixing_is_identity_ = true, tracker_alignment_mixing_is_identity_ = true;
  std::vector<Eigen::Vector3d> point_in_object_, point_in_hmd_;
  std::array<std::vector<Eigen::Vector2d>, kNumEyes> real_pixel_, real_centred_;  // q, and q − principal point
  std::array<std::vector<double>, kNumEyes> real_depth_, surface_disparity_;
  std::array<double, kNumEyes> focal_baseline_{};
  struct DisplayConstants {
    double cx, cy, s, inverse_fx, inverse_fy;  // the display's K⁻¹: the true camera's, or scaled to its own field of view
    Eigen::Matrix3d hmd_from_camera;           // nominal rotation: the display is aligned with the camera's axes
    bool camera_axes_are_hmd_axes;             // hmd_from_camera is exactly I (most rigs): no rotation to apply
    double min_u, max_u, min_v, max_v;         // the image, px
  };
  std::array<DisplayConstants, kNumEyes> display_;
  std::optional<RegistrationFrame> fiducials_;
  std::vector<Eigen::Vector3d> fiducials_in_virtual_;  // nominal measured positions
  std::vector<Systematic> systematic_;
  std::vector<Undefined> nominal_undefined_;
};

// ---------------------------------------------------------------------------------------------

template <typename T>
Rigid3<T> ChainEvaluator::VirtualFromObject(const T* theta) const {
  namespace fo = fixed_order;
  const Vec3<T> rotation = Vec(At(theta, Term::kObjectRotation)), translation = Vec(At(theta, Term::kObjectTranslation));
  if (!fiducials_) return fo::PerturbLeft(virtual_from_object_, rotation, translation);
  // The fiducials as measured in the virtual world (true position + localization error), then the
  // least-squares registration of the object-frame layout onto them. (The pose terms are 0 here.)
  const T* block = At(theta, Term::kFiducial);
  const size_t n = fiducials_in_virtual_.size();
  std::array<Vec3<T>, 64> measured_small;
  std::vector<Vec3<T>> measured_large;
  Vec3<T>* measured = measured_small.data();
  if (n > measured_small.size()) {
    measured_large.resize(n);
    measured = measured_large.data();
  }
  for (size_t k = 0; k < n; ++k) measured[k] = fiducials_in_virtual_[k].cast<T>() + Vec(block + 3 * k);
  return fo::PerturbLeft(RefineRegistration<T>(*fiducials_, virtual_from_object_.R.cast<T>(), measured), rotation,
                         translation);
}

template <typename T>
Vec3<T> ChainEvaluator::DisplayedDirection(int eye, const Vec2<T>& centred, const T* shift, const T& scale,
                                           const T& lens_k1) const {
  // The screen mapping (scale = 1 + magnification about the principal point, shift), the true
  // camera's K⁻¹, the HMD lens's uncorrected radial term 1 + k1·r², the camera's nominal axes.
  const DisplayConstants& c = display_[eye];
  const T du = scale * centred(0) + shift[0];
  const T dv = scale * centred(1) + shift[1];
  const T yn = dv * T(c.inverse_fy);
  const T xn = (du - T(c.s) * yn) * T(c.inverse_fx);
  const T radial = T(1) + lens_k1 * (xn * xn + yn * yn);
  const Vec3<T> direction(xn * radial, yn * radial, T(1));
  // Branching on a constant of the chain, the same for every lane. I·v gives v's bits too (x·1 + 0
  // adds nothing but the sign of a zero, which no later step can see): the shortcut changes no number.
  return c.camera_axes_are_hmd_axes ? direction : fixed_order::Times(c.hmd_from_camera, direction);
}

template <typename T>
void ChainEvaluator::Evaluate(const T* theta, ChainSample<T>* out) const {
  // Branching on a constant of the chain: a chain without couplings reads θ in place, with the
  // bits it always had.
  if (model_.couplings.empty()) return EvaluateUncoupled(theta, out);
  const size_t n = static_cast<size_t>(layout_.size());
  // On the stack for the Monte Carlo scalars (no allocation per sample); Jets go to the heap.
  auto couple = [&](T* coupled) {
    ApplyCouplings(model_, theta, coupled);
    EvaluateUncoupled(static_cast<const T*>(coupled), out);
  };
  constexpr size_t kOnStack = 512;
  if constexpr (sizeof(T) <= 64) {
    if (n <= kOnStack) {
      std::array<T, kOnStack> small;
      return couple(small.data());
    }
  }
  std::vector<T> large(n);
  couple(large.data());
}

template <typename T>
void ChainEvaluator::EvaluateUncoupled(const T* theta, ChainSample<T>* out) const {
  namespace fo = fixed_order;
  Vec3<T> alignment_omega = Vec(At(theta, Term::kTrackerAlignmentRotation)),
          alignment_rho = Vec(At(theta, Term::kTrackerAlignmentTranslation));
  if (!tracker_alignment_mixing_is_identity_) MixPose(model_.tracker_alignment_mixing, &alignment_omega, &alignment_rho);
  const Rigid3<T> tracker_from_virtual = fo::PerturbLeft(tracker_from_virtual_, alignment_omega, alignment_rho);
  const Rigid3<T> virtual_from_object = VirtualFromObject(theta);

  // The renderer's pose is older than the video frame by the tracking and render latencies: the
  // head moved by (ω·age, v·age) in between (hmd(t − age)_from_hmd(t), first order in the motion).
  const T age = At(theta, Term::kTrackingLatency)[0] + At(theta, Term::kRenderLatency)[0];
  const Eigen::Vector3d& w = model_.geometry.head_angular_velocity;
  const Eigen::Vector3d& v = model_.geometry.head_linear_velocity;
  const Rigid3<T> lagged = fo::PerturbLeft(hmd_from_tracker_, Vec3<T>(w.cast<T>() * age), Vec3<T>(v.cast<T>() * age));
  const Rigid3<T> hmd_from_tracker =
      fo::PerturbLeft(lagged, Vec(At(theta, Term::kTrackingRotation)), Vec(At(theta, Term::kTrackingTranslation)));
  // The stereo rig's mount error is common to both eyes: camera_from_hmd_e · (Exp(ω), ρ) · hmd_from_object.
  Vec3<T> mount_omega = Vec(At(theta, Term::kRigRotation)), mount_rho = Vec(At(theta, Term::kRigTranslation));
  if (!mount_mixing_is_identity_) MixPose(model_.mount_mixing, &mount_omega, &mount_rho);
  const Rigid3<T> hmd_from_object =
      fo::PerturbLeft(fo::Compose(hmd_from_tracker, fo::Compose(tracker_from_virtual, virtual_from_object)), mount_omega, mount_rho);

  const T baseline = At(theta, Term::kBaseline)[0];
  auto camera_from_object_of = [&](int e) {
    Vec3<T> omega = Vec(At(theta, Term::kCameraRotation, e)), rho = Vec(At(theta, Term::kCameraTranslation, e));
    if (!extrinsic_mixing_is_identity_[e]) MixPose(model_.extrinsic_mixing[e], &omega, &rho);
    rho += baseline_step_[e].cast<T>() * baseline;
    return fo::Compose(fo::PerturbLeft(camera_from_hmd_[e], omega, rho), hmd_from_object);
  };
  // Built in place: a default Rigid3 would first be written as the identity.
  const std::array<Rigid3<T>, kNumEyes> camera_from_object = {camera_from_object_of(0), camera_from_object_of(1)};

  // The renderer's lens parameters, and the eyes: each at its design eyepoint moved by its own
  // eyepoint error, the common offset of both (how the HMD sits) and half the IPD error. A display
  // whose virtual image is at distance D shows pixel q at E⁰ + D·d(q); seen from E = E⁰ + Δ the
  // ray's direction is D·d(q) − Δ ∝ d(q) − Δ/D.
  std::array<std::array<T, kMaxLensParams>, kNumEyes> lens;
  std::array<Vec3<T>, kNumEyes> towards_eye;
  std::array<T, kNumEyes> screen_scale;
  const T ipd_error = At(theta, Term::kIpd)[0];
  const Vec3<T> eye_offset = Vec(At(theta, Term::kEyeOffset));
  const T inverse_image_distance = T(model_.geometry.display.inverse_image_distance);
  for (int e = 0; e < kNumEyes; ++e) {
    const T* ci = At(theta, Term::kLens, e);
    const std::vector<double>& nominal = model_.renderer[e].params;
    const int n = static_cast<int>(nominal.size());
    for (int i = 0; i < n; ++i) {
      T delta = ci[i];
      if (!mixing_is_identity_[e]) {
        delta = T(0);
        for (int j = 0; j < n; ++j) delta += model_.intrinsic_mixing[e](i, j) * ci[j];
      }
      lens[e][i] = T(nominal[i]) + delta;
    }
    const T side = T(e == 0 ? -0.5 : 0.5);
    const Vec3<T> displacement = Vec(At(theta, Term::kEyepoint, e)) + eye_offset + Vec3<T>(side * ipd_error, T(0), T(0));
    out->eye[e] = design_eyepoint_[e].cast<T>() + displacement;
    towards_eye[e] = inverse_image_distance * displacement;
    screen_scale[e] = T(1) + At(theta, Term::kMagnification, e)[0];
  }

  // What the eyes see now was captured display_latency ago: the physical point, in the head frame
  // at display time, is hmd(t)_from_hmd(t − τ) · p = δ⁻¹ · p with δ = (Exp(ω τ), v τ).
  const T display_latency = At(theta, Term::kDisplayLatency)[0];
  const Rigid3<T> motion{fo::Exp(Vec3<T>(w.cast<T>() * display_latency)), Vec3<T>(v.cast<T>() * display_latency)};
  const Rigid3<T> now_from_captured = fo::Inverse(motion);

  // Point by point in three passes (the truth, each eye's paths, the seen points) rather than one:
  // the iterations of a pass are independent, short enough for the processor to overlap them, and
  // the numbers are the same.
  const size_t num_points = point_in_object_.size();
  for (size_t k = 0; k < num_points; ++k) {
    PointSample<T>& s = out->points[k];
    s.undefined = Undefined::kNone;
    s.truth = fo::Apply(now_from_captured, Vec3<T>(point_in_hmd_[k].cast<T>()));
  }
  for (size_t k = 0; k < num_points; ++k) {
    PointSample<T>& s = out->points[k];
    for (int e = 0; e < kNumEyes; ++e) {
      const DisplayConstants& c = display_[e];
      const Vec3<T> x = fo::Apply(camera_from_object[e], Vec3<T>(point_in_object_[k].cast<T>()));
      Undefined why = Undefined::kNone;
      Vec2<T> q(T(0), T(0));  // ProjectWith writes it (z > 0 here); set for the compiler
      if (!(x(2) > T(0))) {
        why = Undefined::kBehindCamera;
      } else if (!(x(0) * x(0) + x(1) * x(1) <= T(model_.renderer_valid_radius2[e]) * (x(2) * x(2)))) {
        why = Undefined::kOutsideLensDomain;
      } else {
        ProjectWith(model_.renderer[e].model, lens[e].data(), x.data(), q.data());
        if (!(q(0) >= T(c.min_u) && q(0) <= T(c.max_u) && q(1) >= T(c.min_v) && q(1) <= T(c.max_v))) {
          why = Undefined::kOutsideImage;
        }
      }
      if (why != Undefined::kNone) {
        s.undefined = why;
        s.undefined_eye = e;
        break;
      }
      s.pixel_error[e] = q - real_pixel_[e][k].cast<T>();
      s.virtual_depth[e] = x(2);
      const T* shift = At(theta, Term::kScreenShift, e);
      const T& lens_k1 = At(theta, Term::kLensK1, e)[0];
      s.overlay_ray[e] =
          DisplayedDirection(e, Vec2<T>(q(0) - T(c.cx), q(1) - T(c.cy)), shift, screen_scale[e], lens_k1) - towards_eye[e];
      s.seen_ray[e] = DisplayedDirection(e, Vec2<T>(real_centred_[e][k].cast<T>()), shift, screen_scale[e], lens_k1) -
                      towards_eye[e];
    }
  }
  for (size_t k = 0; k < num_points; ++k) {
    PointSample<T>& s = out->points[k];
    if (!s.valid()) continue;
    if (!TriangulateMidpoint(out->eye[0], s.overlay_ray[0], out->eye[1], s.overlay_ray[1], &s.overlay) ||
        !TriangulateMidpoint(out->eye[0], s.seen_ray[0], out->eye[1], s.seen_ray[1], &s.seen)) {
      s.undefined = Undefined::kParallelRays;
    }
  }
}

template <typename T>
bool ChainEvaluator::operator()(const T* theta, T* y) const {
  ChainSample<T> sample(num_points());
  Evaluate(theta, &sample);
  for (size_t k = 0; k < sample.points.size(); ++k) {
    const PointSample<T>& s = sample.points[k];
    if (!s.valid()) return false;
    T* out = y + kVectorOutputsPerPoint * k;
    for (int e = 0; e < kNumEyes; ++e) {
      for (int i = 0; i < 2; ++i) out[VectorOffset(VectorOutput::kPixelError, e) + i] = s.pixel_error[e](i);
    }
    const Vec3<T> misregistration = s.overlay - s.seen;
    const Vec3<T> misperception = s.seen - s.truth - systematic_[k].offset.cast<T>();
    constexpr int kMisregistration = VectorOffset(VectorOutput::kMisregistration);
    constexpr int kMisperception = VectorOffset(VectorOutput::kMisperception);
    for (int i = 0; i < 3; ++i) {
      out[kMisregistration + i] = misregistration(i);
      out[kMisperception + i] = misperception(i);
    }
  }
  return true;
}

}  // namespace vstcal
