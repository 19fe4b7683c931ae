// The outcome of a threshold check a user's CI runs (calib-compare's pixel and σ bounds, err-sim
// check's rise of each metric): one verdict per check, with the numbers in words. A failed check is
// no error: the tool prints every verdict and exits with ExitCode::kCheckFailed (core/error.h,
// docs/conventions.md#exit-codes).
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace vstcal {

enum class CheckVerdict {
  kPass,
  // Above the allowed value, but by less than the Monte Carlo noise of the two numbers explains:
  // not a failure (err-sim check, docs/tools/err-sim.md#check).
  kWithinNoise,
  kFail,
};

// "pass", "within noise", "fail".
std::string_view CheckVerdictName(CheckVerdict verdict);

struct CheckResult {
  std::string name;     // what was checked ("grid", "Middle 1.misregistration.linear")
  CheckVerdict verdict = CheckVerdict::kPass;
  std::string message;  // the numbers behind the verdict, one line
};

// Whether any result is a failure.
bool AnyCheckFailed(std::span<const CheckResult> results);

}  // namespace vstcal
