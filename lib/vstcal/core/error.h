// Errors the library throws, and the exit code each maps to (docs/conventions.md#exit-codes).
//
// Three channels for failure (STYLE.md):
//  - broken assumptions (a bug) throw InternalError from VSTCAL_CHECK; the library never aborts;
//  - bad input (a file, a field, a flag) throws InputError naming what and how to fix it;
//  - expected geometric failures come back as a status in a result struct; a tool may turn them
//    into DegenerateError.
#pragma once

#include <stdexcept>
#include <string>

namespace vstcal {

enum class ExitCode : int {
  kOk = 0,
  kInternal = 1,    // a bug in vstcal
  kBadInput = 2,    // bad usage or bad input: the message names file, field and fix
  kDegenerate = 3,  // degenerate data (coplanar points for DLT, ...): the message says why
  // Not an error but a result: a check the user asked for failed (calib-compare --max-px, err-sim
  // check; core/check.h). The tool printed every verdict and wrote its files.
  kCheckFailed = 4,
};

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ExitCode code() const { return code_; }

 private:
  ExitCode code_;
};

class InternalError : public Error {
 public:
  explicit InternalError(const std::string& message) : Error(ExitCode::kInternal, message) {}
};

class InputError : public Error {
 public:
  explicit InputError(const std::string& message) : Error(ExitCode::kBadInput, message) {}
};

class DegenerateError : public Error {
 public:
  explicit DegenerateError(const std::string& message) : Error(ExitCode::kDegenerate, message) {}
};

// A number as messages quote it: six significant digits ("%.6g": 61.3, 1e+06, -0.00125).
std::string MessageNumber(double v);

}  // namespace vstcal

// Checks an internal invariant; on failure throws InternalError with the location.
#define VSTCAL_CHECK(condition, message)                                                     \
  do {                                                                                       \
    if (!(condition)) {                                                                      \
      throw ::vstcal::InternalError(std::string(__FILE__) + ":" + std::to_string(__LINE__) + \
                                    ": check failed: " #condition ": " + (message));         \
    }                                                                                        \
  } while (false)
