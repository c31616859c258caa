"""A gear-dynamics study from Python, notebook style: the standard pictures of one spur rig.

    PYTHONPATH=build/test/python /usr/bin/python3 examples/python/gear_study.py [OUT_DIR]

1. K(θ) and the load centre of the Kahraman–Blankenship rig's mesh over one mesh cycle.
2. Its modes, and a Campbell diagram: natural frequencies against pinion speed with the mesh
   orders k·f_mesh (a sweep of modes over operating_point.speed_rpm on 2 worker processes).
3. A Floquet stability chart over mesh frequency ratio and stiffness variation (the Kahraman–
   Singh oscillator), the unstable tongues labelled by their parametric resonance.
4. The DTE frequency response with contact loss (nonlinear harmonic balance on slice meshes):
   stable branches solid, unstable dashed, the jumps as arrows.
5. The system matrices M, C, K, checked against the modes with scipy.

Writes OUT_DIR/*.png (default ./results/python) and prints what each step found.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import scipy.linalg  # noqa: E402

import geardyn  # noqa: E402
from geardyn import plotting  # noqa: E402


def main(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    rig = geardyn.Scene.builtin("kahraman-blankenship-rig")

    # 1. Mesh stiffness over one mesh cycle.
    mesh = geardyn.mesh(rig)
    k = mesh.meshes["pinion-wheel"].stiffness
    print(f"1. K(θ): {k.min():.4g} … {k.max():.4g} N/m over one mesh cycle")
    plotting.plot_mesh_stiffness(mesh).figure.savefig(out / "mesh_stiffness.png", dpi=110)

    # 2. Modes and a Campbell diagram from a sweep over speed.
    modes = geardyn.modes(rig, num_modes=8)
    print("2. modes [Hz]: " + ", ".join(f"{f:.0f} ({t})" for f, t in
                                        zip(modes.frequencies_hz, modes.labels)))
    plotting.plot_modes(modes).figure.savefig(out / "modes.png", dpi=110)
    speeds = np.linspace(500.0, 6000.0, 12)
    sweep = geardyn.sweep(rig, [{"operating_point.speed_rpm": s} for s in speeds], "modes",
                          options={"num_modes": 8}, max_workers=2)
    table = np.array([[row[f"f_{i}_hz"] for i in range(8)] for row in sweep.rows])
    teeth = rig.to_dict()["gear"][0]["teeth"]
    plotting.plot_campbell(speeds, table[:, 1:], mesh_hz_per_rpm=teeth / 60.0,
                           orders=(1, 2, 3)).figure.savefig(out / "campbell.png", dpi=110)
    print(f"   Campbell: {len(speeds)} speeds on 2 processes in {sweep.wall_time_s:.2f} s")

    # 3. Stability chart of the parametrically excited oscillator.
    chart = geardyn.stability_chart("builtin:kahraman-singh-oscillator",
                                    x="oscillator.frequency_ratio=0.3:2.6:93",
                                    y="oscillator.alpha=0:0.8:33")
    labels = ", ".join(r["label"] for r in chart.regions)
    print(f"3. stability chart: {chart.report['num_unstable_points']} unstable points, "
          f"regions {labels}")
    plotting.plot_stability_chart(chart).figure.savefig(out / "stability_chart.png", dpi=110)

    # 4. Nonlinear frequency response with contact loss.
    slices = rig.with_overrides({"mesh.pinion-wheel.model": "slices",
                                 "mesh.pinion-wheel.center_distance": 0.1502,
                                 "mesh.pinion-wheel.damping_ratio": 0.05})
    hb = geardyn.hb(slices, mesh_frequency=(1500.0, 4000.0, 120))
    peak = float(np.nanmax(hb.rms_dte_m["pinion-wheel"]))
    print(f"4. nonlinear HB: {len(hb.mesh_frequency_hz)} points, peak RMS DTE "
          f"{peak * 1e6:.2f} µm, {len(hb.jumps)} jump(s), status {hb.summary.status}")
    plotting.plot_frequency_response(hb).figure.savefig(out / "frequency_response.png", dpi=110)

    # 5. The matrices, solved by scipy: the same frequencies as geardyn's modes.
    mats = geardyn.system_matrices(rig)
    lam = scipy.linalg.eigh(mats.stiffness.toarray(), mats.mass.toarray(), eigvals_only=True)
    f = np.sqrt(np.maximum(lam, 0.0))[: len(modes.frequencies_hz)] / (2 * math.pi)
    elastic = modes.frequencies_hz > 0
    worst = float(np.max(np.abs(f[elastic] / modes.frequencies_hz[elastic] - 1.0)))
    print(f"5. scipy on the exported M, K: largest relative difference to geardyn {worst:.1e}")
    plt.close("all")
    print(f"figures written to {out}")


if __name__ == "__main__":  # the sweep's worker processes import this file
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("results/python"))
