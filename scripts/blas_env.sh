#!/usr/bin/env bash
# Prints the BLAS environment a needlefem build should start with on this machine, as shell
# `export` lines to eval:
#   eval "$(scripts/blas_env.sh [build/needlefem])"
# OpenBLAS reads OPENBLAS_CORETYPE only when it loads. On a CPU model it does not know it falls
# back to generic kernels; needlefem then names the kernels to export in a note on stderr
# (integration/blas_threads.hpp holds the rule; docs/speed.md the measurements). Prints nothing
# where OpenBLAS needs no help or OPENBLAS_CORETYPE is already set.
set -euo pipefail
exe=${1:-$(cd "$(dirname "$0")/.." && pwd)/build/needlefem}
[ -n "${OPENBLAS_CORETYPE:-}" ] && exit 0
core=$({ env -u OPENBLAS_CORETYPE "$exe" --version 2>&1 >/dev/null || true; } |
  sed -n 's/^needlefem: note: .*export OPENBLAS_CORETYPE=\([A-Za-z0-9_]*\).*/\1/p' | head -n 1)
[ -n "$core" ] && echo "export OPENBLAS_CORETYPE=$core"
exit 0
