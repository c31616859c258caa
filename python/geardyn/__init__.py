"""geardyn: gear mesh dynamics from Python.

The same C++ library as the ``geardyn`` command (not a wrapper of the command line): scenes,
the analyses (info, mesh, modes, floquet, stability_chart, hb, simulate, compare), the system matrices, and sweeps
of many variants on a process pool or a Dask cluster. See docs/python.md.

>>> import geardyn
>>> scene = geardyn.Scene.builtin("kahraman-blankenship-rig")
>>> modes = geardyn.modes(scene)
>>> modes.frequencies_hz[:3]
"""

from __future__ import annotations

from ._geardyn import InputError, InternalError, SceneError
from ._analyses import (compare, floquet, hb, info, mesh, modes, simulate, stability_chart,
                        system_matrices)
from ._results import (CompareResult, FloquetResult, HbResult, InfoResult, MeshResult,
                       MeshTable, ModesResult, SimulateResult, StabilityChartResult, Summary,
                       SystemMatrices)
from ._scene import Scene, builtin_scenes, to_toml
from .sweep import SweepResult, grid, sweep

__version__ = "0.1.0"

__all__ = [
    "Scene", "builtin_scenes", "to_toml",
    "info", "mesh", "modes", "floquet", "stability_chart", "hb", "simulate", "compare",
    "system_matrices",
    "grid", "sweep", "SweepResult",
    "Summary", "ModesResult", "FloquetResult", "HbResult", "StabilityChartResult", "MeshResult",
    "MeshTable", "InfoResult", "SystemMatrices", "SimulateResult", "CompareResult",
    "InputError", "SceneError", "InternalError",
]
