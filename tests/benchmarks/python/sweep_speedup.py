"""Speed-up of a 200-variant sweep on 2 local workers over 1 (issue 17), with a process pool and
with a Dask LocalCluster of 2 worker processes.

    python3 tests/benchmarks/python/sweep_speedup.py BUILD_DIR

The variants: a 20 × 10 grid of the Kahraman–Blankenship rig's pinion mass and mesh damping
ratio, with two workloads: its linear HB over 20 mesh frequencies with Floquet verdicts
(≈ 90 ms per variant, a realistic design-of-experiments task) and its Floquet multipliers alone
(≈ 0.6 ms, where the executors' per-task cost shows). Rows are checked equal across the runs.
"""

from __future__ import annotations

import concurrent.futures as cf
import multiprocessing
import sys
import time
from pathlib import Path


def main(build: Path) -> None:
    sys.path.insert(0, str(build / "python"))
    import numpy as np

    import geardyn

    base = geardyn.Scene.builtin("kahraman-blankenship-rig")
    variants = geardyn.grid({"gear.pinion.mass": list(np.linspace(2.0, 4.0, 20)),
                             "mesh.pinion-wheel.damping_ratio": list(np.linspace(0.0, 0.09, 10))})
    assert len(variants) == 200
    spawn = multiprocessing.get_context("spawn")
    import distributed

    workloads = [("hb", {"mesh_frequency": "1500.0:3500.0:20"},
                  "pinion-wheel.max_rms_dte_m"),
                 ("floquet", {}, "max_abs_multiplier")]
    for analysis, options, key in workloads:
        results = {}
        for workers in (1, 2):
            with cf.ProcessPoolExecutor(workers, mp_context=spawn) as pool:
                list(pool.map(abs, range(workers)))  # start the workers before the clock
                start = time.perf_counter()
                r = geardyn.sweep(base, variants, analysis, options=options, executor=pool)
                results[f"process pool, {workers} worker(s)"] = (time.perf_counter() - start, r)
        for workers in (1, 2):
            with distributed.LocalCluster(n_workers=workers, threads_per_worker=1,
                                          processes=True, dashboard_address=None,
                                          silence_logs=50) as cluster, \
                    distributed.Client(cluster) as client:
                client.run(lambda: __import__("geardyn"))  # import before the clock
                start = time.perf_counter()
                r = geardyn.sweep(base, variants, analysis, options=options, executor=client)
                results[f"Dask LocalCluster, {workers} worker(s)"] = (time.perf_counter() - start,
                                                                      r)
        reference = results["process pool, 1 worker(s)"][1].rows
        for name, (_, r) in results.items():
            assert [x[key] for x in r.rows] == [x[key] for x in reference], name
            assert not r.failures, name
        per_variant = sum(x["wall_time_s"] for x in reference) / len(variants)
        print(f"\n{analysis}: 200 variants, {per_variant * 1e3:.1f} ms per variant in the worker")
        print("| executor | wall [s] | speed-up over 1 worker |")
        print("|---|---|---|")
        for kind in ("process pool", "Dask LocalCluster"):
            one = results[f"{kind}, 1 worker(s)"][0]
            for workers in (1, 2):
                t = results[f"{kind}, {workers} worker(s)"][0]
                print(f"| {kind}, {workers} worker(s) | {t:.2f} | {one / t:.2f}× |")


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "build/bench"))
