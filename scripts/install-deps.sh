#!/usr/bin/env bash
# Installs the Debian packages geardyn needs, only those that are missing (the C++ build, and the
# Python package with what its tests and sweeps use).
# --clang (or --fuzz) also installs clang and its sanitizer and libFuzzer runtimes: the sanitized
# test build (scripts/run-tests.sh) and the fuzzers (scripts/run-fuzzers.sh).
set -euo pipefail
packages=(build-essential cmake ninja-build pkg-config libeigen3-dev libarpack2-dev liblapack-dev libfftw3-dev libgsl-dev
          libgtest-dev libgmock-dev libbenchmark-dev libtomlplusplus-dev libcli11-dev
          nlohmann-json3-dev
          # The Python package (python/, docs/python.md): pybind11 and the interpreter Debian's
          # numpy, scipy, pandas, Dask distributed, matplotlib and pytest belong to.
          pybind11-dev python3-dev python3-numpy python3-scipy python3-pandas python3-distributed
          python3-matplotlib python3-pytest python3-venv python3-pip python3-setuptools)
for arg in "$@"; do
  case "$arg" in
    --clang | --fuzz) packages+=(clang libclang-rt-14-dev) ;;
    *) echo "install-deps.sh: unknown argument '$arg' (known: --clang, --fuzz)" >&2; exit 2 ;;
  esac
done
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "geardyn: installing missing Debian packages: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
