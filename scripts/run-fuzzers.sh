#!/usr/bin/env bash
# Builds the libFuzzer targets of the input readers (tests/fuzz/, GEARDYN_BUILD_FUZZERS=ON, clang,
# ASan + UBSan) in build/fuzz and runs each one for a bounded time on a scratch copy of its seed
# corpus (the committed corpus never grows). Exit 1 on any crash, timeout, leak or out-of-memory,
# printing where libFuzzer saved the input. docs/fuzzing.md.
#
#   scripts/run-fuzzers.sh [SECONDS_PER_TARGET]      (default 60)
#
# Environment: GEARDYN_FUZZ_BUILD_DIR (default build/fuzz; a build with sanitized twins and the
# fuzzers, such as build/test after `GEARDYN_SANITIZE=address,undefined run-tests.sh`, is used as
# it is), GEARDYN_FUZZ_JOBS (build jobs, default nproc), GEARDYN_FUZZ_TARGETS (default
# "scene_reader mesh_tables"), GEARDYN_FUZZ_WORK_DIR (keep the grown corpora there instead of a
# deleted temporary directory).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -eq 0 ]; then
  echo "run-fuzzers.sh: SECONDS_PER_TARGET must be a positive integer, got '$seconds'" >&2
  exit 2
fi
"$root/scripts/install-deps.sh" --fuzz

build="${GEARDYN_FUZZ_BUILD_DIR:-$root/build/fuzz}"
targets=(${GEARDYN_FUZZ_TARGETS:-scene_reader mesh_tables})
if grep -q '^GEARDYN_SANITIZED_TWINS:STRING=.' "$build/CMakeCache.txt" 2> /dev/null &&
   grep -q '^GEARDYN_BUILD_FUZZERS:BOOL=ON' "$build/CMakeCache.txt"; then
  # A test build with sanitized twins and the fuzzers (GEARDYN_SANITIZE=... run-tests.sh): its
  # fuzz targets link the sanitized twins (-O2, NDEBUG); nothing is configured or compiled again.
  echo "run-fuzzers.sh: the fuzz targets of the sanitized twins in $build"
else
  launcher=()
  command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # -O1 without NDEBUG: Eigen's and GEARDYN_ASSERT's checks stay on (more bugs found), and the
  # sanitized Eigen code compiles much faster than at -O2 -g.
  cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None \
        "-DCMAKE_CXX_FLAGS=-O1 -gline-tables-only" -DGEARDYN_BUILD_FUZZERS=ON \
        -DGEARDYN_BUILD_TESTS=OFF -DGEARDYN_BUILD_APPS=OFF -DGEARDYN_BUILD_EXAMPLES=OFF \
        "${launcher[@]}"
fi
cmake --build "$build" -j"${GEARDYN_FUZZ_JOBS:-$(nproc)}" --target "${targets[@]/%/_fuzz}"

work="${GEARDYN_FUZZ_WORK_DIR:-}"
if [ -z "$work" ]; then
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
artifacts="$build/artifacts"
mkdir -p "$artifacts"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
for t in "${targets[@]}"; do
  corpus="$work/$t"
  mkdir -p "$corpus" "$artifacts/$t"
  cp "$root/tests/fuzz/corpus/$t"/* "$corpus"/
  if compgen -G "$root/tests/fuzz/regressions/$t/*" > /dev/null; then
    cp "$root/tests/fuzz/regressions/$t"/* "$corpus"/
  fi
  echo "=== $t: ${seconds}s, corpus $(ls "$corpus" | wc -l) files"
  log="$artifacts/$t.log"
  set +e
  "$build/fuzz/${t}_fuzz" "$corpus" -dict="$root/tests/fuzz/scene.dict" \
      -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=8192 \
      -artifact_prefix="$artifacts/$t/" -print_final_stats=1 > "$log" 2>&1
  rc=$?
  set -e
  tail -n 80 "$log"
  if [ "$rc" -ne 0 ]; then
    status=1
    echo "=== $t: FAILED (exit $rc; full log $log); inputs saved in $artifacts/$t/:"
    ls -l "$artifacts/$t"/ || true
    echo "    reproduce: $build/fuzz/${t}_fuzz <file>; add it to tests/fuzz/regressions/$t/ (docs/fuzzing.md)"
  else
    echo "=== $t: ok"
  fi
done
exit "$status"
