#!/usr/bin/env bash
# The main job on a fresh machine: install dependencies, build geardyn (Release), and run it on the
# built-in Kahraman–Blankenship rig (derived geometry and ISO stiffness; mesh parameters over one
# mesh period), writing the results to ./results (or $GEARDYN_OUT). The Python package is built
# beside the command (build/release/python; docs/python.md).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
build="${GEARDYN_BUILD_DIR:-$root/build/release}"
mkdir -p "$build"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DGEARDYN_BUILD_TESTS=OFF \
      -DGEARDYN_BUILD_EXAMPLES=OFF -DGEARDYN_BUILD_PYTHON=ON > "$build.configure.log" 2>&1 || { cat "$build.configure.log"; exit 1; }
cmake --build "$build" --target geardyn_cli geardyn_python -j"$(nproc)"
out="${GEARDYN_OUT:-$root/results}"
"$build/apps/geardyn" info builtin:kahraman-blankenship-rig --out "$out" "$@"
"$build/apps/geardyn" mesh builtin:kahraman-blankenship-rig --out "$out" "$@"
echo "geardyn: results written to $out"
echo "geardyn: Python package in $build/python (PYTHONPATH=$build/python /usr/bin/python3)"
