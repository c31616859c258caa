#!/usr/bin/env bash
# The whole test suite on a fresh machine: install dependencies, build everything with tests and
# examples, run ctest. GEARDYN_WARNINGS_AS_ERRORS=ON (set by CI) makes warnings errors.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
build="${GEARDYN_BUILD_DIR:-$root/build/test}"
mkdir -p "$build"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGEARDYN_BUILD_TESTS=ON \
      -DGEARDYN_BUILD_EXAMPLES=ON -DGEARDYN_WARNINGS_AS_ERRORS="${GEARDYN_WARNINGS_AS_ERRORS:-OFF}"
cmake --build "$build" -j"$(nproc)"
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" "$@"
