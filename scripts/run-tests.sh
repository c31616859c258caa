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
#   GEARDYN_SANITIZE=address,undefined  the suite built with ASan + UBSan (-O2) in build/sanitize:
#                                       any report fails the test that triggered it. Without
#                                       ctest arguments this is still the whole suite: the slow
#                                       cross-checks of tests/sanitizer_skip.txt run afterwards in
#                                       the plain build (build/test), which then builds only the
#                                       test executables that hold them
#   GEARDYN_BUILD_DIR=DIR               build directory (default build/test, build/sanitize)
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
        -DGEARDYN_WARNINGS_AS_ERRORS="${GEARDYN_WARNINGS_AS_ERRORS:-OFF}"
}
# -O2 without debug information: the tests need the speed, not a debugger (a -g build of the
# suite writes ~26 GB of executables and links for minutes).
plain_flags=("-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG")
plain_build="$root/build/test"

if [ -z "$sanitize" ]; then
  build="${GEARDYN_BUILD_DIR:-$plain_build}"
  configure "$build" "${plain_flags[@]}"
  cmake --build "$build" -j"$(nproc)"
  ctest --test-dir "$build" --output-on-failure -j"$(nproc)" "$@"
  exit
fi

# The sanitized suite. -O2, not ASan's usual -O1: at -O1 Eigen's small inline kernels are not
# inlined, and the sanitized tests ran 8–70 times slower than at -O2 (KbRigJumps 891 s against
# 12.6 s; docs/benchmarks.md "Build and CI time"), while -O1 saves only 9 % of the compile time.
build="${GEARDYN_BUILD_DIR:-$root/build/sanitize}"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
configure "$build" "${plain_flags[@]}" -DGEARDYN_SANITIZE="$sanitize"
cmake --build "$build" -j"$(nproc)"
if [ "$#" -gt 0 ]; then
  # A chosen set of tests: exactly what the arguments select, sanitized.
  ctest --test-dir "$build" --output-on-failure -j"$(nproc)" "$@"
  exit
fi
skip="$(grep -v '^[[:space:]]*\(#\|$\)' "$root/tests/sanitizer_skip.txt" | paste -sd '|' -)"
if [ -z "$skip" ]; then
  ctest --test-dir "$build" --output-on-failure -j"$(nproc)"
  exit
fi
status=0
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" -E "$skip" || status=$?

# The skipped tests in the plain build, which builds only their executables (and the libraries).
# ctest -N -V prints each test's command; its first word is the executable (a test executable of
# the build tree: the list holds GoogleTest cases only).
targets=()
while read -r exe; do
  case "$exe" in
    "$build"/*) targets+=("$(basename "$exe")") ;;
    *) echo "run-tests.sh: tests/sanitizer_skip.txt selects '$exe', not a test executable" >&2
       exit 2 ;;
  esac
done < <(ctest --test-dir "$build" -N -V -R "$skip" | sed -n 's/^[0-9]*: Test command: \([^ ]*\).*/\1/p' \
         | sort -u)
echo "run-tests.sh: the ${#targets[@]} executables of tests/sanitizer_skip.txt, in the plain build"
configure "$plain_build" "${plain_flags[@]}"
cmake --build "$plain_build" -j"$(nproc)" --target "${targets[@]}"
ctest --test-dir "$plain_build" --output-on-failure -j"$(nproc)" -R "$skip" || status=$?
exit "$status"
