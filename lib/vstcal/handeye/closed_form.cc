#include "vstcal/handeye/closed_form.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/geometry/rotation_average.h"

namespace vstcal {
namespace {

struct Motion {
  Rigid3d A;  // hmd_j_from_hmd_i
  Rigid3d B;  // camera_j_from_camera_i
};

std::vector<Motion> Motions(std::span<const HandEyeSample> s) {
  const size_t n = s.size();
  std::vector<std::pair<size_t, size_t>> pairs;
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 1; k <= 5 && i + k < n; ++k) pairs.emplace_back(i, i + k);
    if (n / 2 > 5 && i + n / 2 < n) pairs.emplace_back(i, i + n / 2);
  }
  std::vector<Motion> out;
  out.reserve(pairs.size());
  for (const auto& [i, j] : pairs) {
    out.push_back({s[j].tracker_from_hmd.inverse() * s[i].tracker_from_hmd, s[j].camera_from_board * s[i].camera_from_board.inverse()});
  }
  return out;
}

}  // namespace

HandEyeStart SolveHandEyeClosedForm(std::span<const HandEyeSample> samples) {
  if (samples.size() < kMinHandEyeSamples) {
    throw DegenerateError(std::to_string(samples.size()) + " samples: hand-eye calibration needs at least " +
                          std::to_string(kMinHandEyeSamples) + " poses, turned about two different axes");
  }
  const std::vector<Motion> motions = Motions(samples);
  HandEyeStart out;
  out.pairs = motions.size();

  // Rotation: α = log R_A = R_X β, β = log R_B, for every pair; Procrustes on Σ α βᵀ.
  Eigen::Matrix3d correlation = Eigen::Matrix3d::Zero(), axes = Eigen::Matrix3d::Zero();
  for (const Motion& m : motions) {
    const Eigen::Vector3d alpha = RotvecFromRotation(m.A.R), beta = RotvecFromRotation(m.B.R);
    correlation += alpha * beta.transpose();
    // Axes weighted by their angle: a turn of 0.1° says little about its axis.
    if (alpha.norm() > 0) axes += alpha * alpha.transpose() / alpha.norm();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> spread(axes);
  const Eigen::Vector3d s = spread.singularValues();
  out.second_axis_spread = s(0) > 0 ? s(1) / s(0) : 0.0;
  if (!(out.second_axis_spread >= kMinHandEyeAxisSpread)) {
    throw DegenerateError("the headset turned about one axis only (second axis spread " + std::to_string(out.second_axis_spread) +
                          " < " + std::to_string(kMinHandEyeAxisSpread) +
                          "): the camera's offset along that axis cannot be told; tilt or roll it as well as turning it");
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(correlation, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  out.hmd_from_camera.R = svd.matrixU() * D * svd.matrixV().transpose();

  // Translation: R_A t_X + t_A = R_X t_B + t_X  ⇒  (R_A − I) t_X = R_X t_B − t_A, stacked.
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (const Motion& m : motions) {
    const Eigen::Matrix3d C = m.A.R - Eigen::Matrix3d::Identity();
    normal += C.transpose() * C;
    rhs += C.transpose() * (out.hmd_from_camera.R * m.B.t - m.A.t);
  }
  out.hmd_from_camera.t = normal.ldlt().solve(rhs);

  // Z: every sample's tracker_from_board, averaged.
  std::vector<Eigen::Matrix3d> rotations;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  for (const HandEyeSample& sample : samples) {
    const Rigid3d z = sample.tracker_from_hmd * out.hmd_from_camera * sample.camera_from_board;
    rotations.push_back(z.R);
    translation += z.t;
  }
  out.tracker_from_board.R = ChordalMeanRotation(rotations);
  out.tracker_from_board.t = translation / static_cast<double>(samples.size());
  return out;
}

}  // namespace vstcal
