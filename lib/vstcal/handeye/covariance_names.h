// The names of a hand-eye solution's covariance rows: part of handeye's model (the value types its
// files hold, cmake/DomainModels.cmake), so the hand-eye file's reader and writer need none of the
// solver.
#pragma once

#include <string>
#include <vector>

namespace vstcal {

// The names of HandEyeSolution::covariance's rows, in order: X's left-perturbation tangent (ω rad,
// ρ length unit; hmd frame), Z's (tracker frame), δ (s). handeye@1 writes them; err-sim reads them.
const std::vector<std::string>& HandEyeCovarianceNames();
// The two rows that follow them when the tracker's noise was estimated jointly.
const std::vector<std::string>& HandEyeNoiseCovarianceNames();

}  // namespace vstcal
