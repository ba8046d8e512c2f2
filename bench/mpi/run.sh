#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# Wall time of the MPI example sweep (example/scenes/mpi_sweep.nml, doc/mpi.md) with 1
# and 2 ranks of mpirun, side by side with the program built without MPI on 1 and 2
# OpenMP threads, in interleaved rounds (every variant once per round, in a fresh
# random order each round). Prints a Markdown table: the median wall time of each
# variant and the median over the rounds of its speed-up against 1 rank in the same
# round. The whole command is timed (start of mpirun and MPI included) with the
# results written (-q -o into a scratch directory).
#
# Usage: bench/mpi/run.sh [--rounds R] [--build DIR]   (a CMake build with MPI and
#        its test programs: build/release by default)
# Timings depend on the machine and its load; nothing here is a test.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$root"
rounds=7
build="build/release"
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) shift; rounds="$1" ;;
    --build) shift; build="$1" ;;
    -h|--help) sed -n '4,14p' "$0"; exit 0 ;;
    *) echo "run.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
program="$build/app/hcimpact"
serial="$build/app/hcimpact_serial"
scene="example/scenes/mpi_sweep.nml"
mpiexec="$(command -v mpirun || command -v mpiexec)"
for p in "$program" "$serial"; do
  [ -x "$p" ] || { echo "run.sh: $p not built (cmake --build $build)" >&2; exit 1; }
done
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT

variants=("mpi-1" "mpi-2" "omp-1" "omp-2")
describe() {
  case "$1" in
    mpi-1) echo "mpirun -n 1 hcimpact (MPI build)" ;;
    mpi-2) echo "mpirun -n 2 hcimpact (MPI build)" ;;
    omp-1) echo "hcimpact without MPI, OMP_NUM_THREADS=1" ;;
    omp-2) echo "hcimpact without MPI, OMP_NUM_THREADS=2" ;;
  esac
}
run() {
  case "$1" in
    mpi-*) OMP_NUM_THREADS=1 bash test/mpi/run_mpi.sh "$mpiexec" "${1#mpi-}" "$program" \
             "$scene" -q -o "$scratch/out" ;;
    omp-*) OMP_NUM_THREADS="${1#omp-}" "$serial" "$scene" -q -o "$scratch/out" ;;
  esac
}
now() { date +%s.%N; }

declare -A times
for ((r = 1; r <= rounds; r++)); do
  for v in $(printf '%s\n' "${variants[@]}" | shuf); do
    t0="$(now)"
    run "$v" > /dev/null
    t1="$(now)"
    times[$v]+="$(echo "$t1 - $t0" | bc -l) "
  done
  echo "round $r/$rounds done" >&2
done

median() { tr ' ' '\n' | sed '/^$/d' | sort -g | awk '{a[NR] = $1} END {if (NR % 2) print a[(NR + 1) / 2]; else print (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
echo "| variant | median wall time (s) | speed-up against 1 rank (median of per-round ratios) |"
echo "|---|---:|---:|"
read -r -a base <<< "${times[mpi-1]}"
for v in "${variants[@]}"; do
  read -r -a mine <<< "${times[$v]}"
  ratios=""
  for ((r = 0; r < rounds; r++)); do
    ratios+="$(echo "${base[$r]} / ${mine[$r]}" | bc -l) "
  done
  printf '| %s | %.3f | %.2f |\n' "$(describe "$v")" "$(echo "${times[$v]}" | median)" \
    "$(echo "$ratios" | median)"
done
echo
echo "Rounds: $rounds; machine: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1), $(nproc) logical CPUs; load average after: $(cut -d' ' -f1-3 /proc/loadavg)."
