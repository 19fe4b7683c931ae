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
import tempfile
import timeit

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]


def benchmark_scenes(bench, sizes):
    """{n: (points, pixels)}: the scenes bench_dlt times (tests/support/scenes.cc RandomVolumeScene, seed 42,
    0.2 px noise), written by `bench_dlt --write-scenes` at %.17g so that the doubles are the same. The
    DLT's refusal certificate is data-dependent: another draw of the same size may cost more or less."""
    with tempfile.TemporaryDirectory() as folder:
        subprocess.run([str(bench / "bench_dlt"), "--write-scenes", folder], check=True)
        scenes = {}
        for n in sizes:
            table = np.loadtxt(pathlib.Path(folder) / f"dlt_scene_{n}.txt", ndmin=2)
            if table.shape != (n, 5):
                raise SystemExit(f"bench.py: bench_dlt wrote {table.shape[0]} points for the {n}-point scene")
            scenes[n] = (np.ascontiguousarray(table[:, :3]), np.ascontiguousarray(table[:, 3:]))
        return scenes


def best_seconds(call, repeats, target_seconds=0.2, **names):
    """The fastest time of one call, timeit-style: calls per repeat chosen to last ~target_seconds. The
    call is a statement over `names` (not a lambda, whose own call would be counted as the binding's)."""
    timer = timeit.Timer(call, globals=names)
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
    scenes = benchmark_scenes(bench, (60, 600, 6000))
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
                keep(("py", n), best_seconds("solve(o)", 3, solve=vstcal.solve_dlt, o=observations[n]))
                keep(("arrays", n), best_seconds("solve(x, u)", 3, solve=vstcal.solve_dlt, x=scenes[n][0], u=scenes[n][1]))
            keep(("floor", 0), best_seconds("length()", 3, length=observations[60].__len__))
        if args.only != "dlt":
            for name, seconds in google_benchmark(bench / "bench_errsim", "BM_ErrSimRun", 3).items():
                keep(("cpp", name), seconds)
            keep(("py", "errsim"), best_seconds("run(chain, samples=16384, seed=1, threads=1)", 3, 1.0, run=vstcal.err_sim, chain=chain))

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
    if args.only != "errsim":
        print(f"the floor of any call into the module (Observations.__len__, no work): {best[('floor', 0)] * 1e6:.3f} µs")


if __name__ == "__main__":
    sys.exit(main())
