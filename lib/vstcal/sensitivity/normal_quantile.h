// The standard normal quantile Φ⁻¹(p), to full double precision: Wichura's algorithm AS 241
// (PPND16), Applied Statistics 37 (1988) 477–484. Deterministic (only +, ×, ÷, log, sqrt, which
// IEEE 754 and glibc make reproducible), so Monte Carlo and quasi-Monte Carlo draws through it
// are bit-identical on every x86-64 machine — unlike std::normal_distribution.
#pragma once

namespace vstcal {

// Φ⁻¹(p) for 0 < p < 1, relative error about 1e-16 (docs/math/sensitivity.md#normal-quantile).
// Symmetric: NormalQuantile(1 − p) == −NormalQuantile(p) whenever 1 − p is exact.
// Throws InputError for p outside (0, 1) (including NaN): ±∞ would poison every sum downstream.
double NormalQuantile(double p);

}  // namespace vstcal
