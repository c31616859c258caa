"""Sweeps: a process pool and a Dask LocalCluster with two worker processes give the serial
result; failed variants keep their error without losing the others; a sweep resumes from its
results file."""

from __future__ import annotations

import concurrent.futures as cf
import json
import math

import numpy as np
import pytest

import geardyn
from geardyn.sweep import summarize

BASE = "builtin:kahraman-blankenship-rig"
AXES = {"gear.pinion.mass": [2.5, 3.0, 3.5], "mesh.pinion-wheel.center_distance": [0.150, 0.1502]}


def serial_rows(variants):
    """The truth: each variant through geardyn.modes in this process, no sweep machinery."""
    base = geardyn.Scene.builtin("kahraman-blankenship-rig")
    return [list(geardyn.modes(base.with_overrides(v), num_modes=6).frequencies_hz)
            for v in variants]


def frequencies(result):
    return [[r[f"f_{k}_hz"] for k in range(6)] for r in result.rows]


def test_grid_is_the_cartesian_product():
    g = geardyn.grid(AXES)
    assert len(g) == 6
    assert g[0] == {"gear.pinion.mass": 2.5, "mesh.pinion-wheel.center_distance": 0.150}
    assert g[1] == {"gear.pinion.mass": 2.5, "mesh.pinion-wheel.center_distance": 0.1502}


def test_a_process_pool_gives_the_serial_result():
    variants = geardyn.grid(AXES)
    result = geardyn.sweep(BASE, variants, "modes", options={"num_modes": 6}, max_workers=2)
    assert frequencies(result) == serial_rows(variants)  # bit for bit: the same code
    assert not result.failures
    table = result.table
    assert list(table["gear.pinion.mass"]) == [v["gear.pinion.mass"] for v in variants]
    assert (table["status"] == "success").all()


def test_a_dask_local_cluster_with_two_workers_gives_the_serial_result():
    distributed = pytest.importorskip("distributed")
    variants = geardyn.grid(AXES)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None, silence_logs=50) as cluster, \
            distributed.Client(cluster) as client:
        result = geardyn.sweep(BASE, variants, "modes", options={"num_modes": 6}, executor=client)
        workers = client.run(lambda: __import__("os").getpid())
    assert len(workers) == 2
    assert frequencies(result) == serial_rows(variants)


def test_failed_variants_keep_their_error_and_the_others_their_results(tmp_path):
    variants = [{"gear.pinion.mass": 3.0}, {"gear.pinion.teeth": -5}, {"gear.pinion.mass": 2.0},
                {"no.such.key": 1}]
    with cf.ThreadPoolExecutor(2) as pool:
        result = geardyn.sweep(BASE, variants, "floquet", executor=pool)
    errors = [r["error"] for r in result.rows]
    assert errors[0] is None and errors[2] is None
    assert errors[1].startswith("SceneError: ") and "must be a positive integer" in errors[1]
    assert errors[3].startswith("SceneError: ")
    assert [f["gear.pinion.teeth"] for f in result.failures if "gear.pinion.teeth" in f] == [-5]
    direct = geardyn.floquet(geardyn.Scene.builtin("kahraman-blankenship-rig",
                                                   {"gear.pinion.mass": 2.0}))
    assert result.rows[2]["max_abs_multiplier"] == direct.max_abs_multiplier


def counting_analysis(scene, log):
    """A picklable user analysis that records each call (for the resume test)."""
    with open(log, "a") as f:
        f.write(json.dumps(list(scene.overrides)) + "\n")
    return {"f_1_hz": float(geardyn.modes(scene, num_modes=3).frequencies_hz[1])}


def test_a_sweep_resumes_from_its_results_file(tmp_path):
    variants = geardyn.grid({"gear.pinion.mass": [2.0, 2.5, 3.0, 3.5]})
    results, log = tmp_path / "sweep.jsonl", tmp_path / "calls.log"
    with cf.ThreadPoolExecutor(1) as pool:
        first = geardyn.sweep(BASE, variants[:2], counting_analysis, options={"log": str(log)},
                              executor=pool, results_file=results)
    # An interrupted sweep: the file holds 2 finished rows and half of a third line.
    with open(results, "a") as f:
        f.write('{"key": "cut sh')
    with cf.ThreadPoolExecutor(1) as pool:
        second = geardyn.sweep(BASE, variants, counting_analysis, options={"log": str(log)},
                               executor=pool, results_file=results)
    assert first.resumed == 0 and second.resumed == 2
    assert len(log.read_text().splitlines()) == 4  # 2 + the 2 missing ones, none twice
    direct = [geardyn.modes(geardyn.Scene.builtin("kahraman-blankenship-rig", v),
                            num_modes=3).frequencies_hz[1] for v in variants]
    assert [r["f_1_hz"] for r in second.rows] == pytest.approx(direct, rel=1e-15)


def test_failed_rows_are_retried_on_request(tmp_path):
    results = tmp_path / "sweep.jsonl"
    variants = [{"gear.pinion.teeth": -5}]
    with cf.ThreadPoolExecutor(1) as pool:
        geardyn.sweep(BASE, variants, "modes", executor=pool, results_file=results)
        again = geardyn.sweep(BASE, variants, "modes", executor=pool, results_file=results)
        retried = geardyn.sweep(BASE, variants, "modes", executor=pool, results_file=results,
                                retry_failed=True)
    assert again.resumed == 1 and retried.resumed == 0
    assert retried.rows[0]["error"].startswith("SceneError")


def test_every_analysis_gives_a_row():
    scene = geardyn.Scene.builtin("kahraman-singh-oscillator")
    with cf.ThreadPoolExecutor(2) as pool:
        for analysis, options, key in [
                ("floquet", {}, "max_abs_multiplier"),
                ("hb", {"mesh_frequency": (0.5, 1.5, 11), "harmonics": 8},
                 "oscillator.max_rms_dte_m"),
                ("simulate", {}, "oscillator.max_rms_dte_m"),
                ("stability_chart", {"x": "oscillator.frequency_ratio=0.5:2.5:5",
                                     "y": "oscillator.alpha=0:0.4:2", "threads": 1},
                 "num_unstable_points")]:
            result = geardyn.sweep(scene, [{"oscillator.zeta": 0.02}], analysis,
                                   options=options, executor=pool)
            row = result.rows[0]
            assert row["error"] is None, (analysis, row)
            assert row[key] is not None and not (isinstance(row[key], float)
                                                 and math.isnan(row[key])), (analysis, row)


def test_progress_counts_every_variant():
    seen = []
    with cf.ThreadPoolExecutor(2) as pool:
        geardyn.sweep(BASE, geardyn.grid({"gear.pinion.mass": [2.0, 3.0, 4.0]}), "modes",
                      executor=pool, progress=lambda done, total: seen.append((done, total)))
    assert sorted(seen) == [(1, 3), (2, 3), (3, 3)]


def numpy_row(scene):
    """A user analysis returning numpy values and a NaN (the results file must still be JSON)."""
    f = geardyn.modes(scene, num_modes=3).frequencies_hz
    return {"f": f[1:], "n": np.int64(3), "missing": float("nan")}


def test_user_rows_with_numpy_values_and_nan_are_written_and_resumed(tmp_path):
    results = tmp_path / "sweep.jsonl"
    variants = [{"gear.pinion.mass": 3.0}]
    with cf.ThreadPoolExecutor(1) as pool:
        first = geardyn.sweep(BASE, variants, numpy_row, executor=pool, results_file=results)
        again = geardyn.sweep(BASE, variants, numpy_row, executor=pool, results_file=results)
    assert again.resumed == 1
    assert first.rows[0]["missing"] is None and first.rows[0]["n"] == 3
    assert again.rows[0]["f"] == first.rows[0]["f"] and len(first.rows[0]["f"]) == 2
    for line in results.read_text().splitlines():
        json.loads(line)  # strict JSON: no NaN


def test_a_thread_pool_gives_the_serial_result_for_every_analysis_at_once():
    # The C++ library runs without the GIL: several analyses at once in threads must not share
    # state (FFTW plans and ARPACK are locked; everything else is per call).
    base = geardyn.Scene.builtin("kahraman-blankenship-rig")
    variants = geardyn.grid({"gear.pinion.mass": [2.5, 3.0, 3.5, 4.0]})
    calls = [("modes", {"num_modes": 6}), ("floquet", {}),
             ("hb", {"mesh_frequency": (2000, 3000, 6), "harmonics": 8})]
    with cf.ThreadPoolExecutor(4) as pool:
        futures = [(a, o, geardyn.sweep(base, variants, a, options=o, executor=pool))
                   for a, o in calls]
    for analysis, options, result in futures:
        serial = [summarize(analysis, getattr(geardyn, analysis)(
            base.with_overrides(v), **options)) for v in variants]
        for got, want in zip(result.rows, serial):
            for key, value in want.items():
                if key not in ("wall_time_s",):
                    assert got[key] == value, (analysis, key)


def test_a_script_without_the_main_guard_gets_a_clear_error(tmp_path):
    import os
    import subprocess
    import sys

    script = tmp_path / "unguarded.py"
    script.write_text("import geardyn\n"
                      "geardyn.sweep('builtin:helical-pair', [{}, {}], 'modes', max_workers=1)\n")
    from pathlib import Path

    env = dict(os.environ, PYTHONPATH=str(Path(geardyn.__file__).resolve().parents[1]))
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env,
                          cwd=tmp_path, timeout=120)
    assert done.returncode != 0
    assert 'if __name__ == "__main__":' in done.stderr.splitlines()[-1]
