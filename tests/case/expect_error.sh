#!/usr/bin/env bash
# expect_error.sh REGEX COMMAND...: passes when COMMAND exits non-zero and prints exactly one
# line on stderr that matches the extended regular expression REGEX. Progress lines before it
# ("mesh: meshing ...", "mesh: from the mesh cache: ...", "run: t = ...") and notes ("needlefem:
# note: ...", e.g. on OpenBLAS's kernels) are not errors and are left out.
regex=$1; shift
stderr=$("$@" 2>&1 >/dev/null); status=$?
stderr=$(printf '%s\n' "$stderr" | grep -Ev '^mesh: meshing the |^mesh: meshed in |^mesh: from the mesh cache: |^run: +t = |^needlefem: note: ')
lines=$(printf '%s\n' "$stderr" | grep -c .)
if [ "$status" -eq 0 ]; then echo "FAIL: exit code 0 (expected non-zero)"; exit 1; fi
if [ "$lines" -ne 1 ]; then echo "FAIL: $lines lines on stderr (expected 1):"; echo "$stderr"; exit 1; fi
if ! printf '%s\n' "$stderr" | grep -Eq -- "$regex"; then echo "FAIL: stderr does not match /$regex/:"; echo "$stderr"; exit 1; fi
echo "ok: exit $status: $stderr"
