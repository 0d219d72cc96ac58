#!/usr/bin/env bash
# Install the Debian packages needlefem needs (only those missing), then configure and build.
# Idempotent: a second run checks dpkg, skips apt, and lets CMake rebuild only what changed.
#   scripts/setup.sh            core build dependencies + build
#   scripts/setup.sh --tests    also what the test suite needs (ParaView, h5py, xvfb, Chromium for the study report)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${NEEDLEFEM_BUILD_DIR:-$root/build}

core_packages=(build-essential cmake pkg-config petsc-dev libsundials-dev libmetis-dev libsuitesparse-dev libgmsh-dev
  libopenblas0-pthread libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libfmt-dev libgtest-dev)
test_packages=(python3-paraview python3-h5py python3-numpy python3-matplotlib xvfb xauth chromium)

packages=("${core_packages[@]}")
for arg in "$@"; do
  case "$arg" in
    --tests) packages+=("${test_packages[@]}") ;;
    *) echo "setup.sh: unknown option '$arg' (expected --tests)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" >/dev/null
"$root/scripts/build.sh"
# On a CPU model OpenBLAS does not know, the kernels to export before running (scripts/blas_env.sh).
blas=$("$root/scripts/blas_env.sh" "$build_dir/needlefem")
[ -z "$blas" ] || echo "setup: OpenBLAS does not know this CPU; before running needlefem: $blas"
