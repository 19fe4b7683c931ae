// Point-based rigid registration: the b_from_a minimising Σ_k |b_from_a · a_k − b_k|² for paired
// points (the fiducial registration of seed 001 §4.7's virtual-object alignment).
//
// Two forms of the same least-squares problem:
//  - RegisterPointsHorn: Horn's closed form (J. Opt. Soc. Am. A 4(4), 1987): centre both sets;
//    the rotation is the unit quaternion of the largest eigenvalue of the 4×4 symmetric matrix N
//    built from the cross-covariance M = Σ ã_k b̃_kᵀ; t = b̄ − R ā. Double only.
//  - RefineRegistration: Gauss–Newton on a left rotation perturbation from a start rotation,
//    templated on the scalar so ceres::Jet differentiates it. Its fixed point is the exact
//    stationarity condition Σ (R ã_k) × b̃_k = 0, so it converges to Horn's answer (tested to
//    1e-12); each step costs O(N) because Σ [Rã]×ᵀ[Rã]× = R C Rᵀ with C fixed by the a-set.
// docs/math/vst-chain.md#fiducials derives both.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "vstcal/core/simd_double.h"
#include "vstcal/geometry/fixed_order.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

// nullopt for fewer than 3 points, different counts, or a collinear a-set (rotation undefined).
std::optional<Rigid3d> RegisterPointsHorn(std::span<const Eigen::Vector3d> points_in_a,
                                          std::span<const Eigen::Vector3d> points_in_b);

// The a-side constants of a registration with a fixed a-set (fiducials in the object frame).
struct RegistrationFrame {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> centred;                         // ã_k = a_k − ā
  Eigen::Matrix3d inverse_inertia = Eigen::Matrix3d::Identity();  // C⁻¹, C = Σ (|ã|² I − ã ãᵀ)

  // nullopt for fewer than 3 points or a collinear set (C singular).
  static std::optional<RegistrationFrame> For(std::span<const Eigen::Vector3d> points_in_a);
};

// Gauss–Newton iterations (at most `max_iterations`, stopping when the step is below 1e-15 rad)
// from `start_rotation`; points_in_b has frame.centred.size() entries.
// Every operation in a fixed order (fixed_order.h): double and SimdDouble give the same bits.
template <typename T>
Rigid3<T> RefineRegistration(const RegistrationFrame& frame, const Mat3<T>& start_rotation, const Vec3<T>* points_in_b,
                             int max_iterations = 8) {
  namespace fo = fixed_order;
  const size_t n = frame.centred.size();
  Vec3<T> centroid_b = Vec3<T>::Zero();
  for (size_t k = 0; k < n; ++k) centroid_b = centroid_b + points_in_b[k];
  centroid_b = centroid_b / T(static_cast<double>(n));
  Mat3<T> R = start_rotation;
  // Samples evaluated together (SimdDouble) converge after different numbers of steps: each lane
  // keeps its rotation from the step that converged it, as the double code stops there.
  auto done = T(1) < T(0);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    // φ = R C⁻¹ Σ ã_k × (Rᵀ b̃_k): the Gauss–Newton step for R' = Exp(φ) R.
    const Mat3<T> Rt = R.transpose();
    Vec3<T> gradient = Vec3<T>::Zero();
    for (size_t k = 0; k < n; ++k) {
      const Vec3<T> a = frame.centred[k].template cast<T>();
      gradient = gradient + fo::Cross(a, fo::Times(Rt, Vec3<T>(points_in_b[k] - centroid_b)));
    }
    const Vec3<T> step = fo::Times(R, fo::Times(frame.inverse_inertia, gradient));
    const Mat3<T> next = fo::Times(fo::Exp(step), R);
    for (int i = 0; i < 9; ++i) R(i) = Select(done, R(i), next(i));
    using std::abs;
    done = done || abs(step(0)) + abs(step(1)) + abs(step(2)) < T(1e-15);
    if (AllLanes(done)) break;
  }
  return Rigid3<T>{R, centroid_b - fo::Times(R, Vec3<T>(frame.centroid.template cast<T>()))};
}

}  // namespace vstcal
