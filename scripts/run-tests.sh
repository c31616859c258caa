#!/usr/bin/env bash
# The whole test suite on a fresh machine: install dependencies, build everything with tests and
# examples, run ctest. Arguments go to ctest (e.g. -L unit, -R Floquet, -LE stress).
#
# The suite is built with clang (-O2 without debug information, build/test): clang compiles
# geardyn's Eigen-heavy code in about half of GCC's time (docs/benchmarks.md "Build and CI time").
#
# Environment:
#   CXX=g++                             another compiler (GEARDYN_BUILD_DIR apart from clang's)
#   GEARDYN_WARNINGS_AS_ERRORS=ON       warnings are errors (CI sets it)
#   GEARDYN_SANITIZE=address,undefined  the suite built with ASan + UBSan (-O1) in build/sanitize:
#                                       any report fails the test that triggered it
#   GEARDYN_BUILD_DIR=DIR               build directory (default build/test, build/sanitize)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh" --clang
sanitize="${GEARDYN_SANITIZE:-}"
flags=(-DCMAKE_CXX_COMPILER="${CXX:-clang++}" -DCMAKE_BUILD_TYPE=Release)
if [ -n "$sanitize" ]; then
  build="${GEARDYN_BUILD_DIR:-$root/build/sanitize}"
  # -O1: ASan's advice (usable speed, exact reports).
  flags+=("-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" -DGEARDYN_SANITIZE="$sanitize")
  export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}"
  export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
else
  build="${GEARDYN_BUILD_DIR:-$root/build/test}"
  # -O2 without debug information: the tests need the speed, not a debugger (a -g build of the
  # suite writes ~26 GB of executables and links for minutes).
  flags+=("-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG")
fi
generator=()
if [ ! -f "$build/CMakeCache.txt" ] && command -v ninja > /dev/null; then generator=(-G Ninja); fi
mkdir -p "$build"
cmake -S "$root" -B "$build" "${generator[@]}" "${flags[@]}" -DGEARDYN_BUILD_TESTS=ON \
      -DGEARDYN_BUILD_EXAMPLES=ON -DGEARDYN_WARNINGS_AS_ERRORS="${GEARDYN_WARNINGS_AS_ERRORS:-OFF}"
cmake --build "$build" -j"$(nproc)"
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" "$@"
