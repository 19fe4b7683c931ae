#!/usr/bin/python3
"""The time offset's estimate in one dimension (docs/math/handeye.md#delta-shape).

A headset moving at v (in report noise σ = 1 per report interval) is reported every interval with
N(0, 1) error; n views, each in its own stretch of the log and all at one place s0 of their report
interval (a camera locked to the tracker's clock), see its position with N(0, c) error. δ̂
minimises calib-handeye's cost in one dimension, Σ (z − interp(δ))² / (c + w(s(δ))) with
w(s) = (1 − s)² + s², over a fine grid (the global minimum). Prints δ̂'s spread (standard deviation
and 1.4826 MAD, in report intervals) over the first-order sandwich σ of
docs/math/handeye.md#delta-likelihood, δ̂'s kurtosis, and the σ from the cost's profile.

  handeye_delta_toy.py views v c s0 [seed = 1] [mode = poly] [recordings = 4000] [still directions = 0]

mode: `poly` (calib-handeye's cost), `line` (each view's two reports' line extended past them: no
kinks), `fixed` (w held at w(s0): the weight does not follow δ), `linefixed` (both).
still directions: error directions of each view along which the headset does not move (the solver
has six a view; the motion's is one), with the same report and view noise, weighed by the same w.
Not a test; needs NumPy (Debian's python3-numpy, which scripts/setup installs).
"""
import sys

import numpy as np


def main():
    n, v, c, s0 = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
    seed = int(sys.argv[5]) if len(sys.argv) > 5 else 1
    mode = sys.argv[6] if len(sys.argv) > 6 else "poly"
    runs = int(sys.argv[7]) if len(sys.argv) > 7 else 4000
    still = int(sys.argv[8]) if len(sys.argv) > 8 else 0  # error directions along which the headset does not move
    if mode not in ("poly", "line", "fixed", "linefixed") or not (0 <= s0 < 1) or n < 2 or v <= 0 or c <= 0:
        sys.exit("usage: handeye_delta_toy.py views>1 v>0 c>0 s0∈[0,1) [seed] [poly|line|fixed|linefixed] [recordings]")
    rng = np.random.default_rng(seed)
    step = 0.001
    grid = np.arange(-2.5, 2.5, step)
    # The sandwich at the truth (one dimension: Jₑ = 1, D = 1).
    w0 = (1 - s0) ** 2 + s0 ** 2
    k0 = c + w0
    beta = (2 * s0 - 1) / w0
    info = n * v * v / k0
    # N sums over every error direction (the still ones' noisy slopes score too), Ī the motion's alone.
    excess = n * (1 + still) * (1 / (w0 * k0) + beta ** 2 * w0 * c / k0 ** 2)
    sandwich = np.sqrt((1 + excess / info) / info)
    rise = 1 + excess / info  # the profile's threshold: ±sandwich on a quadratic cost
    reports = np.arange(-3, 5)  # each view's stretch of the log, around its interval [0, 1)
    estimates, profile = [], []
    for _ in range(runs):
        y = v * reports[None, :] + rng.normal(0, 1, (n, len(reports)))
        z = v * s0 + rng.normal(0, np.sqrt(c), n)
        tau = s0 + grid
        k = np.floor(tau).astype(int)
        if mode in ("line", "linefixed"):
            k = np.full_like(k, int(np.floor(s0)))
        s = tau - k
        interp = (1 - s) * y[:, k + 3] + s * y[:, k + 4]
        w = np.full_like(s, w0) if mode in ("fixed", "linefixed") else (1 - s) ** 2 + s ** 2
        cost = (((z[:, None] - interp) ** 2) / (c + w)).sum(0)
        for _ in range(still):  # the same interpolation of the reports' errors, no motion
            ye = rng.normal(0, 1, (n, len(reports)))
            ze = rng.normal(0, np.sqrt(c), n)
            cost += (((ze[:, None] - ((1 - s) * ye[:, k + 3] + s * ye[:, k + 4])) ** 2) / (c + w)).sum(0)
        m = int(np.argmin(cost))
        estimates.append(grid[m])
        above = np.nonzero(cost[m:] - cost[m] > rise)[0]
        below = np.nonzero(cost[:m][::-1] - cost[m] > rise)[0]
        profile.append(0.5 * step * (above[0] + below[0]) if len(above) and len(below) else np.nan)
    e = np.array(estimates)
    sd = e.std(ddof=1)
    mad = 1.4826 * np.median(np.abs(e - np.median(e)))
    kurtosis = ((e - e.mean()) ** 4).mean() / sd ** 4
    p = np.array(profile)
    rms_profile = np.sqrt(np.nanmean(p ** 2))
    print(f"{mode:9s} views {n} (+{still} still) v {v} c {c} s0 {s0}: first-order σ {sandwich:.4f}, spread {sd:.4f} ({sd / sandwich:.3f} of it), "
          f"robust spread {mad:.4f} ({mad / sandwich:.3f}), kurtosis {kurtosis:.2f}, mean {e.mean():+.4f}; "
          f"profile σ {rms_profile:.4f} (spread / it {sd / rms_profile:.3f}, {int(np.isnan(p).sum())} open)")


if __name__ == "__main__":
    main()
