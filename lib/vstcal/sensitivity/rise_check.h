// Has a Monte Carlo estimate risen by more than allowed, beyond what the sampling noise of the two
// estimates explains? (err-sim check, docs/math/sensitivity.md#rise-check.) Two independent runs
// estimate one quantity with standard errors se_a (accepted) and se_n (new); their difference has
// standard error √(se_a² + se_n²). With rise = new − accepted and excess = rise − allowed:
//   pass          rise ≤ allowed
//   within noise  0 < excess ≤ z·√(se_a² + se_n²)
//   fail          excess > z·√(se_a² + se_n²)
// so a metric whose true value has not risen beyond the allowance fails with probability at most
// 1 − Φ(z) (0.13 % at z = 3), whatever the sample sizes.
#pragma once

#include "vstcal/core/check.h"

namespace vstcal {

// How much a metric may rise: an amount in its unit, or a fraction of the accepted value.
struct RiseAllowance {
  double amount = 0.1;
  bool relative = true;  // amount × accepted
  double Of(double accepted) const { return relative ? amount * accepted : amount; }
};

struct RiseJudgement {
  double rise = 0;     // new − accepted
  double allowed = 0;  // RiseAllowance::Of(accepted)
  double noise = 0;    // √(se_a² + se_n²)
  CheckVerdict verdict = CheckVerdict::kPass;
};

// Standard errors are ≥ 0 and z > 0 (InternalError otherwise: callers validate their inputs).
RiseJudgement JudgeRise(double accepted, double accepted_standard_error, double fresh, double fresh_standard_error,
                        double allowed, double z);

}  // namespace vstcal
