#!/usr/bin/env bash
# Install what is missing (including the test-only packages: ParaView, h5py), build, and run
# the whole test suite with ctest. Exit code is ctest's.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh" --tests
cd "${NEEDLEFEM_BUILD_DIR:-$root/build}"
# OpenMPI refuses to start as root unless told; CI and the quick start run as root.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# ctest runs one test per core; one BLAS thread each keeps the threaded OpenBLAS from
# oversubscribing them.
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
ctest --output-on-failure -j "$(nproc)"
