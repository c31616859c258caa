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
from ._results import (CompareResult, FloquetResult, HbResult, InfoResult, MeshResult,
                       MeshTable, ModesResult, SimulateResult, StabilityChartResult, Summary,
                       SystemMatrices)
from ._results import _report
from ._scene import Scene

__all__ = ["info", "mesh", "modes", "floquet", "hb", "stability_chart", "system_matrices",
           "simulate", "compare"]

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
    return {"report_source": raw["report"], "text": raw["text"], "exit_code": raw["exit_code"],
            "summary": summary if summary is not None else Summary._from_cpp(raw["summary"]),
            "cpp_wall_time_s": raw["cpp_wall_time_s"]}


def _convert(raw: dict[str, Any]) -> dict[str, Any]:
    """`raw` with its report converted to a dict (for the results built from the report)."""
    raw["report"] = _report(raw["report"])
    return raw["report"]


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
    return MeshResult(_convert(raw), tables)


def modes(scene: SceneLike, *, num_modes: int = 20, method: str = "auto", shapes: bool = False,
          damped: bool = False, loaded: bool = False,
          out_dir: str | os.PathLike[str] | None = None) -> ModesResult:
    """``geardyn modes``: natural frequencies, mode types and energy fractions of the mean system.

    Args:
        num_modes: the lowest N modes (all when the system has fewer DOFs).
        method: "auto" (dense below 200 DOFs, else ARPACK), "dense" or "arpack".
        shapes: also return the M-orthonormal mode shapes (n × m).
        damped: also compute the damped complex modes (report["damped_modes"]).
        loaded: the modes about the loaded operating point: each mesh's tangent (geometric)
            stiffness under its static force added (``--loaded``; report["mesh_preload"]).
    """
    raw = _geardyn.modes(_scene(scene).handle(), num_modes, method, shapes, damped, loaded,
                         _out(out_dir))
    fields = {k: raw[k] for k in ("frequencies_hz", "eigenvalues", "shapes", "dof_names", "labels",
                                  "kinetic_fractions", "body_kinetic_fractions", "body_names",
                                  "strain_fractions", "strain_names", "modal_damping_ratios",
                                  "num_rigid_body_modes", "method_used")}
    return ModesResult(**_run_fields(raw), **fields)


def floquet(scene: SceneLike, *, method: str = "auto", tolerance: float = 1e-10, nev: int = 6,
            max_approximant_period: int = 1000,
            out_dir: str | os.PathLike[str] | None = None) -> FloquetResult:
    """``geardyn floquet``: Floquet multipliers, max|λ| and the verdict at the operating point.

    Args:
        method: "auto", "exact_steps", "magnus", "ode_stepper", "hill", "modal_projection" or
            "arpack_monodromy".
        tolerance: error target on the multipliers, in (0, 1).
        nev: arpack_monodromy's number of largest multipliers.
        max_approximant_period: meshes at incommensurate frequencies (no common period of at most
            10⁴ cycles): the longest common period of the rational approximants analysed instead
            [mesh cycles], 0 … 10⁴ (0 refuses such a scene). The approximants are in
            ``report["approximants"]``.
    """
    raw = _geardyn.floquet(_scene(scene).handle(), method, tolerance, nev, max_approximant_period,
                           _out(out_dir))
    fields = {k: raw[k] for k in ("multipliers", "exponents", "max_abs_multiplier", "stable",
                                  "stability_margin", "verdict", "marginal", "mesh_frequency_hz",
                                  "period_s", "period_meshes", "method_used")}
    return FloquetResult(**_run_fields(raw), **fields)


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
    (with the Floquet verdict of every point unless ``stability="none"``). A scene whose meshes
    run at several frequencies (a multi-stage train) is solved on the torus of its mesh
    frequencies (``harmonics`` is then the total order; nonlinear with slice meshes, a sweep
    from point to point, no stability verdicts).

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
    report = _convert(raw)
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
    text = _scene_text(s)
    raw = _geardyn.stability_chart(s.source, text, list(s.overrides), _axis(x), _axis(y), threads,
                                   method, tolerance, boundary_tolerance, max_order, difference,
                                   curves, _out(out_dir), progress)
    _convert(raw)
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


def _floats(values: Sequence[Any]) -> np.ndarray:
    return np.array([math.nan if v is None else float(v) for v in values], dtype=float)


def _scene_text(s: Scene) -> str:
    """The text the C++ runners reload the scene from ("" for a built-in or file scene that is
    read again by name)."""
    return "" if s._text is None else s.text


def simulate(scene: SceneLike, *, mesh_frequency: str | float | Sequence[float] | None = None,
             sweep: str = "", torque: float | Sequence[float] | None = None,
             integrator: str = "auto", tolerance: float | None = None,
             steady_tolerance: float | None = None, max_periods: int | None = None,
             record_periods: int | None = None, samples_per_period: int | None = None,
             max_step: float | None = None, threads: int = 0, quasi_static: bool = False,
             full_period: bool = False, overlay_hb: bool = False,
             out_dir: str | os.PathLike[str] | None = None,
             progress: Progress = None) -> SimulateResult:
    """``geardyn simulate``: time integration of the scene's system to steady state.

    Args:
        mesh_frequency: one frequency [Hz] (default: the operating point), "lo:hi:n" or
            (lo, hi, n) for several (independent runs in parallel, or a stepped ``sweep``).
        sweep: "" (independent speeds), "up", "down" or "both" (the state carried from point to
            point: both branches of a jump).
        torque: mean torque(s) [N·m] (default: the scene's).
        integrator: "auto", "runge_kutta", "generalized_alpha", ... (``geardyn simulate --help``).
        quasi_static: export the loaded K(θ) and STE as a mesh-parameter table instead.
        progress: called with each progress line (the pre-run warnings, e.g. a speed too low
            for the highest mode, are in ``warnings``).
    Defaults of the numeric options are the command's.
    """
    s = _scene(scene)
    torques = [] if torque is None else (
        [float(torque)] if isinstance(torque, (int, float)) else [float(t) for t in torque])
    raw = _geardyn.simulate(s.handle(), _scene_text(s), _frequency_spec(mesh_frequency), sweep,
                            torques, integrator, tolerance, steady_tolerance, max_periods,
                            record_periods, samples_per_period, max_step, threads, quasi_static,
                            full_period, overlay_hb, _out(out_dir), progress)
    report = _convert(raw)
    points = report.get("points", [])
    names = sorted({m["name"] for p in points for m in p.get("meshes", [])})

    def column(key: str) -> dict[str, np.ndarray]:
        return {n: _floats([next((m.get(key) for m in p.get("meshes", []) if m["name"] == n),
                                 None) for p in points]) for n in names}

    histories = raw["histories"]
    empty = np.zeros(0)
    return SimulateResult(
        **_run_fields(raw, Summary._from_report(report)),
        mesh_frequency_hz=_floats([p.get("mesh_frequency_hz") for p in points]),
        torque_nm=_floats([p.get("torque_nm") for p in points]),
        branch=[str(p.get("branch", "")) for p in points], rms_dte_m=column("rms_dte_m"),
        peak_to_peak_dte_m=column("peak_to_peak_dte_m"),
        steady=[str(p.get("steady", "")) for p in points],
        time_s=raw.get("time_s", empty),
        dte_m={n: h["dte_m"] for n, h in histories.items()},
        force_n={n: h["force_n"] for n, h in histories.items()})


def compare(scene: SceneLike, *, levels: str | Sequence[str] | None = None,
            analyses: str | Sequence[str] = "modes,floquet,hb", reference: str = "",
            mesh: str = "", mesh_frequency: str | float | Sequence[float] | None = None,
            num_modes: int = 12, nonlinear_harmonics: int = 24, branch_search: int = 8,
            max_periods: int = 3000, threads: int = 0, match_contact: bool = True,
            chart_x: str | tuple[str, float, float, int] = "",
            chart_y: str | tuple[str, float, float, int] = "",
            out_dir: str | os.PathLike[str] | None = None,
            progress: Progress = None) -> CompareResult:
    """``geardyn compare``: the scene at several model levels (contact, slices,
    blankenship_singh, bs_projected, five_dof, coupling_4dof, lti, torsional) side by side —
    modes matched by MAC, Floquet verdicts, DTE curves, differences to the reference level.

    Args:
        levels: the levels (default: all but contact; a listed level the scene cannot build is
            an error, a default one is skipped with the reason).
        analyses: of modes, floquet, hb, simulate.
        mesh_frequency: the DTE grid (default 0.2 … 2.5 times the scene's, 60 points).
        chart_x, chart_y: a stability chart per level over these axes ("PATH=LO:HI:N").
    """
    s = _scene(scene)
    level_text = None if levels is None else (levels if isinstance(levels, str)
                                              else ",".join(levels))
    analysis_text = analyses if isinstance(analyses, str) else ",".join(analyses)
    raw = _geardyn.compare(s.handle(), _scene_text(s), list(s.overrides), level_text,
                           analysis_text, reference, mesh, _frequency_spec(mesh_frequency),
                           num_modes, nonlinear_harmonics, branch_search, max_periods, threads,
                           match_contact, _axis(chart_x) if chart_x else "",
                           _axis(chart_y) if chart_y else "", _out(out_dir), progress)
    report = _convert(raw)
    runs = report.get("levels", [])
    names = [r["level"] for r in runs]

    def dte(key: str) -> dict[str, np.ndarray]:
        return {r["level"]: _floats((r.get("dte") or {}).get(key, [])) for r in runs
                if r.get("dte")}

    return CompareResult(
        **_run_fields(raw, Summary._from_report(report)), levels=names,
        frequencies_hz=_floats(report.get("frequencies_hz", [])), rms_dte_up_m=dte("rms_up_m"),
        rms_dte_down_m=dte("rms_down_m"),
        modal_frequencies_hz={r["level"]: _floats(r["modes"].get("frequencies_hz", []))
                              for r in runs if isinstance(r.get("modes"), dict)},
        references=dict(report.get("references", {})))
