#!/usr/bin/env bash
# Install what is missing (including the test-only packages: ParaView, h5py), build, and run
# the whole test suite with ctest. Exit code is ctest's.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh" --tests
cd "${NEEDLEFEM_BUILD_DIR:-$root/build}"
# OpenMPI refuses to start as root unless told; CI and the quick start run as root.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# ctest runs one test per core; one BLAS thread and one OpenMP thread each keep the threaded
# OpenBLAS and the element loops from oversubscribing them. (nproc would report
# OMP_NUM_THREADS, so it reads the cores without it.)
cores=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
# OpenBLAS's kernels for this CPU where it does not know the model (scripts/blas_env.sh).
eval "$("$root/scripts/blas_env.sh" "$PWD/needlefem")"
# The tests' scene meshes go to a cache in the build tree, emptied here (not the user's
# ~/.cache/needlefem: mesh/mesh_cache.hpp); tests that check the cache use their own.
export NEEDLEFEM_MESH_CACHE=$PWD/mesh-cache
rm -rf "$NEEDLEFEM_MESH_CACHE"
status=0
ctest --output-on-failure -j "$cores" | tee ctest_output.log || status=$?
if [ "$status" -ne 0 ]; then
  # CI keeps only the end of a long log: repeat each failed test's output (its last 60
  # lines, from ctest's own log) and then ctest's summary, so the reason is in that end.
  while read -r failed; do
    name=${failed#*:}
    echo "===== output of failed test $name ====="
    awk -v name="$name" '$0 ~ "^[0-9]+/[0-9]+ Test: " name "$" {on = 1; next}
      on && /^"[^"]*" end time:/ {exit} on' Testing/Temporary/LastTest.log | tail -n 60
  done < Testing/Temporary/LastTestsFailed.log
  echo "===== ctest summary ====="
  sed -n '/tests passed, /,$p' ctest_output.log
fi
exit "$status"
