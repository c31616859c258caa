"""Sweeps: many independent variants of one scene on any ``concurrent.futures`` executor.

>>> import geardyn
>>> base = geardyn.Scene.builtin("helical-pair")
>>> variants = geardyn.grid({"gear.pinion.teeth": [23, 25], "operating_point.torque": [100, 200]})
>>> result = geardyn.sweep(base, variants, "modes")         # a local process pool
>>> result.table                                            # one row per variant (pandas)

The default local process pool starts its workers with ``spawn``: in a script, call sweep under
``if __name__ == "__main__":`` (a REPL or a notebook needs nothing). A
``concurrent.futures.ThreadPoolExecutor`` works as well (the C++ library releases the GIL and is
thread-safe; a crash in one variant then takes the whole process, not one worker).

On a cluster, pass a Dask ``distributed.Client`` (or its ``get_executor()``) as ``executor``:
the same variants run on its workers, nothing else changes (docs/python.md). geardyn has no
scheduler of its own: the executor distributes, geardyn computes one variant per task.

Every finished variant is appended to ``results_file`` (JSON lines) as it arrives; a failed
variant is a row with its ``error`` and never stops the others; ``sweep(..., results_file=F)``
run again skips the variants F already holds (``retry_failed=True`` runs the failed ones again).
"""

from __future__ import annotations

import concurrent.futures as cf
import itertools
import json
import math
import multiprocessing
import os
import time
import traceback
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from ._scene import Scene, toml_value

__all__ = ["grid", "sweep", "SweepResult", "run_variant", "summarize"]

Variant = Mapping[str, Any]


def grid(axes: Mapping[str, Sequence[Any]]) -> list[dict[str, Any]]:
    """The Cartesian product of override values: ``{"path": [v1, v2], ...}`` → list of dicts,
    the last path varying fastest."""
    paths = list(axes)
    return [dict(zip(paths, values)) for values in itertools.product(*(axes[p] for p in paths))]


def _finite(v: Any) -> Any:
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def _plain(value: Any) -> Any:
    """A row value as plain JSON data: numpy scalars and arrays as Python numbers and lists,
    non-finite floats as None (a row from a user's function may hold any of them)."""
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        return _plain(value.tolist())
    if isinstance(value, float):
        return _finite(value)
    if value is None or isinstance(value, (bool, int, str)):
        return value
    return str(value)


def summarize(analysis: str, result: Any) -> dict[str, Any]:
    """The scalar row a sweep keeps of one analysis result (status, and per analysis:
    modes → f_0 … f_{m−1} [Hz]; floquet → max|λ|, verdict, stable; hb → per mesh the largest
    RMS DTE [m] and its mesh frequency [Hz]; stability_chart → unstable and undetermined points;
    info → contact ratios and mesh frequency)."""
    row: dict[str, Any] = {}
    if analysis == "info":
        report = result.report
        row["status"] = "success"
        for m in report.get("meshes", []):
            name = m.get("name", "mesh")
            for key in ("transverse_contact_ratio", "axial_contact_ratio", "total_contact_ratio",
                        "mesh_frequency_hz"):
                if key in m:
                    row[f"{name}.{key}"] = m[key]
        return row
    row["status"] = result.summary.status
    row["exit_code"] = result.exit_code
    if analysis == "modes":
        for k, f in enumerate(result.frequencies_hz):
            row[f"f_{k}_hz"] = float(f)
    elif analysis == "floquet":
        row["max_abs_multiplier"] = _finite(float(result.max_abs_multiplier))
        row["verdict"] = result.verdict
        row["stable"] = result.stable
    elif analysis in ("hb", "simulate"):
        for name, rms in result.rms_dte_m.items():
            finite = [(float(v), float(f)) for v, f in zip(rms, result.mesh_frequency_hz)
                      if math.isfinite(v)]
            peak = max(finite, default=(math.nan, math.nan))
            row[f"{name}.max_rms_dte_m"] = _finite(peak[0])
            row[f"{name}.peak_mesh_frequency_hz"] = _finite(peak[1])
    elif analysis == "stability_chart":
        row["num_unstable_points"] = result.report["num_unstable_points"]
        row["num_undetermined_points"] = result.report["num_undetermined_points"]
    return row


def run_variant(scene: Scene, overrides: Mapping[str, Any], analysis: str | Callable[..., Any],
                options: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """One variant: ``scene`` with ``overrides``, the analysis, its row. Never raises: an error is
    returned as ``{"error": "InputError: …"}`` (this is the task every executor runs)."""
    from . import _analyses

    start = time.perf_counter()
    try:
        variant = scene.with_overrides(dict(overrides))
        if callable(analysis):
            row = _plain(dict(analysis(variant, **(options or {}))))
        else:
            function = getattr(_analyses, analysis, None)
            if function is None or analysis.startswith("_"):
                raise ValueError(f"analysis: unknown '{analysis}' (info, mesh, modes, floquet, hb, "
                                 "stability_chart, or a callable)")
            row = summarize(analysis, function(variant, **(options or {})))
        row["error"] = None
    except Exception as e:  # noqa: BLE001 — a failed variant is a result, not a crash
        row = {"status": "error", "error": f"{type(e).__name__}: {e}"}
        if not isinstance(e, ValueError):
            row["traceback"] = traceback.format_exc(limit=4)
    row["wall_time_s"] = time.perf_counter() - start
    return row


@dataclass
class SweepResult:
    """The rows of a sweep, in variant order: the variant's override values, then its row.

    ``table`` is a pandas DataFrame when pandas is installed, else the list of dicts.
    """

    variants: list[dict[str, Any]]
    rows: list[dict[str, Any]]
    wall_time_s: float = 0.0
    resumed: int = 0  # variants taken from the results file
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def records(self) -> list[dict[str, Any]]:
        """One dict per variant: its override values, then its row."""
        return [{**v, **r} for v, r in zip(self.variants, self.rows)]

    @property
    def failures(self) -> list[dict[str, Any]]:
        """The failed variants with their error."""
        return [{**v, "error": r["error"]} for v, r in zip(self.variants, self.rows)
                if r.get("error")]

    @property
    def table(self) -> Any:
        """The records as a pandas DataFrame (the list of dicts without pandas)."""
        try:
            import pandas as pd
        except ImportError:
            return self.records
        return pd.DataFrame.from_records(self.records)


def _key(variant: Variant) -> str:
    return json.dumps({k: toml_value(v) for k, v in variant.items()}, sort_keys=True)


def _read_results(path: str) -> dict[str, dict[str, Any]]:
    done: dict[str, dict[str, Any]] = {}
    if not os.path.exists(path):
        return done
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.strip()
            if not line:
                continue
            try:
                entry = json.loads(line)
            except json.JSONDecodeError:
                continue  # a line cut short by a crash: that variant runs again
            done[entry["key"]] = entry["row"]
    return done


def _default_executor(max_workers: int | None) -> cf.Executor:
    # spawn, not fork: a forked child of a process whose OpenMP or FFTW threads are running can
    # hang; scripts therefore need the usual `if __name__ == "__main__":` guard.
    return cf.ProcessPoolExecutor(max_workers=max_workers or os.cpu_count(),
                                  mp_context=multiprocessing.get_context("spawn"))


def sweep(scene: Scene | str, variants: Iterable[Variant], analysis: str | Callable[..., Any] = "modes",
          *, options: Mapping[str, Any] | None = None, executor: Any = None,
          max_workers: int | None = None, results_file: str | os.PathLike[str] | None = None,
          retry_failed: bool = False,
          progress: Callable[[int, int], None] | None = None) -> SweepResult:
    """Runs ``analysis`` on every variant of ``scene`` and gathers one row per variant.

    Args:
        scene: the base scene (a Scene or "builtin:NAME" / a path).
        variants: override dicts, e.g. from :func:`grid`.
        analysis: "modes", "floquet", "hb", "stability_chart", "info", or a picklable callable
            ``f(scene, **options) -> dict`` (a module-level function).
        options: keyword arguments of the analysis (e.g. ``{"num_modes": 6}``).
        executor: a ``concurrent.futures.Executor``, a Dask ``distributed.Client`` (its
            ``get_executor()`` is used), or None for a local process pool of ``max_workers``.
        results_file: JSON-lines file each finished variant is appended to, and read back to
            resume an interrupted sweep.
        retry_failed: on resume, run the variants whose row has an error again.
        progress: called as ``progress(done, total)`` after each variant.
    """
    base = scene if isinstance(scene, Scene) else Scene.load(scene)
    variants = [dict(v) for v in variants]
    keys = [_key(v) for v in variants]
    path = os.fspath(results_file) if results_file is not None else None
    done = _read_results(path) if path else {}
    rows: list[dict[str, Any] | None] = [None] * len(variants)
    resumed = 0
    for i, k in enumerate(keys):
        if k in done and (not retry_failed or not done[k].get("error")):
            rows[i] = done[k]
            resumed += 1
    todo = [i for i, r in enumerate(rows) if r is None]
    start = time.perf_counter()
    own = executor is None
    if own:
        executor = _default_executor(max_workers) if todo else None
    elif hasattr(executor, "get_executor"):  # a dask.distributed Client
        executor = executor.get_executor(pure=False)
    sink = open(path, "a", encoding="utf-8") if path else None
    finished = len(variants) - len(todo)
    try:
        futures = {executor.submit(run_variant, base, variants[i], analysis, options): i
                   for i in todo}
        for future in cf.as_completed(futures):
            i = futures[future]
            try:
                row = future.result()
            except Exception as e:  # noqa: BLE001 — a worker died (the task itself never raises)
                row = {"status": "error", "error": f"{type(e).__name__}: {e}"}
            rows[i] = row
            if sink:
                entry = {"key": keys[i], "variant": _plain(variants[i]), "row": _plain(row)}
                sink.write(json.dumps(entry, allow_nan=False) + "\n")
                sink.flush()
            finished += 1
            if progress:
                progress(finished, len(variants))
    finally:
        if sink:
            sink.close()
        if own and executor is not None:
            executor.shutdown(wait=True, cancel_futures=True)
    if own and todo and all((rows[i] or {}).get("error", "") and
                            str(rows[i]["error"]).startswith("BrokenProcessPool") for i in todo):
        # Nothing ran: the usual cause is a script without the main guard, whose spawned
        # workers re-run it and fail while starting.
        raise RuntimeError(
            "geardyn.sweep: the local process pool's workers could not start (BrokenProcessPool). "
            "A script that calls geardyn.sweep without executor= must do so under "
            "`if __name__ == \"__main__\":` (the spawn start method imports the script in every "
            "worker); or pass executor=concurrent.futures.ThreadPoolExecutor(n) (the C++ "
            "library runs without the GIL and is thread-safe)")
    return SweepResult(variants, [r if r is not None else {} for r in rows],
                       time.perf_counter() - start, resumed)
