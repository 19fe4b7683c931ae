// Direct linear transformation (seed 000 Eq. 7–8, seed 001 Eq. 9–11): the 3×4 projection matrix
// P from ≥ 6 non-coplanar 3-D ↔ 2-D correspondences, minimising ‖A m‖ subject to ‖m‖ = 1 on the
// Hartley-normalized system. Derivation, normalization and degeneracy test: docs/math/dlt.md.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/scene/correspondences.h"
#include "vstcal/core/error.h"
#include "vstcal/core/enum_names.h"

namespace vstcal {

struct DltOptions {
  enum class Solver {
    // Accumulates AᵀA from four 4×4 moment matrices in one pass (40 multiply-adds a point), then
    // finds its two smallest eigenpairs through a 4×4 secular equation. Default: same answer as
    // kFullSvd to ~1e-12 relative on non-degenerate data (tests/unit/dlt_test.cc), and about 40×
    // faster at 6,000 points (docs/performance.md).
    kNormalEquations,
    // Builds the 2N×12 matrix A and takes its SVD: the textbook reference.
    kFullSvd,
  };
  static constexpr EnumNames<Solver, 2> kSolverNames = {{{Solver::kNormalEquations, "normal-equations"}, {Solver::kFullSvd, "svd"}}};
  Solver solver = Solver::kNormalEquations;

  // Refuse when the normalized point cloud is thinner than this along its second (collinear) or
  // third (coplanar) principal axis, relative to the first: docs/math/dlt.md#degeneracy.
  double min_extent_ratio = 1e-2;
  // Refuse when σ₁₁/‖A‖_F of the normalized system is below this: the null space is not one-
  // dimensional (critical configuration): docs/math/dlt.md#degeneracy.
  double min_conditioning = 1e-3;
  // Compute σ₁₁ (and so `conditioning`) exactly even when the refusal test can be decided
  // without it; costs one 12×12 eigenvalue problem (≈ 6 µs). Tools set it for their reports.
  bool exact_diagnostics = false;
  // Warn (but solve) when the cloud is thinner than this: pixel noise is amplified into K.
  double warn_extent_ratio = 5e-2;
};

enum class DltStatus {
  kOk,
  kTooFewPoints,    // fewer than 6 correspondences
  kNonFinite,       // NaN or infinite coordinates, or a spread beyond double precision
  kCoincident,      // all points (or all pixels) at one place
  kCollinear,       // points on (or near) a line
  kCoplanar,        // points on (or near) a plane
  kIllConditioned,  // the normalized system has a multi-dimensional near-null space
  kPointsBehind,    // some points lie behind the camera the others define
  kMirrored,        // the world frame is left-handed relative to the image (det M < 0)
};

struct DltResult {
  DltStatus status = DltStatus::kOk;
  std::string message;  // when status != kOk: why, and what to use instead
  std::vector<std::string> warnings;  // solved, but the user should know (thin volume, ...)

  // Normalized as docs/conventions.md#projection-matrix (unit third row, positive depth).
  Matrix34d P = Matrix34d::Zero();

  // Diagnostics of the normalized 2N×12 system A (docs/math/dlt.md#degeneracy).
  double sigma_11 = 0;       // second-smallest singular value of A; NaN unless computed (see exact_diagnostics)
  double sigma_12 = 0;       // smallest singular value of A (≈ residual size; 0 for exact data)
  double frobenius = 0;      // ‖A‖_F = √(Σσᵢ²)
  double conditioning = 0;   // σ₁₁ / ‖A‖_F (NaN when σ₁₁ was not computed)
  std::array<double, 3> extents{};  // RMS extent of the normalized points along principal axes, descending
  size_t n_points = 0;
  size_t n_behind = 0;        // points with depth ≤ 0 under P
  size_t deepest_behind = 0;  // index of the deepest point behind the camera, when n_behind > 0
};

using Matrix12d = Eigen::Matrix<double, 12, 12>;

// First-order uncertainty of the DLT estimate (docs/math/dlt.md#covariance): pixel noise i.i.d.
// N(0, σ²) per coordinate, propagated through the smallest eigenvector of the normalized AᵀA
// (the algebraic estimator's own sensitivity, not the maximum-likelihood one's) and the
// denormalization into the file's gauge.
struct DltUncertainty {
  // σ̂ = √(Σ‖π(P X_i) − q_i‖² / dof), dof = 2N − 11 (P has 11 degrees of freedom).
  double sigma_px = 0;
  int dof = 0;
  // Cov(vec P), P row-major, in the gauge of docs/conventions.md#projection-matrix
  // (‖P(2, 0:3)‖ = 1, positive depth). Rank 11: the gauge's normal, ∂‖P(2, 0:3)‖/∂vec P, is its
  // null direction.
  Matrix12d P_covariance = Matrix12d::Zero();
};

// `P` is SolveDlt's (status kOk) for the same observations; needs ≥ 6 of them.
DltUncertainty EstimateDltUncertainty(std::span<const Observation> observations, const Matrix34d& P);

// Solves P from the observations (points in one world frame). Never throws on bad geometry: the
// status says what went wrong.
DltResult SolveDlt(std::span<const Observation> observations, const DltOptions& options = {});

// Exit code a tool returns for a status (2 for bad input, 3 for degenerate geometry).
ExitCode DltStatusExitCode(DltStatus status);

}  // namespace vstcal
