"""The plotting helpers draw what they promise (lines, shaded regions, labels) on the results."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import geardyn  # noqa: E402
from geardyn import plotting  # noqa: E402


def test_mesh_stiffness(tmp_path):
    mesh = geardyn.mesh("builtin:helical-pair")
    ax = plotting.plot_mesh_stiffness(mesh)
    line = ax.get_lines()[0]
    np.testing.assert_array_equal(line.get_ydata(), mesh.meshes["pinion-wheel"].stiffness)
    ax.figure.savefig(tmp_path / "k.png")
    plt.close("all")


def test_modes_and_campbell():
    modes = geardyn.modes("builtin:kahraman-blankenship-rig")
    ax = plotting.plot_modes(modes)
    widths = sorted(p.get_width() for p in ax.patches)
    np.testing.assert_allclose(widths, np.sort(modes.frequencies_hz))
    speeds = [1000.0, 2000.0, 3000.0]
    table = np.tile(modes.frequencies_hz[:4], (3, 1))
    ax = plotting.plot_campbell(speeds, table, mesh_hz_per_rpm=28 / 60, orders=(1, 2))
    assert len(ax.get_lines()) == 4 + 2
    order2 = ax.get_lines()[-1]
    np.testing.assert_allclose(order2.get_ydata(), 2 * 28 / 60 * np.array(speeds))
    plt.close("all")


def test_stability_chart_labels_every_region():
    chart = geardyn.stability_chart("builtin:kahraman-singh-oscillator",
                                    x="oscillator.frequency_ratio=0.5:2.5:41",
                                    y="oscillator.alpha=0:0.6:9", threads=1)
    ax = plotting.plot_stability_chart(chart)
    texts = [t.get_text() for t in ax.texts]
    assert texts == [r["label"] for r in chart.regions if (chart.region == chart.regions.index(r)).any()]
    assert len(texts) >= 1 and all(t for t in texts)
    assert len(ax.get_lines()) == len(chart.curves)
    plt.close("all")


def test_frequency_response_dashes_the_unstable_points():
    hb = geardyn.hb("builtin:kahraman-blankenship-rig", mesh_frequency=(2000, 3400, 15),
                    harmonics=16)
    ax = plotting.plot_frequency_response(hb)
    styles = {line.get_linestyle() for line in ax.get_lines()}
    assert (hb.stable == 0.0).any() and "--" in styles and "-" in styles
    drawn = sum(len(line.get_xdata()) for line in ax.get_lines())
    assert drawn >= len(hb.mesh_frequency_hz)
    plt.close("all")


def test_points_without_a_verdict_are_never_drawn_as_stable():
    hb = geardyn.hb("builtin:kahraman-blankenship-rig", mesh_frequency=(2000, 3400, 6),
                    harmonics=16, stability="none")
    assert np.isnan(hb.stable).all()
    ax = plotting.plot_frequency_response(hb)
    assert {line.get_linestyle() for line in ax.get_lines()} == {":"}
    plt.close("all")
