// The closed-form start of hand-eye calibration (issue 22; docs/math/handeye.md): a camera rigidly
// mounted on a tracked body (the HMD) sees a fixed board while the tracker reports the body's pose.
// For each sample i, taken at one instant: tracker_from_hmd[i] (the tracker's report) and
// camera_from_board[i] (the board's pose in the image). The unknowns are hmd_from_camera (X) and
// tracker_from_board (Z), tied by
//   tracker_from_board = tracker_from_hmd[i] · hmd_from_camera · camera_from_board[i]   (A_i X = Z B_i).
// Pairs of samples eliminate Z: A_ij X = X B_ij with A_ij = hmd_j_from_hmd_i and
// B_ij = camera_j_from_camera_i (Park & Martin 1994), solved here in closed form; Z then follows.
#pragma once

#include <span>

#include "vstcal/geometry/rigid3.h"

namespace vstcal {

struct HandEyeSample {
  Rigid3d tracker_from_hmd;
  Rigid3d camera_from_board;
};

struct HandEyeStart {
  Rigid3d hmd_from_camera;
  Rigid3d tracker_from_board;
  size_t pairs = 0;                  // relative motions used
  double second_axis_spread = 0;     // how far the relative rotations' axes leave one axis (0 … 1, see below)
};

// Fewer than this many samples are refused: two relative motions about different axes need three.
inline constexpr size_t kMinHandEyeSamples = 3;
// The relative rotations must turn about at least two axes: the second singular value of their
// angle-weighted unit axes, over the first, below this (≈ 6° of spread) leaves X's translation
// along the common axis undetermined.
inline constexpr double kMinHandEyeAxisSpread = 0.1;

// X's rotation by orthogonal Procrustes of the pairs' rotation vectors (log R_A = R_X log R_B), its
// translation by linear least squares ((R_A − I) t_X = R_X t_B − t_A), over the pairs (i, j) with
// j − i ∈ {1, …, 5} and j − i = ⌊n/2⌋ (linear in n; near and far motions both). Z is then the chordal
// mean rotation and mean translation of tracker_from_hmd[i] · X · camera_from_board[i]. Exact on
// noise-free samples. Throws DegenerateError for fewer than kMinHandEyeSamples samples, or
// rotations about one axis only (the message says which motion to add).
HandEyeStart SolveHandEyeClosedForm(std::span<const HandEyeSample> samples);

}  // namespace vstcal
