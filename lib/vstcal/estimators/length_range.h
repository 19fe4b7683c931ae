// Lengths the solvers compute with. A pose's information holds 1/length² and length² terms, and
// Zhang's closed form products of board lengths: lengths far from 1 (a board in units of 1e200 or
// 1e-300) underflow or overflow them, so that many points spread over a plane or a volume look
// "degenerate" or "on one line". This tells that case apart, to say what is really wrong.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "vstcal/scene/correspondences.h"

namespace vstcal {

// Why the points of view `view` (every view when nullopt) are beyond the lengths the solvers
// compute with ("the points spread over 6.32e+202 mm, beyond the lengths (1e-50 to 1e50) the
// solver computes with"); nullopt when they are within them, or are 6 or fewer, or lie on one line
// (then the points themselves are the problem). Computed without squares out of range.
std::optional<std::string> LengthsOutOfRange(const Correspondences& c, std::optional<size_t> view);

}  // namespace vstcal
