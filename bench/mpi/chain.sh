#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# The distributed chain (hcimpact_mpi_chain, doc/mpi.md) on a long chain with 1 and 2
# ranks of mpirun, side by side with the serial chain integrator (--serial), in
# interleaved rounds (every variant once per round, in a fresh random order). The
# chain is example/scenes/mpi_chain.nml with N beads (default 20000) and t_end 3e-4 s.
# Prints per variant the median of the integration time the program reports
# ("seconds": CVODE alone, the slowest rank), the median over the rounds of the
# ratio of the 1-rank time to the variant's, and the work and halo figures of the
# summary (the same every round).
#
# Usage: bench/mpi/chain.sh [--rounds R] [--beads N] [--build DIR]
# Timings depend on the machine and its load; nothing here is a test.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$root"
rounds=5
beads=20000
build="build/release"
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) shift; rounds="$1" ;;
    --beads) shift; beads="$1" ;;
    --build) shift; build="$1" ;;
    -h|--help) sed -n '4,13p' "$0"; exit 0 ;;
    *) echo "chain.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
program="$build/app/hcimpact_mpi_chain"
[ -x "$program" ] || { echo "chain.sh: $program not built" >&2; exit 1; }
mpiexec="$(command -v mpirun || command -v mpiexec)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
sed -e "s/^  n_beads = .*/  n_beads = $beads/" -e "s/^  t_end = .*/  t_end = 3.0e-4/" \
  example/scenes/mpi_chain.nml > "$work/chain.nml"

variants=(serial n1 n2)
run() {
  case "$1" in
    serial) "$program" --serial "$work/chain.nml" "$work/state.csv" ;;
    n1) bash test/mpi/run_mpi.sh "$mpiexec" 1 "$program" "$work/chain.nml" "$work/state.csv" ;;
    n2) bash test/mpi/run_mpi.sh "$mpiexec" 2 "$program" "$work/chain.nml" "$work/state.csv" ;;
  esac
}
for ((r = 1; r <= rounds; r++)); do
  for v in $(printf '%s\n' "${variants[@]}" | shuf); do
    run "$v" > "$work/$v.$r.txt"
  done
done
seconds() { awk '$1 == "seconds" {print $2 + 0}' "$1"; }
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
echo "| variant | integration: median (s) | speed-up against 1 rank | steps | rhs evaluations | halo bytes per step |"
echo "|---|---:|---:|---:|---:|---:|"
for v in "${variants[@]}"; do
  t="$(for ((r = 1; r <= rounds; r++)); do seconds "$work/$v.$r.txt"; done | median)"
  s="$(for ((r = 1; r <= rounds; r++)); do
    awk -v a="$(seconds "$work/n1.$r.txt")" -v b="$(seconds "$work/$v.$r.txt")" 'BEGIN {print a / b}'
  done | median)"
  steps="$(awk '$1 == "steps" {print $2}' "$work/$v.1.txt")"
  rhs="$(awk '$1 == "rhs_evaluations" {print $2}' "$work/$v.1.txt")"
  halo="$(awk '$1 == "halo_bytes_per_step" {print $2 + 0}' "$work/$v.1.txt")"
  printf '| %s | %.3f | %.2f | %s | %s | %s |\n' "$v" "$t" "$s" "$steps" "$rhs" "${halo:--}"
done
echo
echo "Rounds: $rounds; beads: $beads; load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
