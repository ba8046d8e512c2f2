#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# The distributed chain (hcimpact_mpi_chain) under MPI with N ranks against the serial
# chain integrator of the CVODE component (the same program with --serial): every
# bead's final position within POSITION_TOL metres and velocity within VELOCITY_TOL
# m/s, the same beads in the same order; the summary names N ranks and, with more than
# one, halo bytes sent.
#
# Usage: check_mpi_chain.sh MPIEXEC N PROGRAM SCENE OUTPUT_DIR POSITION_TOL VELOCITY_TOL
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mpiexec="$1" ranks="$2" program="$3" scene="$4" out="$5" qtol="$6" vtol="$7"

rm -rf "$out"
mkdir -p "$out"
"$program" --serial "$scene" "$out/serial.csv" > "$out/serial.txt"
bash "$here/run_mpi.sh" "$mpiexec" "$ranks" "$program" "$scene" "$out/mpi.csv" \
  > "$out/mpi.txt"

if ! grep -Eq "^ranks +$ranks\$" "$out/mpi.txt"; then
  echo "FAIL: the summary does not say $ranks ranks" >&2
  exit 1
fi
if [ "$ranks" -ge 2 ] && ! grep -Eq "^halo_bytes +[1-9][0-9]*\$" "$out/mpi.txt"; then
  echo "FAIL: $ranks ranks exchanged no halo bytes" >&2
  exit 1
fi
serial_lines="$(wc -l < "$out/serial.csv")"
mpi_lines="$(wc -l < "$out/mpi.csv")"
if [ "$serial_lines" -lt 2 ] || [ "$serial_lines" != "$mpi_lines" ]; then
  echo "FAIL: $serial_lines lines serial, $mpi_lines lines with $ranks ranks" >&2
  exit 1
fi
paste -d, "$out/serial.csv" "$out/mpi.csv" | awk -F, -v qtol="$qtol" -v vtol="$vtol" '
  function abs(x) { return x < 0 ? -x : x }
  NR == 1 { if ($0 != "bead,position,velocity,bead,position,velocity") bad = "headers"; next }
  {
    if ($1 != $4 || $1 != NR - 1) bad = "bead numbers at line " NR
    dq = abs($2 - $5); dv = abs($3 - $6)
    if (!(dq <= qtol)) bad = "position of bead " $1 " (" $2 " against " $5 ")"
    if (!(dv <= vtol)) bad = "velocity of bead " $1 " (" $3 " against " $6 ")"
    if (dq > mq) mq = dq
    if (dv > mv) mv = dv
  }
  END {
    if (bad != "") { print "FAIL: " bad > "/dev/stderr"; exit 1 }
    printf "%d beads, %s ranks: largest differences %.3g m, %.3g m/s\n", NR - 1, ranks, mq, mv
  }' ranks="$ranks"
