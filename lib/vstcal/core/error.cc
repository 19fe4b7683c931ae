#include "vstcal/core/error.h"

#include <cstdio>

namespace vstcal {

std::string MessageNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace vstcal
