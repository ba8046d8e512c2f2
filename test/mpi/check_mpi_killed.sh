#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# A rank killed in the middle of a run under MPI (2 ranks): the run fails (exit code
# not 0, mpirun names the rank that died) and leaves no file that looks complete
# (only .partial files and the checkpoints of sweeps, if any). The rank killed is rank 1, found among the children
# of the mpirun this script started and killed by its process id.
#
# Usage: check_mpi_killed.sh MPIEXEC MPI_PROGRAM SCENE WORK_DIR
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mpiexec="$1" program="$2" scene="$3" work="$4"

rm -rf "$work"
mkdir -p "$work"
bash "$here/run_mpi.sh" "$mpiexec" 2 "$program" "$scene" -q -o "$work/results" \
  > "$work/stdout" 2> "$work/stderr" &
launcher=$!
victim=""
for _ in $(seq 1 400); do
  for child in $(pgrep -P "$launcher" 2>/dev/null); do
    if tr '\0' '\n' < "/proc/$child/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=1"; then
      victim="$child"
    fi
  done
  # killed once the results directory exists: rank 0 is at work
  if [ -n "$victim" ] && [ -d "$work/results" ]; then
    break
  fi
  sleep 0.05
done
if [ -z "$victim" ]; then
  echo "FAIL: rank 1 of the run was not found" >&2
  wait "$launcher"
  exit 1
fi
kill -KILL "$victim"
wait "$launcher"
code=$?
cat "$work/stderr"
if [ "$code" -eq 0 ]; then
  echo "FAIL: the run succeeded although rank 1 was killed" >&2
  exit 1
fi
if ! grep -qi "rank 1" "$work/stderr"; then
  echo "FAIL: the error does not name rank 1" >&2
  exit 1
fi
if [ -d "$work/results" ]; then
  complete="$(cd "$work/results" && ls -A | grep -vE '\.(partial|checkpoint)$' || true)"
  if [ -n "$complete" ]; then
    echo "FAIL: files that look complete were left: $complete" >&2
    exit 1
  fi
fi
echo "failed as expected (exit code $code), nothing left that looks complete"
