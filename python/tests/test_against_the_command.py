"""Every binding against the geardyn command for the same input: the result's ``report`` is the
command's --json output (timings aside), its ``text`` the command's text, its numpy arrays the
report's numbers, and ``exit_code`` the command's exit code."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import geardyn
from conftest import assert_same, cli_json, run_cli

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
RIG = "builtin:kahraman-blankenship-rig"
PAIR = "builtin:helical-pair"
SLICES = ["mesh.pinion-wheel.model=slices", "mesh.pinion-wheel.center_distance=0.1502",
          "mesh.pinion-wheel.damping_ratio=0.05"]


def sets(overrides):
    return [a for o in overrides for a in ("--set", o)]


@pytest.mark.parametrize("scene", [PAIR, RIG, "builtin:planetary-lin-parker",
                                   "builtin:geared-shafts"])
def test_modes(scene):
    py = geardyn.modes(scene, num_modes=10, shapes=True, damped=True)
    cli = cli_json("modes", scene, "--modes", "10", "--shapes", "--damped")
    assert_same(py.report, cli)
    assert py.exit_code == cli["_exit_code"]
    np.testing.assert_array_equal(py.frequencies_hz, cli["frequencies_hz"])
    np.testing.assert_array_equal(py.shapes, np.array(cli["shapes"]).T)
    assert py.labels == [m["label"] for m in cli["modes"]]
    assert py.dof_names == cli["dof_names"]
    assert py.summary.status == cli["status"] and py.method_used == cli["method_used"]
    text = run_cli("modes", scene, "--modes", "10", "--shapes", "--damped").stdout
    assert py.text == text


@pytest.mark.parametrize("scene", [PAIR, "builtin:planetary-lin-parker"])
def test_modes_loaded(scene):
    py = geardyn.modes(scene, num_modes=12, loaded=True)
    cli = cli_json("modes", scene, "--modes", "12", "--loaded")
    assert_same(py.report, cli)
    assert py.exit_code == cli["_exit_code"] == 0
    np.testing.assert_array_equal(py.frequencies_hz, cli["frequencies_hz"])
    # The preload is the static mesh force's: one entry per mesh, compressive.
    assert len(py.report["mesh_preload"]) == len(geardyn.info(scene).report["meshes"])
    assert all(p["force_n"] > 0 for p in py.report["mesh_preload"])
    assert run_cli("modes", scene, "--modes", "12", "--loaded").stdout == py.text


@pytest.mark.parametrize("scene,extra", [(PAIR, []), (RIG, []),
                                         ("builtin:kahraman-singh-oscillator", [])])
def test_floquet(scene, extra):
    py = geardyn.floquet(scene)
    cli = cli_json("floquet", scene)
    assert_same(py.report, cli)
    assert py.exit_code == cli["_exit_code"]
    lam = np.array([m["re"] + 1j * m["im"] for m in cli["multipliers"]])
    np.testing.assert_allclose(py.multipliers, lam, rtol=1e-15, atol=0)
    assert py.stable == cli["stable"] and py.verdict == cli["verdict"]
    assert py.max_abs_multiplier == pytest.approx(cli["max_abs_multiplier"], rel=1e-15)


def test_an_undetermined_floquet_verdict_is_reported_as_the_command_reports_it():
    # 1 rpm: Magnus would need more than 65 536 steps per period; the multipliers are NaN.
    over = ["operating_point.speed_rpm=1"]
    py = geardyn.floquet(geardyn.Scene.builtin("helical-pair", over))
    cli = cli_json("floquet", PAIR, *sets(over))
    assert_same(py.report, cli)  # null, not NaN, in the report
    assert py.report["max_abs_multiplier"] is None and py.stable is None
    assert py.verdict == "undetermined" and py.exit_code == cli["_exit_code"] == 1
    assert py.summary.status == "numerical_issue" and np.isnan(py.max_abs_multiplier)


def test_floquet_method_options_reach_the_library():
    py = geardyn.floquet(RIG, method="hill", tolerance=1e-8)
    cli = cli_json("floquet", RIG, "--method", "hill", "--tolerance", "1e-8")
    assert_same(py.report, cli)
    assert py.method_used == "hill"


def test_linear_hb_with_verdicts():
    py = geardyn.hb(RIG, mesh_frequency=(2000, 3400, 8), harmonics=16)
    cli = cli_json("hb", RIG, "--mesh-frequency", "2000:3400:8", "--harmonics", "16")
    assert_same(py.report, cli)
    assert not py.nonlinear and py.exit_code == cli["_exit_code"]
    np.testing.assert_array_equal(py.mesh_frequency_hz, [p["mesh_frequency_hz"]
                                                         for p in cli["points"]])
    rms = [p["meshes"][0]["rms_dte_m"] for p in cli["points"]]
    np.testing.assert_array_equal(py.rms_dte_m["pinion-wheel"], rms)
    verdicts = [{"stable": 1.0, "unstable": 0.0}[p["stability"]["verdict"]] for p in cli["points"]]
    np.testing.assert_array_equal(py.stable, verdicts)


def test_nonlinear_hb_trace():
    overrides = SLICES
    scene = geardyn.Scene.builtin("kahraman-blankenship-rig", overrides)
    py = geardyn.hb(scene, mesh_frequency="2000:3500:30", branch_search=0)
    cli = cli_json("hb", RIG, *sets(overrides), "--mesh-frequency", "2000:3500:30",
                   "--branch-search", "0")
    assert py.nonlinear
    assert_same(py.report, cli, rel=1e-9)
    assert len(py.mesh_frequency_hz) == len(cli["points"]) > 30
    np.testing.assert_allclose(py.rms_dte_m["pinion-wheel"],
                               [p["meshes"][0]["rms_dte_m"] for p in cli["points"]], rtol=1e-9)
    assert py.jumps == cli["jumps"]


def test_nonlinear_quasi_periodic_hb_on_the_two_stage_train():
    """Slice meshes on a train with two mesh frequencies: the nonlinear HB on the torus."""
    path = str(EXAMPLES / "multi-stage" / "wind-turbine-two-stage.toml")
    overrides = ["mesh.sun-planet.model=slices", "mesh.planet-ring.model=slices",
                 "mesh.hs-pinion-hs-wheel.model=slices"]
    py = geardyn.hb(geardyn.Scene.from_file(path, overrides), mesh_frequency=208.37, harmonics=4)
    cli = cli_json("hb", path, *sets(overrides), "--mesh-frequency", "208.37", "--harmonics", "4")
    assert py.nonlinear and cli["mode"] == "nonlinear, quasi-periodic"
    assert_same(py.report, cli, rel=1e-9)
    rows = cli["points"][0]["meshes"]
    assert all(m["contact_loss_fraction"] == 0.0 for m in rows)
    np.testing.assert_allclose(py.rms_dte_m["hs-pinion-hs-wheel"], [rows[0]["rms_dte_m"]],
                               rtol=1e-9)


def test_stability_chart_from_a_text_scene_equals_the_file_chart(tmp_path):
    text = geardyn.Scene.builtin("kahraman-singh-oscillator").text
    path = tmp_path / "osc.toml"
    path.write_text(text)
    x, y = "oscillator.frequency_ratio=0.5:2.5:21", "oscillator.alpha=0:0.6:7"
    py = geardyn.stability_chart(geardyn.Scene.from_toml(text, name=str(path)), x=x, y=y,
                                 threads=1)
    cli = cli_json("stability-chart", str(path), "--x", x, "--y", y, "--threads", "1")
    assert_same(py.report, cli)
    assert py.max_abs_multiplier.shape == (7, 21)
    assert py.report["num_unstable_points"] == int((py.stable == 0.0).sum()) > 0
    assert py.regions and py.regions[0]["label"] == cli["regions"][0]["label"]


def test_mesh_tables_equal_the_commands_csv(tmp_path):
    py = geardyn.mesh(PAIR, samples=90)
    run_cli("mesh", PAIR, "--samples", "90", "--out", str(tmp_path))
    cli = json.loads((tmp_path / "mesh.json").read_text())
    assert_same(py.report, cli)
    table = np.genfromtxt(tmp_path / "mesh_pinion-wheel.csv", delimiter=",", names=True)
    t = py.meshes["pinion-wheel"]
    # The CSV prints 12 significant digits.
    np.testing.assert_allclose(t.cycle, table[table.dtype.names[0]], rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(t.stiffness, table[table.dtype.names[1]], rtol=1e-11)
    assert t.stiffness.shape == (90,)


def test_info():
    py = geardyn.info(RIG)
    assert_same(py.report, cli_json("info", RIG))
    assert py.text == run_cli("info", RIG).stdout


def test_simulate_single_run_and_its_histories(tmp_path):
    scene = "builtin:kahraman-singh-oscillator"
    py = geardyn.simulate(scene, out_dir=tmp_path)
    cli = cli_json("simulate", scene)
    assert_same(py.report, cli, rel=1e-9)
    assert py.exit_code == cli["_exit_code"] == 0
    assert py.rms_dte_m["oscillator"][0] == pytest.approx(
        cli["points"][0]["meshes"][0]["rms_dte_m"], rel=1e-9)
    # The histories are the rows of simulate_dte.csv (written by out_dir, as --out).
    table = np.genfromtxt(tmp_path / "simulate_dte.csv", delimiter=",", names=True)
    assert len(py.time_s) == len(table) == len(py.dte_m["oscillator"])
    np.testing.assert_allclose(py.time_s, table[table.dtype.names[0]], rtol=1e-12)
    rms = np.sqrt(np.mean((py.dte_m["oscillator"] - py.dte_m["oscillator"].mean()) ** 2))
    assert rms == pytest.approx(py.rms_dte_m["oscillator"][0], rel=2e-2)


def test_simulate_independent_speeds():
    scene = "builtin:kahraman-singh-oscillator"
    py = geardyn.simulate(scene, mesh_frequency=(0.6, 1.4, 3), threads=1)
    cli = cli_json("simulate", scene, "--mesh-frequency", "0.6:1.4:3", "--threads", "1")
    assert_same(py.report, cli, rel=1e-9)
    np.testing.assert_allclose(py.mesh_frequency_hz, [0.6, 1.0, 1.4])
    assert py.time_s.size == 0 and py.dte_m == {}


def test_compare():
    scene = "builtin:kahraman-singh-oscillator"
    py = geardyn.compare(scene)
    cli = cli_json("compare", scene)
    assert_same(py.report, cli, rel=1e-9)
    assert py.levels == [lv["level"] for lv in cli["levels"]]
    assert py.references == cli["references"]
    np.testing.assert_array_equal(py.frequencies_hz, cli["frequencies_hz"])


def test_out_dir_writes_the_commands_files(tmp_path):
    a, b = tmp_path / "py", tmp_path / "cli"
    geardyn.floquet(PAIR, out_dir=a)
    run_cli("floquet", PAIR, "--out", str(b))
    assert sorted(p.name for p in a.iterdir()) == sorted(p.name for p in b.iterdir())
    assert (a / "multipliers.csv").read_text() == (b / "multipliers.csv").read_text()
