"""`pip install .` from the checkout into a fresh virtual environment gives a working package
(pyproject.toml + setup.py; the extension of the test build tree is reused through
GEARDYN_BUILD_DIR, so this does not compile geardyn a second time)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE = os.environ.get("GEARDYN_SOURCE_DIR")
BUILD = os.environ.get("GEARDYN_BUILD_DIR")


@pytest.mark.skipif(not SOURCE or not BUILD, reason="run by ctest (GEARDYN_SOURCE_DIR, _BUILD_DIR)")
def test_pip_install_into_a_venv(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    python = venv / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["GEARDYN_BUILD_DIR"] = BUILD
    done = subprocess.run([str(python), "-m", "pip", "install", "--no-build-isolation",
                           "--no-index", "--no-deps", "-q", SOURCE], env=env,
                          capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    check = subprocess.run(
        [str(python), "-c",
         "import geardyn, json; r = geardyn.modes('builtin:helical-pair'); "
         "print(json.dumps([geardyn.__file__, r.summary.status, float(r.frequencies_hz[1])]))"],
        env=env, capture_output=True, text=True, cwd=tmp_path)
    assert check.returncode == 0, check.stderr
    import json
    location, status, f1 = json.loads(check.stdout)
    assert Path(location).is_relative_to(venv), location  # the installed copy, not the tree
    assert status == "success"
    import geardyn
    assert f1 == float(geardyn.modes("builtin:helical-pair").frequencies_hz[1])
