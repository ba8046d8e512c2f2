#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# Strong and weak scaling of the distributed chain (hcimpact_mpi_chain, doc/mpi.md "A
# model of a cluster"), and the constants of the model: the chain of
# bench/mpi/million.nml (touching steel beads, the first struck) with
#   strong: N beads (default 200000) on 1, 2 and 4 ranks,
#   weak:   W beads per rank (default 100000) on 1, 2 and 4 ranks,
# 4 ranks oversubscribed where the machine has fewer cores. Every variant runs once per
# round, in a fresh random order each round; the integration time is the one the
# program reports ("seconds": CVODE alone, the slowest rank); medians over the rounds,
# and the median of the per-round ratios (strong: speed-up against 1 rank; weak: the
# 1-rank time over the variant's, 1 = perfect). Then, once per rank count, the same run
# with bench/mpi/count_mpi.c preloaded counts the global reductions (MPI_Allreduce) per
# step, and bench/mpi/latency.c times one MPI_Allreduce of a double and one halo
# exchange. Prints Markdown tables.
#
# Usage: bench/mpi/scaling.sh [--rounds R] [--strong N] [--weak W] [--t-end T]
#                             [--ranks "1 2 4"] [--build DIR]
# Timings depend on the machine and its load; nothing here is a test.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$root"
rounds=3
strong=200000
weak=100000
t_end=1.0e-5
ranks_list="1 2 4"
build="build/release"
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) shift; rounds="$1" ;;
    --strong) shift; strong="$1" ;;
    --weak) shift; weak="$1" ;;
    --t-end) shift; t_end="$1" ;;
    --ranks) shift; ranks_list="$1" ;;
    --build) shift; build="$1" ;;
    -h|--help) sed -n '4,20p' "$0"; exit 0 ;;
    *) echo "scaling.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
program="$build/app/hcimpact_mpi_chain"
[ -x "$program" ] || { echo "scaling.sh: $program not built" >&2; exit 1; }
mpiexec="$(command -v mpirun || command -v mpiexec)"
command -v mpicc > /dev/null || { echo "scaling.sh: mpicc not found" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mpicc -O2 -Wall -Wextra bench/mpi/latency.c -o "$work/latency"
mpicc -shared -fPIC -O2 -Wall -Wextra bench/mpi/count_mpi.c -o "$work/libcount_mpi.so"

scene() {  # scene NAME BEADS
  sed -e "s/^  n_beads = .*/  n_beads = $2/" -e "s/^  t_end = .*/  t_end = $t_end/" \
    bench/mpi/million.nml > "$work/$1.nml"
}
variants=()
for p in $ranks_list; do
  scene "strong$p" "$strong"
  scene "weak$p" "$((weak * p))"
  variants+=("strong$p" "weak$p")
done
ranks_of() { echo "${1//[a-z]/}"; }
run() {  # run VARIANT OUTPUT [extra mpirun arguments]
  local v="$1" out="$2"
  shift 2
  bash test/mpi/run_mpi.sh "$mpiexec" "$(ranks_of "$v")" "$@" "$program" "$work/$v.nml" \
    "$work/state.csv" > "$out" 2> "$out.err"
}
for ((r = 1; r <= rounds; r++)); do
  for v in $(printf '%s\n' "${variants[@]}" | shuf); do
    run "$v" "$work/$v.$r.txt"
  done
done
value() { awk -v k="$2" '$1 == k {print $2 + 0}' "$1"; }
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
first="$(echo "$ranks_list" | awk '{print $1}')"

for kind in strong weak; do
  echo
  echo "**$kind scaling** ($([ "$kind" = strong ] && echo "$strong beads" || echo "$weak beads per rank"), t_end = $t_end s, $rounds rounds)"
  echo
  echo "| ranks | beads | integration: median (s) | $([ "$kind" = strong ] && echo "speed-up" || echo "efficiency") against $first rank | steps | Krylov iterations per step | halo bytes per step | allreduces per step |"
  echo "|---:|---:|---:|---:|---:|---:|---:|---:|"
  for p in $ranks_list; do
    v="$kind$p"
    t="$(for ((r = 1; r <= rounds; r++)); do value "$work/$v.$r.txt" seconds; done | median)"
    s="$(for ((r = 1; r <= rounds; r++)); do
      awk -v a="$(value "$work/$kind$first.$r.txt" seconds)" -v b="$(value "$work/$v.$r.txt" seconds)" \
        'BEGIN {print a / b}'
    done | median)"
    run "$v" "$work/$v.count.txt" -x LD_PRELOAD="$work/libcount_mpi.so"
    steps="$(value "$work/$v.1.txt" steps)"
    krylov="$(value "$work/$v.1.txt" linear_iterations)"
    beads="$(value "$work/$v.1.txt" beads)"
    halo="$(value "$work/$v.1.txt" halo_bytes_per_step)"
    reductions="$(awk '$1 == "count_mpi:" && $3 == "0" {print $5}' "$work/$v.count.txt.err")"
    printf '| %s | %s | %.3f | %.2f | %s | %.2f | %s | %s |\n' "$p" "$beads" "$t" "$s" "$steps" \
      "$(awk -v a="$krylov" -v b="$steps" 'BEGIN {print a / b}')" "${halo:--}" \
      "$(awk -v a="${reductions:-0}" -v b="$steps" 'BEGIN {printf "%.1f", a / b}')"
  done
done

echo
echo "**Latency** (bench/mpi/latency.c, medians of 21 batches of 2000 calls)"
echo
echo "| ranks | MPI_Allreduce of one double (µs) | halo exchange with both neighbours (µs) |"
echo "|---:|---:|---:|"
for p in $ranks_list; do
  bash test/mpi/run_mpi.sh "$mpiexec" "$p" "$work/latency" 21 2000 |
    awk -v p="$p" '{print "| " p " | " $4 " | " $6 " |"}'
done
echo
echo "Machine: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1), $(nproc) logical CPUs;" \
  "$(mpirun --version 2>/dev/null | head -n 1); load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
