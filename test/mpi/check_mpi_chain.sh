#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# The distributed chain (hcimpact_mpi_chain) under MPI with N ranks against the serial
# chain integrator of the CVODE component (the same program with --serial): every
# bead's final position within POSITION_TOL metres and velocity within VELOCITY_TOL
# m/s, the same beads in the same order; the summary names N ranks and, with more than
# one, halo bytes sent. With TIME_TOL, SPEED_TOL and RELATIVE_TOL, the contact lists
# too (CONTACTS.csv of both runs, in pair order): the same pairs in the same order,
# every start and end within TIME_TOL seconds, approach and separation speeds within
# SPEED_TOL m/s, peak force, largest deformation and dissipated energy within
# RELATIVE_TOL of the larger of the two; at least one contact. With ENERGY_TOL or
# MOMENTUM_TOL in the environment, the distributed run's energy_error or momentum_error
# (its summary) at most that; with IMPULSE_TOL, both walls' impulses within that
# relative to the serial run's.
#
# Usage: check_mpi_chain.sh MPIEXEC N PROGRAM SCENE OUTPUT_DIR POSITION_TOL VELOCITY_TOL
#          [TIME_TOL SPEED_TOL RELATIVE_TOL]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mpiexec="$1" ranks="$2" program="$3" scene="$4" out="$5" qtol="$6" vtol="$7"
ttol="${8:-}" stol="${9:-}" rtol="${10:-}"

rm -rf "$out"
mkdir -p "$out"
contacts_serial=() contacts_mpi=()
if [ -n "$ttol" ]; then
  contacts_serial=("$out/serial_contacts.csv")
  contacts_mpi=("$out/mpi_contacts.csv")
fi
"$program" --serial "$scene" "$out/serial.csv" "${contacts_serial[@]}" > "$out/serial.txt"
bash "$here/run_mpi.sh" "$mpiexec" "$ranks" "$program" "$scene" "$out/mpi.csv" \
  "${contacts_mpi[@]}" > "$out/mpi.txt"

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

# value NAME FILE: the summary's value of NAME in FILE, checked to be a number in the
# summary's form (awk reads NaN or Infinity as 0)
value() {
  local v
  v="$(awk -v name="$1" '$1 == name { print $2 }' "$2")"
  if ! awk -v v="$v" 'BEGIN { exit !(v ~ /^[-+]?[0-9]+\.[0-9]+E[-+][0-9]+$/) }'; then
    echo "FAIL: $1 '$v' in $2 is not a number" >&2
    exit 1
  fi
  echo "$v"
}
# at_most NAME TOL: the distributed run's NAME (a balance's relative error) <= TOL
at_most() {
  local v
  v="$(value "$1" "$out/mpi.txt")"
  if ! awk -v v="$v" -v tol="$2" 'BEGIN { exit !(v + 0 <= tol + 0) }'; then
    echo "FAIL: $1 $v with $ranks ranks, above $2" >&2
    exit 1
  fi
  echo "$1 $v with $ranks ranks (at most $2)"
}
[ -z "${ENERGY_TOL:-}" ] || at_most energy_error "$ENERGY_TOL"
[ -z "${MOMENTUM_TOL:-}" ] || at_most momentum_error "$MOMENTUM_TOL"
# the walls' impulses against the serial run's, relative to the larger (both walls
# of the scene must have given one)
if [ -n "${IMPULSE_TOL:-}" ]; then
  for side in left right; do
    a="$(value "wall_impulse_$side" "$out/serial.txt")"
    b="$(value "wall_impulse_$side" "$out/mpi.txt")"
    if ! awk -v a="$a" -v b="$b" -v tol="$IMPULSE_TOL" 'BEGIN {
        m = a < 0 ? -a : a; if (b > m || -b > m) m = b < 0 ? -b : b
        d = a - b; if (d < 0) d = -d
        exit !(m > 0 && d <= tol * m) }'; then
      echo "FAIL: the $side wall's impulse $b N s with $ranks ranks, $a serially" >&2
      exit 1
    fi
    echo "wall_impulse_$side $b N s with $ranks ranks, $a serially (within $IMPULSE_TOL)"
  done
fi
[ -n "$ttol" ] || exit 0
serial_lines="$(wc -l < "$out/serial_contacts.csv")"
mpi_lines="$(wc -l < "$out/mpi_contacts.csv")"
if [ "$serial_lines" -lt 2 ] || [ "$serial_lines" != "$mpi_lines" ]; then
  echo "FAIL: $((serial_lines - 1)) contacts serial, $((mpi_lines - 1)) with $ranks ranks" >&2
  exit 1
fi
paste -d, "$out/serial_contacts.csv" "$out/mpi_contacts.csv" | awk -F, \
  -v ttol="$ttol" -v stol="$stol" -v rtol="$rtol" -v ranks="$ranks" '
  function abs(x) { return x < 0 ? -x : x }
  function rel(a, b,   m) { m = abs(a) > abs(b) ? abs(a) : abs(b); return m > 0 ? abs(a - b) / m : 0 }
  NR == 1 { if ($1 != "pair" || $9 != "pair") bad = "headers"; next }
  {
    if ($1 != $9) bad = "pair at line " NR " (" $1 " against " $9 ")"
    for (k = 2; k <= 3; k++) { d = abs($k - $(k + 8)); if (!(d <= ttol)) bad = "time " k " of contact " NR - 1; if (d > mt) mt = d }
    for (k = 4; k <= 5; k++) { d = abs($k - $(k + 8)); if (!(d <= stol)) bad = "speed " k " of contact " NR - 1; if (d > ms) ms = d }
    for (k = 6; k <= 8; k++) { d = rel($k, $(k + 8)); if (!(d <= rtol)) bad = "value " k " of contact " NR - 1 " (" $k " against " $(k + 8) ")"; if (d > mr) mr = d }
  }
  END {
    if (bad != "") { print "FAIL: contacts: " bad > "/dev/stderr"; exit 1 }
    printf "%d contacts, %s ranks: largest differences %.3g s, %.3g m/s, %.3g relative\n", NR - 1, ranks, mt, ms, mr
  }'
