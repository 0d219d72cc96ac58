#!/usr/bin/env bash
# Build (part of) the tree in build/, serialised with a lock so concurrent callers on this
# 2-core machine never run two compilers over the same build directory.
#   scripts/build.sh [target ...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${NEEDLEFEM_BUILD_DIR:-$root/build}
exec 9>/tmp/needlefem-build.lock
flock 9
[ -f "$build_dir/CMakeCache.txt" ] || cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$build_dir" -j "$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)" "${targets[@]}"
