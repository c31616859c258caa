"""Shared helpers of the Python package's tests: the geardyn command (GEARDYN_CLI, set by ctest)
as the independent reference of every binding, and a report comparison."""

from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
from typing import Any

import pytest

CLI = os.environ.get("GEARDYN_CLI") or shutil.which("geardyn")

# Keys whose values are wall-clock measurements: they differ between any two runs.
TIMING_KEYS = ("wall_time", "_time_s")


def run_cli(*args: str) -> subprocess.CompletedProcess[str]:
    if CLI is None:
        pytest.skip("the geardyn command is not built (GEARDYN_CLI unset)")
    return subprocess.run([CLI, *args], capture_output=True, text=True, check=False)


def cli_json(*args: str) -> dict[str, Any]:
    """`geardyn ARGS --json`, parsed; the exit code is returned as "_exit_code"."""
    done = run_cli(*args, "--json")
    assert done.returncode in (0, 1), done.stderr
    report = json.loads(done.stdout)
    report["_exit_code"] = done.returncode
    return report


def cli_error(*args: str) -> str:
    """The message of a `geardyn` run that must fail with exit code 2 (bad input)."""
    done = run_cli(*args)
    assert done.returncode == 2, (done.returncode, done.stdout, done.stderr)
    text = done.stderr.strip()
    return text.removeprefix("geardyn: error: ")


def assert_same(a: Any, b: Any, path: str = "", rel: float = 1e-12) -> None:
    """Recursive equality of two JSON values: floats to `rel` (the same computation in two
    processes agrees to round-off), timing keys skipped."""
    if isinstance(a, dict) and isinstance(b, dict):
        keys = {k for k in set(a) | set(b) if not k.startswith("_")
                and not any(t in k for t in TIMING_KEYS)}
        for k in sorted(keys):
            assert k in a and k in b, f"{path}.{k}: only in {'python' if k in a else 'cli'}"
            if k == "counters":
                continue  # counters include timings of parallel work (threads, evaluations)
            assert_same(a[k], b[k], f"{path}.{k}", rel)
        return
    if isinstance(a, list) and isinstance(b, list):
        assert len(a) == len(b), f"{path}: {len(a)} != {len(b)} entries"
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, f"{path}[{i}]", rel)
        return
    if isinstance(a, float) or isinstance(b, float):
        assert isinstance(a, (int, float)) and isinstance(b, (int, float)), f"{path}: {a} {b}"
        assert math.isclose(a, b, rel_tol=rel, abs_tol=1e-300), f"{path}: {a!r} != {b!r}"
        return
    assert a == b, f"{path}: {a!r} != {b!r}"
