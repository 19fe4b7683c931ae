// The message of the InputError a call throws, for tests that check readers' one-line errors.
#pragma once

#include <string>

#include "vstcal/core/error.h"

namespace vstcal::testing {

// The message of the InputError `f` throws ("" if it throws none).
template <typename F>
std::string ErrorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace vstcal::testing
