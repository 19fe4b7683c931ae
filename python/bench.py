#!/usr/bin/python3
"""What the Python binding adds over the C++ call (docs/performance.md#python): the DLT benchmark
(tests/bench/bench_dlt.cc: SolveDlt + DecomposeProjection at 60, 600 and 6,000 points) and the err-sim
one (tests/bench/bench_errsim.cc BM_ErrSimRun: app::RunErrSim on seed 001, 16,384 samples, one thread),
each timed with timeit from Python beside Google Benchmark's figure for the C++ call, run back to back.

  PYTHONPATH=build/python /usr/bin/python3 python/bench.py [--build build] [--rounds 5]

Each figure is the fastest seen over alternating rounds of both sides (the least disturbed by other
processes on a shared machine).
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import timeit

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]


def volume_scene(vstcal, n, noise_px=0.2, seed=42):
    """tests/support/scenes.cc RandomVolumeScene's geometry: K, pose and volume (1200 × 900 × 2000 mm) the
    same, points drawn by NumPy (the DLT's cost does not depend on the draw)."""
    K = np.array([[1700, 0.8, 652.3], [0, 1695, 498.1], [0, 0, 1.0]])
    cam = vstcal.Camera.from_K(K, (1280, 1024))
    rotvec = np.array([0.05, -0.2, 0.03])
    theta = np.linalg.norm(rotvec)
    k = rotvec / theta
    Kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    R = np.eye(3) + np.sin(theta) * Kx + (1 - np.cos(theta)) * Kx @ Kx
    t = np.array([-120.0, 80.0, 2600.0])
    rng = np.random.default_rng(seed)
    points, pixels = [], []
    while len(points) < n:
        a = rng.uniform(size=3)
        p = np.array([(a[0] - 0.5) * 1200, (a[1] - 0.5) * 900, a[2] * 2000])
        px = cam.project(np.ascontiguousarray(R @ p + t))
        if not cam.in_image(px.reshape(1, 2))[0]:
            continue
        points.append(p)
        pixels.append(px + noise_px * rng.standard_normal(2))
    return np.ascontiguousarray(points), np.ascontiguousarray(pixels)


def best_seconds(function, repeats, target_seconds=0.2):
    """The fastest time of one call, timeit-style: calls per repeat chosen to last ~target_seconds."""
    timer = timeit.Timer(function)
    number, elapsed = timer.autorange()
    number = max(1, int(number * target_seconds / max(elapsed, 1e-9)))
    return min(timer.repeat(repeat=repeats, number=number)) / number


def google_benchmark(binary, pattern, repeats):
    """{name: fastest real time per iteration in seconds} of a Google Benchmark binary."""
    out = subprocess.run([str(binary), f"--benchmark_filter={pattern}", f"--benchmark_repetitions={repeats}",
                          "--benchmark_format=json"], check=True, capture_output=True, text=True).stdout
    best = {}
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
    for b in json.loads(out)["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        seconds = b["real_time"] * scale[b["time_unit"]]
        best[b["run_name"]] = min(best.get(b["run_name"], seconds), seconds)
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--rounds", type=int, default=5, help="C++ and Python measured alternately this many times")
    parser.add_argument("--only", choices=["dlt", "errsim"], help="one of the two benchmarks")
    args = parser.parse_args()
    import vstcal
    bench = pathlib.Path(args.build) / "tests" / "bench"
    chain = str(ROOT / "datasets" / "vst" / "seed001.json")
    scenes = {n: volume_scene(vstcal, n) for n in (60, 600, 6000)}
    observations = {n: vstcal.Observations(*scenes[n]) for n in scenes}
    best = {}

    def keep(key, seconds):
        best[key] = min(best.get(key, seconds), seconds)

    # Alternating rounds, the fastest of each kept: on a shared machine the two sides then see the
    # same quiet moments, rather than one of them a busy one.
    for _ in range(args.rounds):
        if args.only != "errsim":
            for name, seconds in google_benchmark(bench / "bench_dlt", "BM_DltNormalEquations", 3).items():
                keep(("cpp", name), seconds)
            for n in scenes:
                keep(("py", n), best_seconds(lambda: vstcal.solve_dlt(observations[n]), 3))
                keep(("arrays", n), best_seconds(lambda: vstcal.solve_dlt(*scenes[n]), 3))
        if args.only != "dlt":
            for name, seconds in google_benchmark(bench / "bench_errsim", "BM_ErrSimRun", 3).items():
                keep(("cpp", name), seconds)
            keep(("py", "errsim"), best_seconds(lambda: vstcal.err_sim(chain, samples=16384, seed=1, threads=1), 3, 1.0))

    rows = []
    if args.only != "errsim":
        rows += [(f"DLT, {n} points", best[("cpp", f"BM_DltNormalEquations/{n}")], best[("py", n)], best[("arrays", n)])
                 for n in scenes]
    if args.only != "dlt":
        rows.append(("err-sim run, seed 001, 16,384 samples", best[("cpp", "BM_ErrSimRun")], best[("py", "errsim")], None))
    print(f"{'benchmark':40s} {'C++ (Google Benchmark)':>24s} {'Python (timeit)':>16s} {'added':>8s}  NumPy arrays in")
    for name, c, p, arrays in rows:
        unit, scale = ("ms", 1e3) if c > 1e-3 else ("µs", 1e6)
        extra = f"{arrays * scale:.2f} {unit} ({100 * (arrays / c - 1):+.1f} %)" if arrays else ""
        print(f"{name:40s} {c * scale:>21.2f} {unit} {p * scale:>13.2f} {unit} {100 * (p / c - 1):>+7.1f} %  {extra}")


if __name__ == "__main__":
    sys.exit(main())
