"""examples/python/gear_study.py runs as documented and makes its five pictures; its own checks
(scipy's eigen solution of the exported matrices against geardyn's modes) hold."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

SOURCE = Path(os.environ.get("GEARDYN_SOURCE_DIR", Path(__file__).resolve().parents[2]))


def test_gear_study_example(tmp_path):
    script = SOURCE / "examples" / "python" / "gear_study.py"
    done = subprocess.run([sys.executable, str(script), str(tmp_path)], capture_output=True,
                          text=True, check=False)
    assert done.returncode == 0, done.stderr
    for name in ("mesh_stiffness", "modes", "campbell", "stability_chart", "frequency_response"):
        png = tmp_path / f"{name}.png"
        assert png.exists() and png.stat().st_size > 10_000, name
    difference = float(re.search(r"difference to geardyn ([0-9.e+-]+)", done.stdout).group(1))
    assert difference < 1e-9
    assert re.search(r"regions 2f_0/1", done.stdout)  # the principal tongue Ω = 2
    assert re.search(r"[1-9]\d* jump\(s\)", done.stdout)  # contact loss: a jump
