"""Bad input raises InputError (a ValueError) with the C++ message, naming the option the
command line would name; numerical trouble is a status, never an exception."""

from __future__ import annotations

import math

import pytest

import geardyn
from conftest import cli_error

PAIR = "builtin:helical-pair"


@pytest.mark.parametrize("call,argv", [
    (lambda: geardyn.modes(PAIR, num_modes=0), ["modes", PAIR, "--modes", "0"]),
    (lambda: geardyn.floquet(PAIR, nev=0), ["floquet", PAIR, "--nev", "0"]),
    (lambda: geardyn.hb(PAIR, mesh_frequency="3:1:5"), ["hb", PAIR, "--mesh-frequency", "3:1:5"]),
    (lambda: geardyn.hb(PAIR, harmonics=0), ["hb", PAIR, "--harmonics", "0"]),
    (lambda: geardyn.stability_chart(PAIR, x="nope.path=0:1:3",
                                     y="operating_point.torque=1:2:2"),
     ["stability-chart", PAIR, "--x", "nope.path=0:1:3", "--y", "operating_point.torque=1:2:2"]),
    (lambda: geardyn.simulate(PAIR, sweep="up"), ["simulate", PAIR, "--sweep", "up"]),
])
def test_the_message_is_the_commands(call, argv):
    with pytest.raises(geardyn.InputError) as e:
        call()
    assert str(e.value) == cli_error(*argv)


@pytest.mark.parametrize("call,flag", [
    (lambda: geardyn.modes(PAIR, method="bogus"), "--method"),
    (lambda: geardyn.floquet(PAIR, method="bogus"), "--method"),
    (lambda: geardyn.floquet(PAIR, tolerance=math.nan), "--tolerance"),
    (lambda: geardyn.floquet(PAIR, tolerance=2.0), "--tolerance"),
    (lambda: geardyn.floquet(PAIR, max_approximant_period=20000), "--max-approximant-period"),
    (lambda: geardyn.floquet(PAIR, max_approximant_period=-1), "--max-approximant-period"),
    (lambda: geardyn.hb(PAIR, stability="sometimes"), "--stability"),
    (lambda: geardyn.hb(PAIR, branch_search=-1), "--branch-search"),
    (lambda: geardyn.stability_chart(PAIR, x="operating_point.speed_rpm=100:200:3",
                                     y="operating_point.torque=1:2:2", max_order=0), "--max-order"),
    (lambda: geardyn.stability_chart(PAIR, x="operating_point.speed_rpm=100:200:3",
                                     y="operating_point.torque=1:2:2", threads=-1), "--threads"),
    (lambda: geardyn.system_matrices(PAIR, harmonics=-1), "--harmonics"),
    (lambda: geardyn.compare(PAIR, levels="bogus"), "bogus"),
    (lambda: geardyn.hb(PAIR, mesh_frequency=(1, 2)), "mesh_frequency"),
])
def test_options_the_command_line_checks_are_checked_here_too(call, flag):
    # CLI11 checks these before the library sees them; from Python the library checks them.
    with pytest.raises(geardyn.InputError, match=flag.replace("-", r"\-")):
        call()


def test_an_oscillator_has_no_mesh_table():
    with pytest.raises(geardyn.InputError, match="oscillator scene has no gear mesh"):
        geardyn.mesh("builtin:kahraman-singh-oscillator")


def test_numerical_trouble_is_a_status_not_an_exception():
    # A 2-period cap on the steady-state search cannot reach steady state: not_converged.
    r = geardyn.simulate("builtin:kahraman-singh-oscillator", max_periods=2)
    assert r.exit_code == 1 and r.summary.status != "success" and not r.ok
    assert r.report["status"] == r.summary.status


def test_exception_classes():
    assert issubclass(geardyn.SceneError, geardyn.InputError)
    assert issubclass(geardyn.InputError, ValueError)
    assert issubclass(geardyn.InternalError, RuntimeError)
