"""Overhead of the Python call over the C++ call for the same analysis (issue 17 target: under
5 % for runs above 10 ms).

    python3 tests/benchmarks/python/overhead.py BUILD_DIR

BUILD_DIR is a Release tree configured with -DGEARDYN_BUILD_BENCHMARKS=ON -DGEARDYN_BUILD_PYTHON=ON
(targets analysis_runs_benchmark and geardyn_python; docs/benchmarks.md "Python package").
The C++ side is tests/benchmarks/micro/analysis_runs_benchmark (Google Benchmark, the commands'
analyses on a scene loaded once); the Python side calls geardyn.modes / geardyn.hb on a Scene
whose C++ handle is cached (the median of 3 rounds of N calls' mean, as Google Benchmark's
median of 3 repetitions), so both sides time the same work plus, on the
Python side, the argument conversion, the report's JSON → dict, the numpy copies and the result
objects.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path


def mean_of(f, repeats: int) -> float:
    """The mean time of `repeats` calls: a Google Benchmark repetition's statistic."""
    start = time.perf_counter()
    for _ in range(repeats):
        f()
    return (time.perf_counter() - start) / repeats


def main(build: Path) -> None:
    sys.path.insert(0, str(build / "python"))
    import geardyn

    bench = build / "tests" / "benchmarks" / "analysis_runs_benchmark"
    done = subprocess.run([str(bench), "--benchmark_format=json",
                           "--benchmark_min_time=1", "--benchmark_repetitions=3",
                           "--benchmark_report_aggregates_only=true"],
                          capture_output=True, text=True, check=True)
    # Google Benchmark reports mean/median/stddev of the repetitions: the median [ms → s].
    cpp = {b["run_name"]: b["real_time"] / 1e3 for b in json.loads(done.stdout)["benchmarks"]
           if b.get("aggregate_name") == "median"}

    pair = geardyn.Scene.builtin("helical-pair")
    shafts = geardyn.Scene.builtin("geared-shafts")
    rig = geardyn.Scene.builtin("kahraman-blankenship-rig")
    slices = rig.with_overrides(["mesh.pinion-wheel.model=slices",
                                 "mesh.pinion-wheel.center_distance=0.1502",
                                 "mesh.pinion-wheel.damping_ratio=0.05"])
    for s in (pair, shafts, rig, slices):
        s.handle()
    cases = [
        ("BM_ModesHelicalPair", lambda: geardyn.modes(pair), 400),
        ("BM_ModesGearedShaftsAllShapesDamped",
         lambda: geardyn.modes(shafts, num_modes=1000, shapes=True, damped=True), 40),
        ("BM_HbLinearRig40", lambda: geardyn.hb(rig, mesh_frequency="700.0:3500.0:40"), 12),
        ("BM_HbNonlinearRig", lambda: geardyn.hb(slices, mesh_frequency="1500.0:4000.0:120"), 4),
    ]
    print("| case | C++ benchmark [ms] | Python call [ms] | difference | of which the Python "
          "layer (in-call split) |")
    print("|---|---|---|---|---|")
    for name, call, repeats in cases:
        call()  # warm-up (first-call imports)
        # The median of 3 rounds of N calls, as the C++ side's median of 3 repetitions.
        rounds = sorted(mean_of(call, repeats) for _ in range(3))
        py = rounds[1]
        c = cpp[name]
        # The same call split in itself: total wall time minus the C++ library's share
        # (cpp_wall_time_s), median of N calls; free of the run-to-run noise of two processes.
        layer = []
        for _ in range(repeats):
            start = time.perf_counter()
            r = call()
            total = time.perf_counter() - start
            layer.append((total - r.cpp_wall_time_s, total))
        layer.sort()
        extra, total = layer[len(layer) // 2]
        print(f"| {name} | {c * 1e3:.3f} | {py * 1e3:.3f} | {100 * (py - c) / c:+.1f} % | "
              f"{extra * 1e6:.0f} µs = {100 * extra / total:.2f} % |")


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "build/bench"))
