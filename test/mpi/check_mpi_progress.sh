#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# Under mpirun rank 0's standard error is no terminal: --progress shows the progress
# line anyway (items done of the total, the percentage), and the run succeeds.
#
# Usage: check_mpi_progress.sh MPIEXEC N MPI_PROGRAM SCENE OUTPUT_DIR
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mpiexec="$1" ranks="$2" program="$3" scene="$4" out="$5"
rm -rf "$out"
err="$(bash "$here/run_mpi.sh" "$mpiexec" "$ranks" "$program" "$scene" --progress -o "$out" \
  2>&1 >/dev/null)" || { echo "FAIL: the run failed: $err" >&2; exit 1; }
if ! printf '%s' "$err" | tr '\r' '\n' | grep -qE '^sweep: [0-9]+/100000 \([0-9]+%\)'; then
  echo "FAIL: no progress line on standard error: $err" >&2
  exit 1
fi
echo "progress shown: $(printf '%s' "$err" | tr '\r' '\n' | grep -cE '^sweep: ') lines"
