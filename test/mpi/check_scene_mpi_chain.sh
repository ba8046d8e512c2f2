#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# A scene of the distributed chain (&mpi_chain) run serially by the scene runner
# hcimpact against hcimpact_mpi_chain --serial on the same file: both compute it with
# chain_simulate (method 'integrated') from the same reader of &mpi_chain, so every
# body's final position and velocity (final.csv against STATE.csv) and every
# contact's pair, start, end, speeds, peak force, deformation and dissipated energy
# (contacts.csv, put in pair order, against CONTACTS.csv) are the same doubles.
#
# Usage: check_scene_mpi_chain.sh RUNNER MPI_CHAIN SCENE OUTPUT_DIR
set -euo pipefail
runner="$1" program="$2" scene="$3" out="$4"

rm -rf "$out"
mkdir -p "$out"
"$runner" "$scene" -o "$out/runner" > "$out/runner.txt"
"$program" --serial "$scene" "$out/state.csv" "$out/contacts.csv" > "$out/serial.txt"

# final.csv: body, mass, initial position, initial velocity, position, velocity, time
tail -n +2 "$out/runner/final.csv" | cut -d, -f1,5,6 > "$out/runner_state.csv"
tail -n +2 "$out/state.csv" > "$out/serial_state.csv"
# contacts.csv: method, pair, t_start, t_end, duration, approach, separation,
# restitution, closed-form restitution, peak force, deformation, dissipated (in the
# order they ended: sorted by pair, stable)
tail -n +2 "$out/runner/contacts.csv" | cut -d, -f2,3,4,6,7,10,11,12 \
  | sort -t, -k1,1g -s > "$out/runner_contacts.csv"
tail -n +2 "$out/contacts.csv" > "$out/serial_contacts.csv"
for kind in state contacts; do
  a="$out/runner_$kind.csv" b="$out/serial_$kind.csv"
  if [ "$(wc -l < "$a")" != "$(wc -l < "$b")" ] || [ "$(wc -l < "$a")" -lt 1 ]; then
    echo "FAIL: $kind: $(wc -l < "$a") rows from the runner, $(wc -l < "$b") from --serial" >&2
    exit 1
  fi
  paste -d, "$a" "$b" | awk -F, -v kind="$kind" '
    { n = NF / 2; for (k = 1; k <= n; k++) if (($k + 0) != ($(k + n) + 0)) {
        print "FAIL: " kind " row " NR " column " k ": " $k " against " $(k + n) > "/dev/stderr"; exit 1 } }
    END { printf "%s: %d rows, the same doubles\n", kind, NR }'
done
