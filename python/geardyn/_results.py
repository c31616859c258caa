"""Result objects of the analyses.

Every array is a numpy copy owned by the result (it stays valid after the result, or the
geardyn objects it came from, are gone). Every result carries ``report`` (the dict of the
``geardyn`` command's ``--json`` output for the same input), ``text`` (the command's text output),
``summary``, ``exit_code`` (the command's: 0 success, 1 a status other than success) and
``cpp_wall_time_s`` (the C++ share of the call's time).
Units are SI: Hz, m, rad, N, N·m, s.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["Summary", "ModesResult", "FloquetResult", "HbResult", "StabilityChartResult",
           "MeshTable", "MeshResult", "InfoResult", "SystemMatrices", "SimulateResult",
           "CompareResult"]


@dataclass(frozen=True)
class Summary:
    """Status of an analysis run (architecture §3.3): ``status`` is ``"success"``,
    ``"not_converged"``, ``"numerical_issue"``, ``"tolerance_not_met"`` or ``"interrupted"``."""

    status: str
    message: str = ""
    error_estimate: float = 0.0
    wall_time_s: float = 0.0
    counters: dict[str, int] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        """True when the status is "success"."""
        return self.status == "success"

    @classmethod
    def _from_cpp(cls, s: Any) -> Summary:
        return cls(s.status, s.message, s.error_estimate, s.wall_time_s, dict(s.counters),
                   list(s.warnings))

    @classmethod
    def _from_report(cls, r: dict[str, Any]) -> Summary:
        return cls(r.get("status", "success"), r.get("message", "") or "",
                   float(r.get("error_estimate", 0.0) or 0.0),
                   float(r.get("wall_time_s", 0.0) or 0.0), dict(r.get("counters", {}) or {}),
                   list(r.get("warnings", []) or []))


def _report(source: Any) -> dict[str, Any]:
    """A report dict from a C++ ReportHolder (converted once) or a dict."""
    return source.to_python() if hasattr(source, "to_python") else source


@dataclass(frozen=True)
class _Run:
    # The C++ report, converted to a dict on first access of `report` (a report with mode
    # shapes is thousands of numbers a caller of the arrays never reads).
    report_source: Any = field(repr=False, compare=False)
    text: str
    summary: Summary
    exit_code: int
    #: Seconds spent in the C++ library during the call; the rest of the call's wall time is the
    #: Python layer (argument conversion, numpy copies, result objects).
    cpp_wall_time_s: float

    @property
    def report(self) -> dict[str, Any]:
        """The command's --json output for the same input, as a dict."""
        cached = self.__dict__.get("_report_cache")
        if cached is None:
            cached = _report(self.report_source)
            object.__setattr__(self, "_report_cache", cached)
        return cached

    @property
    def ok(self) -> bool:
        """True when the command would have exited with 0."""
        return self.exit_code == 0

    @property
    def warnings(self) -> list[str]:
        """The report's warnings (the scene's, prefixed "scene: ", and the analysis')."""
        return list(self.report.get("warnings", []))


@dataclass(frozen=True)
class InfoResult:
    """``geardyn info``: derived geometry, contact ratios, mesh stiffness (``report``)."""

    report: dict[str, Any]
    text: str


@dataclass(frozen=True)
class ModesResult(_Run):
    """``geardyn modes``: modes of the mean (LTI) system.

    Attributes:
        frequencies_hz: (m,) natural frequencies, ascending [Hz]; 0 for rigid-body modes.
        eigenvalues: (m,) ω² [rad²/s²].
        shapes: (n, m) M-orthonormal mode shapes [m or rad per √kg]; (n, 0) without shapes=True.
        dof_names: (n,) row names of ``shapes`` ("<body>.<component>"); empty without shapes.
        labels: (m,) mode types ("rigid_body", "torsional", "translational", ...).
        kinetic_fractions: (m, 4) kinetic energy per DOF kind.
        strain_fractions: (m, s) strain energy per owner (columns ``strain_names``).
        modal_damping_ratios: (m,) ζ_k, empty without damping.
        method_used: "dense" or "arpack".
    """

    frequencies_hz: np.ndarray
    eigenvalues: np.ndarray
    shapes: np.ndarray
    dof_names: list[str]
    labels: list[str]
    kinetic_fractions: np.ndarray
    body_kinetic_fractions: np.ndarray
    body_names: list[str]
    strain_fractions: np.ndarray
    strain_names: list[str]
    modal_damping_ratios: np.ndarray
    num_rigid_body_modes: int
    method_used: str


@dataclass(frozen=True)
class FloquetResult(_Run):
    """``geardyn floquet``: Floquet multipliers at the operating point.

    ``stable`` is True, False, or None when the verdict is undetermined (never read None as
    unstable: see ``summary``).
    """

    multipliers: np.ndarray  # (k,) complex, by |λ|
    exponents: np.ndarray  # (k,) complex μ = ln(λ)/T [1/s]
    max_abs_multiplier: float
    stability_margin: float
    verdict: str  # "stable", "unstable" or "undetermined"
    stable: bool | None
    marginal: bool
    mesh_frequency_hz: float
    period_s: float
    period_meshes: int
    method_used: str


@dataclass(frozen=True)
class HbResult(_Run):
    """``geardyn hb``: steady-state DTE over mesh frequency (linear sweep or nonlinear trace).

    Attributes:
        nonlinear: which model ran (contact loss with slice meshes, else linear).
        mesh_frequency_hz: (p,) the points' mesh frequencies [Hz], in trace order (nonlinear:
            along the branch, folds included).
        rms_dte_m: mesh name → (p,) RMS dynamic transmission error [m].
        peak_to_peak_dte_m: mesh name → (p,) [m].
        rms_force_n: mesh name → (p,) RMS mesh force [N].
        stable: (p,) 1.0 stable, 0.0 unstable, NaN undetermined or not computed.
        branch: (p,) branch number (nonlinear; 0 for the linear sweep).
        segment: (p,) traced segment (nonlinear; 0 for the linear sweep).
        jumps: the nonlinear trace's jumps (report["jumps"]); empty for the linear sweep.
    """

    nonlinear: bool
    mesh_frequency_hz: np.ndarray
    rms_dte_m: dict[str, np.ndarray]
    peak_to_peak_dte_m: dict[str, np.ndarray]
    rms_force_n: dict[str, np.ndarray]
    stable: np.ndarray
    branch: np.ndarray
    segment: np.ndarray
    jumps: list[dict[str, Any]]


@dataclass(frozen=True)
class StabilityChartResult(_Run):
    """``geardyn stability-chart``: max|λ| over two scene parameters.

    Grid arrays are (ny, nx): row iy is ``y[iy]``, column ix is ``x[ix]``. ``stable`` is 1.0,
    0.0, or NaN where the point is undetermined (``determined`` False: the CSV's ``ok``). ``region`` is the index into
    ``regions`` (report["regions"], labelled by their parametric resonance), −1 if stable.
    ``curves`` are the transition curves as (x, y, closed).
    """

    x_path: str
    y_path: str
    x: np.ndarray
    y: np.ndarray
    max_abs_multiplier: np.ndarray
    error_estimate: np.ndarray
    mesh_frequency_hz: np.ndarray
    determined: np.ndarray
    stable: np.ndarray
    region: np.ndarray
    regions: list[dict[str, Any]]
    curves: list[tuple[np.ndarray, np.ndarray, bool]]


@dataclass(frozen=True)
class MeshTable:
    """K(θ), h(θ), κ(θ), μ(θ), ε(θ) of one mesh over its period (columns of mesh_NAME.csv)."""

    name: str
    cycle: np.ndarray  # θ/2π [mesh cycles]
    stiffness: np.ndarray  # K [N/m]
    load_centre: np.ndarray  # h [m]
    kappa: np.ndarray  # h/b [-]
    mu: np.ndarray  # [-]
    te_eta: np.ndarray  # ε_η [m] (empty without transmission error)
    te_zeta: np.ndarray  # ε_ζ [rad] (empty without transmission error)


@dataclass(frozen=True)
class MeshResult:
    """``geardyn mesh``: the sampled mesh parameters of every mesh, and ``report`` (mesh.json)."""

    report: dict[str, Any]
    meshes: dict[str, MeshTable]


@dataclass(frozen=True)
class SystemMatrices:
    """The system matrices (``geardyn matrices``): M, C, K of the mean system that
    ``geardyn modes`` solves (scipy.sparse CSC), the mean load f, and the Fourier harmonics
    K_m, C_m, f_m (m = 0 … H, dense complex) with
    K(θ) = K_0 + Σ_{m≥1} (K_m e^{imθ/P} + conj(K_m) e^{−imθ/P}), P = ``period_meshes``.

    ``dofs`` lists per DOF its index, name, body, component, kind and unit (m or rad).
    """

    report: dict[str, Any]
    mass: Any
    damping: Any
    stiffness: Any
    mean_load: np.ndarray
    stiffness_harmonics: list[np.ndarray]
    damping_harmonics: list[np.ndarray]
    load_harmonics: list[np.ndarray]

    @property
    def dofs(self) -> list[dict[str, Any]]:
        """Per DOF: index, name, body, component, kind and unit ("m" or "rad")."""
        return list(self.report["dofs"])

    @property
    def period_meshes(self) -> int:
        """P: harmonic m of the expansion is at m/P times the mesh frequency."""
        return int(self.report["period_meshes"])


@dataclass(frozen=True)
class SimulateResult(_Run):
    """``geardyn simulate``: time integration to steady state (one speed, several, or stepped
    sweeps), per mean torque.

    Attributes:
        mesh_frequency_hz: (p,) the points' mesh frequencies [Hz] (report["points"]).
        torque_nm: (p,) the points' mean torque [N·m].
        branch: (p,) "single", "independent", "up" or "down".
        rms_dte_m, peak_to_peak_dte_m: mesh name → (p,) [m] (NaN where a point has none).
        steady: (p,) the points' steady-state verdicts ("steady", "not_steady", ...).
        time_s: (s,) the recorded periods' sample times of a single run [s]; empty otherwise.
        dte_m, force_n: mesh name → (s,) DTE [m] and mesh force [N] histories of a single run.
    """

    mesh_frequency_hz: np.ndarray
    torque_nm: np.ndarray
    branch: list[str]
    rms_dte_m: dict[str, np.ndarray]
    peak_to_peak_dte_m: dict[str, np.ndarray]
    steady: list[str]
    time_s: np.ndarray
    dte_m: dict[str, np.ndarray]
    force_n: dict[str, np.ndarray]


@dataclass(frozen=True)
class CompareResult(_Run):
    """``geardyn compare``: one scene at several model levels side by side.

    Attributes:
        levels: the levels that ran, in report order (report["levels"] has each one's modes,
            Floquet verdict, DTE and comparison with the reference).
        frequencies_hz: (g,) the DTE grid [Hz].
        rms_dte_up_m, rms_dte_down_m: level → (g,) RMS DTE along the up/down sweep branches [m]
            (NaN where the level has no stable solution or ran no DTE).
        modal_frequencies_hz: level → its natural frequencies [Hz].
        references: analysis → the reference level.
    """

    levels: list[str]
    frequencies_hz: np.ndarray
    rms_dte_up_m: dict[str, np.ndarray]
    rms_dte_down_m: dict[str, np.ndarray]
    modal_frequencies_hz: dict[str, np.ndarray]
    references: dict[str, str]
