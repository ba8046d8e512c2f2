#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# A sweep killed in the middle resumes from its checkpoint: the run is killed (with
# MPI: its rank 1, so that mpirun ends the job; without: the program itself) once the
# checkpoint holds some impacts; the checkpoint is left; a rerun into the same
# directory takes those impacts from it (its log says how many), computes the rest,
# removes the checkpoint and writes the same files, byte for byte, as a run in one go
# of the program built without MPI (all but log.txt).
#
# Usage: check_resume.sh MPIEXEC N PROGRAM SERIAL_PROGRAM SCENE WORK_DIR [OUTPUT]
#        (N = 0: PROGRAM is run alone, without mpirun, and killed itself; OUTPUT: the
#        output whose checkpoint is watched, sweep by default, or system_sweep)
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mpiexec="$1" ranks="$2" program="$3" serial="$4" scene="$5" work="$6" output="${7:-sweep}"
fail() { echo "FAIL: $*" >&2; exit 1; }

rm -rf "$work"
mkdir -p "$work"
"$serial" "$scene" -q -o "$work/reference" > /dev/null || fail "the reference run failed"

checkpoint="$work/results/$output.checkpoint"
bash "$here/run_mpi.sh" "$mpiexec" "$ranks" "$program" "$scene" -q -o "$work/results" \
  > "$work/first.stdout" 2> "$work/first.stderr" &
launcher=$!
victim=""
for _ in $(seq 1 1200); do
  if [ -f "$checkpoint" ] && [ "$(wc -l < "$checkpoint")" -ge 2 ]; then
    if [ "$ranks" -eq 0 ]; then
      victim="$launcher"
    else
      for child in $(pgrep -P "$launcher" 2>/dev/null); do
        if tr '\0' '\n' < "/proc/$child/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=1"; then
          victim="$child"
        fi
      done
    fi
    break
  fi
  kill -0 "$launcher" 2>/dev/null || break
  sleep 0.01
done
[ -n "$victim" ] || { wait "$launcher"; fail "no checkpoint seen before the run ended"; }
kill -KILL "$victim"
wait "$launcher" && fail "the killed run succeeded"
[ -f "$checkpoint" ] || fail "the killed run left no checkpoint"
kept=$(($(wc -l < "$checkpoint") - 1))
echo "killed with $kept items in the checkpoint"

bash "$here/run_mpi.sh" "$mpiexec" "$ranks" "$program" "$scene" -q -o "$work/results" \
  > "$work/second.stdout" 2> "$work/second.stderr" || { cat "$work/second.stderr"; fail "the rerun failed"; }
grep -q "from the checkpoint of an earlier run" "$work/results/log.txt" \
  || fail "the rerun's log does not say it resumed"
grep "from the checkpoint" "$work/results/log.txt"
[ ! -e "$checkpoint" ] || fail "the checkpoint was left after the successful rerun"
reference_files="$(cd "$work/reference" && ls -A | grep -v '^log.txt$')"
result_files="$(cd "$work/results" && ls -A | grep -v '^log.txt$')"
[ "$reference_files" = "$result_files" ] \
  || fail "different files: in one go: $reference_files; resumed: $result_files"
for file in $reference_files; do
  cmp "$work/reference/$file" "$work/results/$file" || fail "$file differs"
done
echo "resumed: the same $(echo $reference_files | wc -w) files as a run in one go"
