#!/usr/bin/env bash
# The whole test suite on a fresh machine: install dependencies, build everything with tests,
# examples and the Python package (build/test/python: PYTHONPATH=build/test/python imports
# geardyn), run ctest. Arguments go to ctest (e.g. -L unit, -R Floquet, -LE stress, -L python).
#
# The suite is built with clang (-O2 without debug information, build/test): clang compiles
# geardyn's Eigen-heavy code in about half of GCC's time (docs/benchmarks.md "Build and CI time").
#
# Environment:
#   CXX=g++                             another compiler (GEARDYN_BUILD_DIR apart from clang's)
#   GEARDYN_WARNINGS_AS_ERRORS=ON       warnings are errors (CI sets it)
#   GEARDYN_SANITIZE=address,undefined  the suite again against the libraries and the command
#                                       built with ASan + UBSan (-O2): the sanitized twins of the
#                                       same build (GEARDYN_SANITIZED_TWINS, docs/sanitizers.md),
#                                       tests "sanitized:<Suite>.<Case>"; any report fails the
#                                       test that triggered it. Without ctest arguments this is
#                                       the whole suite: the sanitized tests minus the slow
#                                       cross-checks of tests/sanitizer_skip.txt, which then run
#                                       plain. With arguments, the sanitized tests they select
#   GEARDYN_BUILD_DIR=DIR               build directory (default build/test)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh" --clang
sanitize="${GEARDYN_SANITIZE:-}"
compiler="${CXX:-clang++}"

# configure DIR FLAG...: a test build (tests and examples) in DIR.
configure() {
  local dir="$1"
  shift
  local generator=()
  if [ ! -f "$dir/CMakeCache.txt" ] && command -v ninja > /dev/null; then generator=(-G Ninja); fi
  mkdir -p "$dir"
  cmake -S "$root" -B "$dir" "${generator[@]}" -DCMAKE_CXX_COMPILER="$compiler" \
        -DCMAKE_BUILD_TYPE=Release "$@" -DGEARDYN_BUILD_TESTS=ON -DGEARDYN_BUILD_EXAMPLES=ON \
        -DGEARDYN_BUILD_PYTHON=ON \
        -DGEARDYN_WARNINGS_AS_ERRORS="${GEARDYN_WARNINGS_AS_ERRORS:-OFF}"
}
# -O2 without debug information: the tests need the speed, not a debugger (a -g build of the
# suite writes ~26 GB of executables and links for minutes).
plain_flags=("-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG")
build="${GEARDYN_BUILD_DIR:-$root/build/test}"

if [ -z "$sanitize" ]; then
  configure "$build" "${plain_flags[@]}" -DGEARDYN_SANITIZED_TWINS= -DGEARDYN_BUILD_FUZZERS=OFF
  cmake --build "$build" -j"$(nproc)"
  ctest --test-dir "$build" --output-on-failure -j"$(nproc)" "$@"
  exit
fi

# The sanitized twins: only the libraries and the command are compiled again (instrumented); each
# test's objects are linked a second time, against them. -O2, not ASan's usual -O1: at -O1 Eigen's
# small inline kernels are not inlined, and the sanitized tests ran 8–70 times slower than at -O2
# (KbRigJumps 891 s against 12.6 s; docs/benchmarks.md "Build and CI time").
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# With clang the libFuzzer targets are built too, from the twins (scripts/run-fuzzers.sh runs them
# when GEARDYN_FUZZ_BUILD_DIR is this build).
fuzzers=OFF
if "$compiler" --version 2> /dev/null | grep -q clang; then fuzzers=ON; fi
configure "$build" "${plain_flags[@]}" -DGEARDYN_SANITIZED_TWINS="$sanitize" \
          -DGEARDYN_BUILD_FUZZERS="$fuzzers"
cmake --build "$build" -j"$(nproc)"
if [ "$#" -gt 0 ]; then
  ctest --test-dir "$build" --output-on-failure -j"$(nproc)" -L '^sanitized$' "$@"
  exit
fi
skip="$(grep -v '^[[:space:]]*\(#\|$\)' "$root/tests/sanitizer_skip.txt" | paste -sd '|' -)"
if [ -z "$skip" ]; then
  ctest --test-dir "$build" --output-on-failure -j"$(nproc)" -L '^sanitized$'
  exit
fi
status=0
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" -L '^sanitized$' -E "$skip" || status=$?
echo "run-tests.sh: the tests of tests/sanitizer_skip.txt, plain"
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" -LE '^sanitized$' -R "$skip" || status=$?
exit "$status"
