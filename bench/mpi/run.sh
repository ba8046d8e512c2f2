#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# Wall time of the MPI example sweep (example/scenes/mpi_sweep.nml, doc/mpi.md) with 1
# and 2 ranks of mpirun, side by side with the program built without MPI on 1 and 2
# OpenMP threads, in interleaved rounds (every variant once per round, in a fresh
# random order each round). Prints a Markdown table: the median wall time of each
# variant and the median over the rounds of its speed-up against 1 rank in the same
# round, for two times: the whole command (start of mpirun and MPI, the CSV files
# written by rank 0 included; -q -o into a scratch directory) and the impacts of the
# sweep alone (the time rank 0 reports for them in log.txt). A control shows what a
# second process can gain on the machine at that moment at all: two copies of the
# program without MPI (one thread each) started together, timed until both end (the
# impacts: the slower copy's).
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

variants=("mpi-1" "mpi-2" "omp-1" "omp-2" "pair")
describe() {
  case "$1" in
    mpi-1) echo "mpirun -n 1 hcimpact (MPI build)" ;;
    mpi-2) echo "mpirun -n 2 hcimpact (MPI build)" ;;
    omp-1) echo "hcimpact without MPI, OMP_NUM_THREADS=1" ;;
    omp-2) echo "hcimpact without MPI, OMP_NUM_THREADS=2" ;;
    pair) echo "control: 2 independent copies of hcimpact without MPI at once (1 thread each)" ;;
  esac
}
run() {
  case "$1" in
    mpi-*) OMP_NUM_THREADS=1 bash test/mpi/run_mpi.sh "$mpiexec" "${1#mpi-}" "$program" \
             "$scene" -q -o "$scratch/out" ;;
    omp-*) OMP_NUM_THREADS="${1#omp-}" "$serial" "$scene" -q -o "$scratch/out" ;;
    pair) OMP_NUM_THREADS=1 "$serial" "$scene" -q -o "$scratch/other" & local other=$!
          OMP_NUM_THREADS=1 "$serial" "$scene" -q -o "$scratch/out"
          wait "$other" ;;
  esac
}
now() { date +%s.%N; }

# the time of the sweep's impacts in log.txt ("sweep  20000 impacts: 166 ms, ..."), in s
sweep_seconds() {
  local logs=("$scratch/out/log.txt")
  [ "$1" = pair ] && logs+=("$scratch/other/log.txt")
  awk '/^sweep +[0-9]+ impacts: / {
         v = $4; u = $5; sub(/,.*/, "", u)
         if (u == "ms") v /= 1e3; else if (u == "us") v /= 1e6
         if (v > worst) worst = v }
       END { print worst }' "${logs[@]}"
}

declare -A times sweeps
for ((r = 1; r <= rounds; r++)); do
  for v in $(printf '%s\n' "${variants[@]}" | shuf); do
    t0="$(now)"
    run "$v" > /dev/null
    t1="$(now)"
    times[$v]+="$(echo "$t1 - $t0" | bc -l) "
    sweeps[$v]+="$(sweep_seconds "$v") "
  done
  echo "round $r/$rounds done" >&2
done

median() { tr ' ' '\n' | sed '/^$/d' | sort -g | awk '{a[NR] = $1} END {if (NR % 2) print a[(NR + 1) / 2]; else print (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
# median over the rounds of (time of 1 rank) / (time of the variant), same round
speedup() {
  local -a base mine
  local ratios="" r
  read -r -a base <<< "$1"
  read -r -a mine <<< "$2"
  for ((r = 0; r < rounds; r++)); do
    ratios+="$(echo "${base[$r]} / ${mine[$r]}" | bc -l) "
  done
  echo "$ratios" | median
}
echo "| variant | whole command: median (s) | speed-up | impacts of the sweep: median (s) | speed-up |"
echo "|---|---:|---:|---:|---:|"
for v in "${variants[@]}"; do
  printf '| %s | %.3f | %.2f | %.3f | %.2f |\n' "$(describe "$v")" \
    "$(echo "${times[$v]}" | median)" "$(speedup "${times[mpi-1]}" "${times[$v]}")" \
    "$(echo "${sweeps[$v]}" | median)" "$(speedup "${sweeps[mpi-1]}" "${sweeps[$v]}")"
done
echo
echo "Rounds: $rounds; machine: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1), $(nproc) logical CPUs; load average after: $(cut -d' ' -f1-3 /proc/loadavg)."
