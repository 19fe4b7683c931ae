// Variance-based sensitivity: first-order and total Sobol indices per GROUP of parameters, for
// every output (docs/math/sensitivity.md#sobol).
//
// Scheme (Saltelli et al. 2010, "Variance based sensitivity analysis of model output", CPC 181):
// two independent N × n sample matrices A and B (the first and last n coordinates of N points of
// the 2n-dimensional unit cube, unit_points.h), and for each group g the matrix A_B^(g): A with
// every column of g taken from B. Cost: N·(G + 2) model evaluations (groups whose parameters are all
// constant are exactly 0 and cost nothing). With f centred by the pooled mean f̂₀ of f(A), f(B):
//
//   V     = pooled variance of f(A) and f(B)                       (2N values, divisor 2N)
//   V_g   = 1/N Σ_j f(B)_j (f(A_B^g)_j − f(A)_j)        first order, Saltelli 2010 Table 2 (b)
//   VT_g  = 1/(2N) Σ_j (f(A)_j − f(A_B^g)_j)²            total,       Jansen 1999 (Table 2 (f))
//   S_g = V_g / V,   ST_g = VT_g / V
//
// Intervals: bootstrap over the N rows (bootstrap.h), R replicates. For Sobol (QMC) points the rows
// are not independent and the bootstrap overstates the error: a conservative interval.
//
// Deterministic: every evaluation lands in its own slot, sums run in sample order after the
// parallel part, replicates are keyed by index — the same bits for any thread count.
// Memory: 8·N·(G + 2)·m bytes for the stored evaluations.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vstcal/sensitivity/bootstrap.h"
#include "vstcal/sensitivity/model.h"
#include "vstcal/sensitivity/parameter_space.h"
#include "vstcal/sensitivity/unit_points.h"

namespace vstcal {

struct SobolOptions {
  uint64_t samples = 8192;  // N; with kSobol a power of two keeps the points a net
  SamplingOptions sampling;
  size_t bootstrap_resamples = 500;  // R; 0 → no intervals (standard errors 0)
  double confidence = 0.95;          // of the percentile intervals, in (0, 1)
  uint64_t bootstrap_seed = 0;
  unsigned threads = 0;  // 0 → all cores; the result does not depend on it
};

struct GroupSensitivity {
  Estimate first_order;  // S_g
  Estimate total;        // ST_g
};

struct OutputSensitivity {
  std::string name;
  double mean = 0;
  double variance = 0;  // V; 0 → the output is constant and every index is reported as 0
  std::vector<GroupSensitivity> groups;  // in ParameterSpace::group_names() order
};

enum class SobolStatus {
  kOk,
  kModelUndefined,  // the model returned false (or non-finite) for some sample: no indices
};

struct SobolResult {
  SobolStatus status = SobolStatus::kOk;
  std::string message;  // why, when status is not kOk
  std::vector<std::string> group_names;
  std::vector<OutputSensitivity> outputs;
  uint64_t evaluations = 0;
  uint64_t undefined_evaluations = 0;
};

// InputError for N < 2, a confidence outside (0, 1), or a model that does not fit the space.
SobolResult EstimateSobolIndices(const ParameterSpace& space, const Model& model, const SobolOptions& options);

}  // namespace vstcal
