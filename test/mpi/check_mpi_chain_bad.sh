#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# hcimpact_mpi_chain on a scene it must refuse: exit status 2 (also through mpirun), the
# expected message on standard error, no output file.
#
# Usage: check_mpi_chain_bad.sh MPIEXEC N PROGRAM SCENE OUTPUT_DIR MESSAGE
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mpiexec="$1" ranks="$2" program="$3" scene="$4" out="$5" message="$6"

rm -rf "$out"
mkdir -p "$out"
bash "$here/run_mpi.sh" "$mpiexec" "$ranks" "$program" "$scene" "$out/state.csv" \
  > "$out/stdout" 2> "$out/stderr"
status=$?
if [ "$status" -ne 2 ]; then
  echo "FAIL: exit status $status, expected 2" >&2
  cat "$out/stderr" >&2
  exit 1
fi
if ! grep -qF "error: $message" "$out/stderr"; then
  echo "FAIL: no 'error: $message' on standard error:" >&2
  cat "$out/stderr" >&2
  exit 1
fi
if [ -e "$out/state.csv" ]; then
  echo "FAIL: a state file was left behind" >&2
  exit 1
fi
echo "refused with status 2: $message"
