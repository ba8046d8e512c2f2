#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# A run under MPI with N ranks whose results directory cannot be created (its parent
# is a file: root cannot write there either) fails with exit code 1, names the
# directory, ends every rank (no hang: CTest's timeout) and leaves nothing behind.
#
# Usage: check_mpi_fault.sh MPIEXEC N MPI_PROGRAM SCENE WORK_DIR
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mpiexec="$1" ranks="$2" program="$3" scene="$4" work="$5"

rm -rf "$work"
mkdir -p "$work"
: > "$work/a-file"
bash "$here/run_mpi.sh" "$mpiexec" "$ranks" "$program" "$scene" -q \
  -o "$work/a-file/results" > "$work/stdout" 2> "$work/stderr"
code=$?
cat "$work/stderr"
if [ "$code" -ne 1 ]; then
  echo "FAIL: exit code $code, expected 1" >&2
  exit 1
fi
if ! grep -q "a-file/results: cannot create the results directory" "$work/stderr"; then
  echo "FAIL: the error does not name the results directory" >&2
  exit 1
fi
left="$(cd "$work" && ls -A)"
if [ "$left" != "a-file stderr stdout" ] && [ "$left" != "$(printf 'a-file\nstderr\nstdout')" ]; then
  echo "FAIL: left behind: $left" >&2
  exit 1
fi
echo "failed as expected with $ranks ranks"
