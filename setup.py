"""Builds the _geardyn extension with the project's CMake for `pip install .` (pyproject.toml).

Environment:
    GEARDYN_BUILD_DIR  an existing geardyn build tree configured with -DGEARDYN_BUILD_PYTHON=ON
                       (e.g. build/test of scripts/run-tests.sh): only its target geardyn_python
                       is built and its extension installed, no second configure or cold build.
                       Unset: a Release tree in build/python-pip (libraries and extension only).
    CMAKE_BUILD_PARALLEL_LEVEL  build jobs (default: the number of CPUs).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name: str) -> None:
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        given = os.environ.get("GEARDYN_BUILD_DIR")
        build = Path(given).resolve() if given else ROOT / "build" / "python-pip"
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        if not (build / "CMakeCache.txt").exists():
            if given:
                raise RuntimeError(f"GEARDYN_BUILD_DIR={given}: not a configured CMake build tree")
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), *generator,
                            "-DCMAKE_BUILD_TYPE=Release", "-DGEARDYN_BUILD_PYTHON=ON",
                            "-DGEARDYN_BUILD_TESTS=OFF", "-DGEARDYN_BUILD_EXAMPLES=OFF",
                            f"-DPython_EXECUTABLE={sys.executable}"], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "geardyn_python", "-j", jobs],
                       check=True)
        built = sorted((build / "python" / "geardyn").glob("_geardyn*.so"))
        if not built:
            raise RuntimeError(f"{build}: the build made no _geardyn extension (configured "
                               "without -DGEARDYN_BUILD_PYTHON=ON?)")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)


setup(ext_modules=[CMakeExtension("geardyn._geardyn")], cmdclass={"build_ext": CMakeBuild})
