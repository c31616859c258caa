"""matplotlib pictures of geardyn results: K(θ), Campbell diagrams, stability charts with labelled
regions, and frequency-response curves with their stable and unstable branches and jumps.

Each function draws on ``ax`` (a new figure when None) and returns the Axes. matplotlib is
imported on first use, so ``import geardyn`` does not need it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ._results import (HbResult, MeshResult, MeshTable, ModesResult, SimulateResult,
                       StabilityChartResult)

__all__ = ["plot_mesh_stiffness", "plot_modes", "plot_campbell", "plot_stability_chart",
           "plot_frequency_response"]


def _axes(ax: Any) -> Any:
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    _, ax = plt.subplots(figsize=(7.5, 4.5))
    return ax


def plot_mesh_stiffness(mesh: MeshResult | MeshTable, ax: Any = None,
                        load_centre: bool = True) -> Any:
    """K(θ) [N/m] over mesh cycles of every mesh (and the load centre h(θ) [mm] on a second
    axis)."""
    ax = _axes(ax)
    tables = list(mesh.meshes.values()) if isinstance(mesh, MeshResult) else [mesh]
    for t in tables:
        ax.plot(t.cycle, t.stiffness, label=f"K, {t.name}")
    ax.set_xlabel("mesh cycles θ/2π")
    ax.set_ylabel("mesh stiffness K [N/m]")
    if load_centre and any(len(t.load_centre) for t in tables):
        twin = ax.twinx()
        for t in tables:
            twin.plot(t.cycle, np.asarray(t.load_centre) * 1e3, "--", linewidth=0.8,
                      label=f"h, {t.name}")
        twin.set_ylabel("load centre h [mm]")
    ax.legend(loc="best", fontsize="small")
    ax.set_title("mesh stiffness K(θ)")
    return ax


def plot_modes(modes: ModesResult, ax: Any = None, max_modes: int | None = None) -> Any:
    """The mode table as a frequency chart: one bar per mode at its frequency, coloured and
    labelled by its type (torsional, transverse, axial, ...)."""
    ax = _axes(ax)
    f = np.asarray(modes.frequencies_hz)
    labels = list(modes.labels) or [""] * len(f)
    if max_modes is not None:
        f, labels = f[:max_modes], labels[:max_modes]
    kinds = sorted(set(labels))
    colours = {k: f"C{i % 10}" for i, k in enumerate(kinds)}
    for i, (freq, label) in enumerate(zip(f, labels)):
        ax.barh(i, freq, color=colours[label], label=label)
        ax.text(freq, i, f" {freq:.1f} Hz", va="center", fontsize="x-small")
    handles, names = ax.get_legend_handles_labels()
    unique = dict(zip(names, handles))
    ax.legend(unique.values(), unique.keys(), loc="lower right", fontsize="small")
    ax.set_yticks(range(len(f)))
    ax.set_yticklabels([str(i) for i in range(len(f))])
    ax.set_ylabel("mode")
    ax.set_xlabel("natural frequency [Hz]")
    ax.set_title("modes of the mean system")
    return ax


def plot_campbell(speed_rpm: Sequence[float], frequencies_hz: Sequence[Sequence[float]],
                  mesh_hz_per_rpm: float, orders: Sequence[int] = (1, 2, 3), ax: Any = None,
                  labels: Sequence[str] | None = None) -> Any:
    """A Campbell diagram: natural frequencies (one row per speed, e.g. from a
    :func:`geardyn.sweep` of modes over ``operating_point.speed_rpm``) against speed, with the
    mesh orders k·f_mesh; crossings are the candidate resonances (B–S: k f_m = f_n).

    Args:
        speed_rpm: (s,) speeds [rpm].
        frequencies_hz: (s, m) natural frequencies [Hz] at each speed.
        mesh_hz_per_rpm: f_mesh per rpm (teeth / 60 for the pinion's speed).
    """
    ax = _axes(ax)
    speed = np.asarray(speed_rpm, dtype=float)
    table = np.asarray(frequencies_hz, dtype=float)
    for j in range(table.shape[1]):
        ax.plot(speed, table[:, j], "k-", linewidth=1.0,
                label=(labels[j] if labels is not None else None))
    for k in orders:
        ax.plot(speed, k * mesh_hz_per_rpm * speed, "--", label=f"{k}× mesh")
    ax.set_xlabel("speed [rpm]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_ylim(0, max(float(np.nanmax(table)) * 1.05, 1e-9))
    ax.legend(loc="upper left", fontsize="small")
    ax.set_title("Campbell diagram")
    return ax


def plot_stability_chart(chart: StabilityChartResult, ax: Any = None,
                         curves: bool = True, labels: bool = True) -> Any:
    """max|λ| over the two parameters, unstable points shaded, undetermined points hatched grey,
    the transition curves, and each unstable region labelled by its parametric resonance at its
    most unstable point."""
    ax = _axes(ax)
    x, y = np.asarray(chart.x), np.asarray(chart.y)
    unstable = np.where(chart.stable == 0.0, chart.max_abs_multiplier, np.nan)
    ax.pcolormesh(x, y, np.where(np.isnan(chart.stable), np.nan, 1.0), shading="nearest",
                  cmap="Greys", vmin=0.0, vmax=8.0)
    mesh = ax.pcolormesh(x, y, unstable, shading="nearest", cmap="Reds")
    if np.isfinite(unstable).any():
        ax.figure.colorbar(mesh, ax=ax, label="max|λ| (unstable)")
    undetermined = ~chart.determined
    if undetermined.any():
        gx, gy = np.meshgrid(x, y)
        ax.scatter(gx[undetermined], gy[undetermined], marker="x", color="0.4", s=12,
                   label="undetermined")
    if curves:
        for cx, cy, closed in chart.curves:
            px, py = (np.append(cx, cx[:1]), np.append(cy, cy[:1])) if closed else (cx, cy)
            ax.plot(px, py, "k-", linewidth=0.8)
    if labels:
        for k, region in enumerate(chart.regions):
            inside = chart.region == k
            if not inside.any():
                continue
            values = np.where(inside, chart.max_abs_multiplier, -np.inf)
            iy, ix = np.unravel_index(int(np.argmax(values)), values.shape)
            ax.annotate(region.get("label", "unstable"), (x[ix], y[iy]), fontsize="small",
                        ha="center", va="center",
                        bbox={"boxstyle": "round", "fc": "white", "alpha": 0.8})
    ax.set_xlabel(chart.x_path)
    ax.set_ylabel(chart.y_path)
    ax.set_title("stability chart (shaded: max|λ| > 1)")
    return ax


def plot_frequency_response(result: HbResult | SimulateResult, mesh: str | None = None,
                            ax: Any = None, unit: float = 1e-6, label: str | None = None) -> Any:
    """RMS DTE against mesh frequency: stable parts solid, unstable parts dashed, points without a
    verdict (undetermined, or stability="none") dotted, each traced segment (and each branch) a separate line, and the jumps
    of a nonlinear trace as vertical arrows. ``unit`` scales the DTE (1e-6: µm)."""
    ax = _axes(ax)
    name = mesh or next(iter(result.rms_dte_m), None)
    if name is None:
        return ax
    f = np.asarray(result.mesh_frequency_hz)
    rms = np.asarray(result.rms_dte_m[name]) / unit
    # A time-domain point is a response the integration reached (no verdict to draw); an HB point
    # without a verdict (undetermined, or stability="none") is dotted, never drawn as stable.
    stable = getattr(result, "stable", np.ones(len(f)))
    segment = getattr(result, "segment", np.zeros(len(f), dtype=int))
    branch = getattr(result, "branch", np.zeros(len(f), dtype=int))
    group = [f"{b}/{s}" for b, s in zip(branch, segment)]
    colour = None

    def kind(v: float) -> str:
        return "unknown" if math.isnan(v) else ("stable" if v == 1.0 else "unstable")

    for key in dict.fromkeys(group):
        idx = np.flatnonzero([g == key for g in group])
        ff, rr = f[idx], rms[idx]
        kinds = [kind(float(v)) for v in np.asarray(stable, dtype=float)[idx]]
        start = 0
        for i in range(1, len(ff) + 1):
            if i < len(ff) and kinds[i] == kinds[start]:
                continue
            # One run of equal verdicts, joined to the next run's first point.
            run = slice(start, min(i + 1, len(ff)))
            style = {"stable": "-", "unstable": "--", "unknown": ":"}[kinds[start]]
            lines = ax.plot(ff[run], rr[run], style, color=colour)
            colour = lines[0].get_color()
            start = i
    for jump in getattr(result, "jumps", []) or []:
        fj = jump.get("mesh_frequency_hz")
        lo, hi = jump.get("rms_dte_before_m"), jump.get("rms_dte_after_m")
        if fj is not None and lo is not None and hi is not None:
            ax.annotate("", (fj, hi / unit), (fj, lo / unit),
                        arrowprops={"arrowstyle": "->", "color": colour})
        elif fj is not None:
            ax.axvline(fj, color=colour, linestyle=":", linewidth=0.8)
    ax.set_xlabel("mesh frequency [Hz]")
    ax.set_ylabel("RMS DTE [µm]" if unit == 1e-6 else f"RMS DTE [{unit:g} m]")
    ax.set_title("frequency response (dashed: unstable, dotted: no verdict)")
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color=colour, linestyle="-", label=label or name)]
    if (np.asarray(stable) == 0.0).any():
        handles.append(Line2D([], [], color=colour, linestyle="--", label="unstable"))
    if np.isnan(np.asarray(stable, dtype=float)).any():
        handles.append(Line2D([], [], color=colour, linestyle=":", label="no verdict"))
    ax.legend(handles=handles, loc="best", fontsize="small")
    return ax
