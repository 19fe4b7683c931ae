#include "vstcal/core/check.h"

#include <algorithm>

namespace vstcal {

std::string_view CheckVerdictName(CheckVerdict verdict) {
  switch (verdict) {
    case CheckVerdict::kPass:
      return "pass";
    case CheckVerdict::kWithinNoise:
      return "within noise";
    case CheckVerdict::kFail:
      return "fail";
  }
  return "fail";
}

bool AnyCheckFailed(std::span<const CheckResult> results) {
  return std::any_of(results.begin(), results.end(), [](const CheckResult& r) { return r.verdict == CheckVerdict::kFail; });
}

}  // namespace vstcal
