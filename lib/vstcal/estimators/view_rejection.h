// Outlier views and corners (docs/math/uncertainty.md#view-rejection): after a solve, a view whose
// residuals are inconsistent with the noise the other views show — a robust σ̂ from the median
// view — is rejected, and, once every view is consistent, single corners beyond a threshold; the
// caller re-solves and tests again until nothing is rejected. Each threshold is a χ² quantile at a
// stated false-alarm probability for the whole calibration (Bonferroni over views or corners).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vstcal/scene/correspondences.h"
#include "vstcal/scene/fit.h"

namespace vstcal {

struct ViewRejectionOptions {
  bool enabled = false;
  // Probability that a clean calibration (every view and corner consistent with one σ) loses any
  // view, resp. any corner, in one test.
  double view_false_alarm = 0.01;
  double corner_false_alarm = 0.01;
  int max_rounds = 10;  // solve → test → reject rounds; the last solve is kept, with a warning
};

// The fewest views a view test needs (its scale is a median) and the fewest a rejection may leave.
inline constexpr size_t kMinViewsToTest = 3;
inline constexpr size_t kMinPlanarViewsKept = 3;
inline constexpr size_t kMinVolumeViewsKept = 2;

struct Rejection {
  enum class Kind { kView, kCorner };
  Kind kind = Kind::kView;
  int round = 0;                // 1 for the first solve's test
  size_t view = 0;              // index in the input correspondences
  std::string view_name;
  std::optional<size_t> point;  // corners: index in the input view's observations
  double rms_px = 0;            // view: √(Σ w|r|² / n); corner: √w |r|
  double threshold_px = 0;      // the same statistic's threshold
  std::string because;
};

// One test of a solved calibration's residuals.
struct RejectionTest {
  double sigma_px = 0;                 // robust σ̂ per coordinate, from the median view
  std::vector<double> view_rms_px;     // per view, √(Σ w|r|² / n)
  std::vector<double> view_threshold_px;
  std::optional<size_t> worst_view;    // the view furthest beyond its threshold, if any is
  struct Corner {
    size_t view = 0, point = 0;
    double residual_px = 0, threshold_px = 0;
  };
  std::vector<Corner> corners;  // beyond their threshold (tested only when no view is)
};

// `fit` holds residuals for `c` (same views and points); `num_params` is the number of parameters
// the solve estimated (11 for the DLT, intrinsics + 6 per pose for a refinement), of which
// `pose_params_per_view` belong to each view alone (6 for planar views, 0 for a volume).
RejectionTest TestResiduals(const Correspondences& c, const Fit& fit, size_t num_params, size_t pose_params_per_view,
                            const ViewRejectionOptions& options);

}  // namespace vstcal
