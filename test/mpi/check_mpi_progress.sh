#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# --progress shows the progress line on standard error even where it is no terminal
# (under mpirun rank 0's standard error never is), and the run succeeds. Every line
# has its fields in the documented form: items done of the total, the percentage, the
# rate (items per second, or "-" before any was done) and the time left; the items
# done never go back. No timing is asserted. N = 0 runs the program alone.
#
# Usage: check_mpi_progress.sh MPIEXEC N PROGRAM SCENE OUTPUT_DIR
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mpiexec="$1" ranks="$2" program="$3" scene="$4" out="$5"
rm -rf "$out"
err="$(bash "$here/run_mpi.sh" "$mpiexec" "$ranks" "$program" "$scene" --progress -o "$out" \
  2>&1 >/dev/null)" || { echo "FAIL: the run failed: $err" >&2; exit 1; }
lines="$(printf '%s' "$err" | tr '\r' '\n' | sed 's/ *$//' | grep -E '^sweep: ')"
if [ -z "$lines" ]; then
  echo "FAIL: no progress line on standard error: $err" >&2
  exit 1
fi
number='[0-9]+(\.[0-9]+)?(e-?[0-9]+)?'
left='([0-9]+ s|[0-9]+ min [0-5][0-9] s|[0-9]+ h [0-5][0-9] min|> 99 h)'
form="^sweep: [0-9]+/100000 \([0-9]{1,3}%\), ($number/s, $left|- /s, -) left\$"
bad="$(printf '%s\n' "$lines" | grep -vE "$form")"
if [ -n "$bad" ]; then
  echo "FAIL: progress lines not of the form 'sweep: done/total (p%), rate/s, time left':" >&2
  printf '%s\n' "$bad" >&2
  exit 1
fi
# grep reads to the end (no -q): with pipefail, grep -q stopping at the first match
# left printf writing into a closed pipe (SIGPIPE) on long runs of lines
if ! printf '%s\n' "$lines" | grep -E "/s, $left left\$" >/dev/null; then
  echo "FAIL: no progress line with a rate and a time left: $lines" >&2
  exit 1
fi
# the items done and the percentage never go back
if ! printf '%s\n' "$lines" | sed -E 's/^sweep: ([0-9]+)\/.*/\1/' | sort -n -c; then
  echo "FAIL: the items done went back: $lines" >&2
  exit 1
fi
echo "progress shown: $(printf '%s\n' "$lines" | wc -l) lines, the last: $(printf '%s\n' "$lines" | tail -1)"
