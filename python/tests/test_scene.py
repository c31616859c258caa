"""Scenes from Python: built-ins, files, TOML strings, dicts, overrides, pickling, and the
reader's errors with the command's messages."""

from __future__ import annotations

import pickle
import tomllib

import numpy as np
import pytest

import geardyn
from conftest import cli_error, run_cli


def test_builtin_scenes_are_the_commands():
    listed = run_cli("scenes").stdout.split()
    assert ["builtin:" + n for n in geardyn.builtin_scenes()] == listed


@pytest.mark.parametrize("name", geardyn.builtin_scenes())
def test_a_dict_of_the_builtins_text_is_the_same_scene(name):
    builtin = geardyn.Scene.builtin(name)
    data = tomllib.loads(builtin.text)
    from_dict = geardyn.Scene.from_dict(data, name="dict")
    # The writer's TOML reads back to the same tables (an independent reader: tomllib).
    assert tomllib.loads(geardyn.to_toml(data)) == data
    a = geardyn.modes(builtin, num_modes=6)
    b = geardyn.modes(from_dict, num_modes=6)
    np.testing.assert_array_equal(a.frequencies_hz, b.frequencies_hz)


def test_file_and_string_scenes_equal_the_builtin(tmp_path):
    text = geardyn.Scene.builtin("helical-pair").text
    path = tmp_path / "pair.toml"
    path.write_text(text)
    f = geardyn.modes(geardyn.Scene.from_file(path)).frequencies_hz
    s = geardyn.modes(geardyn.Scene.from_toml(text)).frequencies_hz
    b = geardyn.modes("builtin:helical-pair").frequencies_hz
    np.testing.assert_array_equal(f, b)
    np.testing.assert_array_equal(s, b)
    assert geardyn.Scene.from_file(path).source == str(path)


def test_overrides_as_dict_and_strings_equal_the_commands_set():
    base = geardyn.Scene.builtin("kahraman-blankenship-rig")
    a = base.with_overrides({"gear.pinion.mass": 3.5, "gear.wheel.face_width": 0.025})
    b = base.with_overrides(["gear.pinion.mass=3.5", "gear.wheel.face_width=0.025"])
    assert a.overrides == b.overrides
    ours = geardyn.modes(a).frequencies_hz
    from conftest import cli_json
    theirs = cli_json("modes", "builtin:kahraman-blankenship-rig", "--set", "gear.pinion.mass=3.5",
                      "--set", "gear.wheel.face_width=0.025")["frequencies_hz"]
    np.testing.assert_allclose(ours, theirs, rtol=1e-14)
    assert not np.array_equal(ours, geardyn.modes(base).frequencies_hz)  # the override acts


def test_a_scene_pickles_as_its_recipe():
    s = geardyn.Scene.from_toml(geardyn.Scene.builtin("helical-pair").text, name="x",
                                overrides={"operating_point.speed_rpm": 900})
    s.handle()
    t = pickle.loads(pickle.dumps(s))
    assert t == s and t._handle is None
    assert t.mesh_frequency_hz == pytest.approx(s.mesh_frequency_hz, rel=1e-15)
    assert s.mesh_frequency_hz == pytest.approx(900 / 60 * s.to_dict()["gear"][0]["teeth"])


def test_scene_errors_carry_the_readers_message_and_fields():
    with pytest.raises(geardyn.SceneError) as e:
        geardyn.Scene.builtin("helical-pair", {"gear.pinion.teeth": -5}).handle()
    assert str(e.value) == cli_error("modes", "builtin:helical-pair", "--set",
                                     "gear.pinion.teeth=-5")
    assert e.value.key == "gear.pinion.teeth" and e.value.line == 0
    assert "positive integer" in e.value.reason and e.value.override == "gear.pinion.teeth=-5"
    assert isinstance(e.value, geardyn.InputError) and isinstance(e.value, ValueError)
    with pytest.raises(geardyn.SceneError) as e:
        geardyn.Scene.builtin("nope")
    assert str(e.value) == cli_error("modes", "builtin:nope")


def test_a_bad_file_names_file_line_and_key(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('title = "x"\n\n[[gear]]\nname = "pinion"\nteeth = -3\n')
    with pytest.raises(geardyn.SceneError) as e:
        geardyn.Scene.from_file(path)
    assert str(e.value) == cli_error("modes", str(path))
    assert str(e.value).startswith(f"{path}:")
    with pytest.raises(geardyn.SceneError) as e:
        geardyn.Scene.from_file(tmp_path / "missing.toml")
    assert str(e.value) == cli_error("modes", str(tmp_path / "missing.toml"))


def test_values_that_toml_cannot_hold_are_refused():
    with pytest.raises(geardyn.InputError, match="not a finite number"):
        geardyn.Scene.builtin("helical-pair", {"operating_point.torque": float("nan")})
    with pytest.raises(geardyn.InputError, match="not a TOML value"):
        geardyn.Scene.builtin("helical-pair", {"operating_point.torque": object()})
