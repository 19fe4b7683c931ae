#include "vstcal/sensitivity/rise_check.h"

#include <cmath>

#include "vstcal/core/error.h"

namespace vstcal {

RiseJudgement JudgeRise(double accepted, double accepted_standard_error, double fresh, double fresh_standard_error,
                        double allowed, double z) {
  VSTCAL_CHECK(accepted_standard_error >= 0 && fresh_standard_error >= 0, "standard errors are non-negative");
  VSTCAL_CHECK(z > 0 && std::isfinite(z), "z is positive");
  VSTCAL_CHECK(std::isfinite(accepted) && std::isfinite(fresh) && std::isfinite(allowed), "finite values");
  RiseJudgement j;
  j.rise = fresh - accepted;
  j.allowed = allowed;
  j.noise = std::hypot(accepted_standard_error, fresh_standard_error);
  const double excess = j.rise - allowed;
  if (!(excess > 0)) {
    j.verdict = CheckVerdict::kPass;
  } else if (excess <= z * j.noise) {
    j.verdict = CheckVerdict::kWithinNoise;
  } else {
    j.verdict = CheckVerdict::kFail;
  }
  return j;
}

}  // namespace vstcal
