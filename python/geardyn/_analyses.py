"""The analyses of the ``geardyn`` command as functions of a :class:`Scene`.

Each takes the command's options as keyword arguments with the same defaults, runs the same C++
code (apps/geardyn/analysis_runs.hpp) with the GIL released, and returns a result whose
``report`` equals the command's ``--json`` output. ``out_dir`` writes the files the command's
``--out`` writes. Bad input raises :class:`InputError` (a ValueError) with the C++ message;
numerical trouble is a status in ``summary`` (``exit_code`` 1), never an exception.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from . import _geardyn  # type: ignore[attr-defined]
from ._results import (FloquetResult, HbResult, InfoResult, MeshResult, MeshTable, ModesResult,
                       StabilityChartResult, Summary, SystemMatrices)
from ._scene import Scene

__all__ = ["info", "mesh", "modes", "floquet", "hb", "stability_chart", "system_matrices"]

SceneLike = Scene | str | os.PathLike[str]
Progress = Callable[[str], None] | None


def _scene(scene: SceneLike) -> Scene:
    return scene if isinstance(scene, Scene) else Scene.load(scene)


def _out(out_dir: str | os.PathLike[str] | None) -> str:
    if out_dir is None:
        return ""
    path = os.fspath(out_dir)
    os.makedirs(path, exist_ok=True)
    return path


def _run_fields(raw: dict[str, Any], summary: Summary | None = None) -> dict[str, Any]:
    return {"report": raw["report"], "text": raw["text"], "exit_code": raw["exit_code"],
            "summary": summary if summary is not None else Summary._from_cpp(raw["summary"])}


def info(scene: SceneLike) -> InfoResult:
    """``geardyn info``: derived geometry, contact ratios, ISO 6336 stiffness, mesh frequency."""
    report, text = _geardyn.info(_scene(scene).handle())
    return InfoResult(report, text)


def mesh(scene: SceneLike, *, samples: float | None = None,
         cycles: float | None = None) -> MeshResult:
    """``geardyn mesh``: K(θ), h(θ), κ(θ), μ(θ), ε(θ) of every mesh.

    Args:
        samples: samples per mesh cycle (default 360; fewer over long hunting periods).
        cycles: mesh cycles from θ = 0 (default: the mesh's period).
    """
    raw = _geardyn.mesh(_scene(scene).handle(), samples, cycles)
    tables = {t["name"]: MeshTable(**t) for t in raw["meshes"]}
    return MeshResult(raw["report"], tables)


def modes(scene: SceneLike, *, num_modes: int = 20, method: str = "auto", shapes: bool = False,
          damped: bool = False, out_dir: str | os.PathLike[str] | None = None) -> ModesResult:
    """``geardyn modes``: natural frequencies, mode types and energy fractions of the mean system.

    Args:
        num_modes: the lowest N modes (all when the system has fewer DOFs).
        method: "auto" (dense below 200 DOFs, else ARPACK), "dense" or "arpack".
        shapes: also return the M-orthonormal mode shapes (n × m).
        damped: also compute the damped complex modes (report["damped_modes"]).
    """
    raw = _geardyn.modes(_scene(scene).handle(), num_modes, method, shapes, damped, _out(out_dir))
    labels = [m["label"] for m in raw["report"].get("modes", [])]
    fields = {k: raw[k] for k in ("frequencies_hz", "eigenvalues", "shapes", "dof_names",
                                  "kinetic_fractions", "body_kinetic_fractions", "body_names",
                                  "strain_fractions", "strain_names", "modal_damping_ratios",
                                  "num_rigid_body_modes")}
    return ModesResult(**_run_fields(raw), labels=labels, **fields)


def floquet(scene: SceneLike, *, method: str = "auto", tolerance: float = 1e-10, nev: int = 6,
            out_dir: str | os.PathLike[str] | None = None) -> FloquetResult:
    """``geardyn floquet``: Floquet multipliers, max|λ| and the verdict at the operating point.

    Args:
        method: "auto", "exact_steps", "magnus", "ode_stepper", "hill", "modal_projection" or
            "arpack_monodromy".
        tolerance: error target on the multipliers, in (0, 1).
        nev: arpack_monodromy's number of largest multipliers.
    """
    raw = _geardyn.floquet(_scene(scene).handle(), method, tolerance, nev, _out(out_dir))
    stable = raw["report"]["stable"]
    fields = {k: raw[k] for k in ("multipliers", "exponents", "max_abs_multiplier",
                                  "stability_margin", "verdict", "marginal", "mesh_frequency_hz",
                                  "period_s", "period_meshes", "method_used")}
    return FloquetResult(**_run_fields(raw), stable=stable, **fields)


def _frequency_spec(mesh_frequency: Any) -> str:
    if mesh_frequency is None:
        return ""
    if isinstance(mesh_frequency, str):
        return mesh_frequency
    if isinstance(mesh_frequency, (int, float)):
        return repr(float(mesh_frequency))
    values = tuple(mesh_frequency)
    if len(values) != 3:
        raise _geardyn.InputError(
            f"mesh_frequency: give a frequency, 'lo:hi:n' or (lo, hi, n), got {mesh_frequency!r}")
    lo, hi, n = values
    if int(n) != n:
        raise _geardyn.InputError(f"mesh_frequency: n must be an integer, got {n!r}")
    return f"{float(lo)!r}:{float(hi)!r}:{int(n)}"


def hb(scene: SceneLike, *, mesh_frequency: str | float | Sequence[float] | None = None,
       harmonics: int | None = None, tolerance: float | None = None, linear: bool = False,
       nonlinear: bool = False, stability: str = "monodromy", monodromy_steps: int = 0,
       branch_search: int = 8, out_dir: str | os.PathLike[str] | None = None,
       progress: Progress = None) -> HbResult:
    """``geardyn hb``: steady-state DTE, mesh and bearing forces over mesh frequency.

    Nonlinear (contact loss, continuation) when a mesh has ``model = "slices"``, else linear
    (with the Floquet verdict of every point unless ``stability="none"``).

    Args:
        mesh_frequency: one frequency [Hz], "lo:hi:n" or (lo, hi, n); default 0.2 … 2.5 times
            the scene's, n = 200.
        harmonics: H (default: from ``tolerance``; nonlinear 24).
        tolerance: linear: the accepted change of the RMS DTE from H/2 to H (default 1e-4).
        progress: called with each progress line (e.g. ``print``).
    """
    if harmonics is not None and harmonics < 1:
        raise _geardyn.InputError(
            f"--harmonics: must be >= 1 (omit it to choose H from --tolerance), got {harmonics}")
    raw = _geardyn.hb(_scene(scene).handle(), _frequency_spec(mesh_frequency), harmonics or 0,
                      tolerance, linear, nonlinear, stability, monodromy_steps, branch_search,
                      _out(out_dir), progress)
    report = raw["report"]
    points = report.get("points", [])
    names = list(report.get("meshes", [])) or sorted(
        {m["name"] for p in points for m in p.get("meshes", [])})
    names = [n if isinstance(n, str) else n.get("name") for n in names]

    def column(key: str) -> dict[str, np.ndarray]:
        out = {}
        for name in names:
            values = []
            for p in points:
                row = next((m for m in p.get("meshes", []) if m["name"] == name), None)
                v = None if row is None else row.get(key)
                values.append(math.nan if v is None else float(v))
            out[name] = np.array(values, dtype=float)
        return out

    def verdict(p: dict[str, Any]) -> float:
        s = p.get("stable")
        if s is None and isinstance(p.get("stability"), dict):
            v = p["stability"].get("verdict")
            s = None if v in (None, "undetermined") else v == "stable"
        return math.nan if s is None else float(bool(s))

    freq = np.array([float(p["mesh_frequency_hz"]) for p in points], dtype=float)
    return HbResult(
        **_run_fields(raw, Summary._from_report(report)), nonlinear=raw["nonlinear"],
        mesh_frequency_hz=freq, rms_dte_m=column("rms_dte_m"),
        peak_to_peak_dte_m=column("peak_to_peak_dte_m"), rms_force_n=column("rms_force_n"),
        stable=np.array([verdict(p) for p in points], dtype=float),
        branch=np.array([int(p.get("branch", 0)) for p in points], dtype=int),
        segment=np.array([int(p.get("segment", 0)) for p in points], dtype=int),
        jumps=list(report.get("jumps", [])))


def _axis(axis: str | tuple[str, float, float, int]) -> str:
    if isinstance(axis, str):
        return axis
    path, lo, hi, n = axis
    return f"{path}={float(lo)!r}:{float(hi)!r}:{int(n)}"


def stability_chart(scene: SceneLike, *, x: str | tuple[str, float, float, int],
                    y: str | tuple[str, float, float, int], threads: int = 0,
                    method: str = "auto", tolerance: float = 1e-6,
                    boundary_tolerance: float = 1e-3, max_order: int = 3,
                    difference: bool = False, curves: bool = True,
                    out_dir: str | os.PathLike[str] | None = None,
                    progress: Progress = None) -> StabilityChartResult:
    """``geardyn stability-chart``: max|λ| of the Floquet multipliers over two scene parameters,
    the unstable regions labelled by their parametric resonance, and the transition curves.

    Args:
        x, y: "PATH=LO:HI:N" or (PATH, LO, HI, N) over any override path, e.g.
            ("operating_point.speed_rpm", 500, 6000, 60).
        threads: threads (0 = all cores).
        tolerance: Floquet error target of every point.
    """
    s = _scene(scene)
    text = "" if s.source.startswith("builtin:") and s._text is None else s.text
    raw = _geardyn.stability_chart(s.source, text, list(s.overrides), _axis(x), _axis(y), threads,
                                   method, tolerance, boundary_tolerance, max_order, difference,
                                   curves, _out(out_dir), progress)
    nx, ny = len(raw["x"]), len(raw["y"])
    ok = raw["ok"].reshape(ny, nx).astype(bool)
    stable = raw["stable"].reshape(ny, nx).astype(float)
    stable[~ok] = math.nan
    return StabilityChartResult(
        **_run_fields(raw), x_path=raw["x_path"], y_path=raw["y_path"], x=raw["x"], y=raw["y"],
        max_abs_multiplier=raw["max_abs_multiplier"].reshape(ny, nx),
        error_estimate=raw["error_estimate"].reshape(ny, nx),
        mesh_frequency_hz=raw["mesh_frequency_hz"].reshape(ny, nx), determined=ok, stable=stable,
        region=raw["region"].reshape(ny, nx), regions=list(raw["report"]["regions"]),
        curves=[(cx, cy, bool(closed)) for cx, cy, closed in raw["curves"]])


def system_matrices(scene: SceneLike, *, harmonics: int = 0,
                    out_dir: str | os.PathLike[str] | None = None) -> SystemMatrices:
    """M, C, K of the mean system (exactly what :func:`modes` solves), the mean load f and the
    harmonics K_m, C_m, f_m (m = 0 … ``harmonics``), with the DOF map; ``out_dir`` writes the
    MatrixMarket files and dofs.json of ``geardyn matrices``.
    """
    import scipy.sparse as sp

    raw = _geardyn.system_matrices(_scene(scene).handle(), harmonics, _out(out_dir))

    def csc(t: tuple[Any, Any, Any, tuple[int, int]]) -> Any:
        data, indices, indptr, shape = t
        return sp.csc_matrix((data, indices, indptr), shape=shape)

    return SystemMatrices(raw["report"], csc(raw["mass"]), csc(raw["damping"]),
                          csc(raw["stiffness"]), raw["mean_load"], list(raw["stiffness_harmonics"]),
                          list(raw["damping_harmonics"]), list(raw["load_harmonics"]))
