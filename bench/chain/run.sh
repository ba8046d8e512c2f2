#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
#
# Benchmarks of systems of bodies on a line (issue 15, "Speed and scale"): configure a
# Release build with the shared libraries (libhcimpact, libhcimpact_cvode) and the
# benchmarks, build bench_chain, run every part, and write the CSV files
# (bench/chain/results/), the figures doc/figures/chain_*.png and the generated sections
# of doc/chains-bench.md.
#
# Parts (all by default; --only PART,PART,... to run some, the others' CSV files kept):
#   scaling  per-step cost of the struck chain against N = 1e2 ... 1e5 (interleaved rounds):
#            touching and integrated whole, touching with method auto, and with small gaps
#   memory   peak RSS against N = 1e2 ... 1e6 (one process per N, the whole chain
#            integrated)
#   scipy    work-precision against SciPy's solve_ivp, N = 100 and N = 1000 (and
#            N = 10000 and 100000 against DOP853 alone)
#   dilute   closed forms against CVODE on the dilute systems (interleaved rounds)
#   row      the dilute row of N = 1e3 ... 1e5 beads with random speeds: method auto
#            (a region per cluster), and the whole row integrated up to N = 1e3
#
# Usage (from anywhere): bench/chain/run.sh [options]
#   --quick          small sizes, one or two rounds: a smoke run (a few minutes). Writes
#                    to $TMPDIR/hcimpact_chain_quick (nothing in the source tree changes)
#   --only LIST      the parts to run (comma-separated)
#   --wait-quiet L   before each part, wait (at most 30 minutes) until the one-minute
#                    load average is below L (the machine is shared)
#   --build DIR      build directory (default build/bench-chain)
#   --no-build       reuse the binary already in the build directory
#   --sundials7 DIR  build against the SUNDIALS 7.1.1 that `bash .ci/sundials7-check` left
#                    in DIR (its work directory, build/sundials7-check): compiled by
#                    SUNDIALS' own CMake in Release (-O3), where Debian 12's 6.4.1 is
#                    compiled without optimisation. Build directory build/bench-chain7,
#                    results in bench/chain/results-sundials7, the generated sections of
#                    doc/chains-bench-sundials7.md and doc/figures/sundials7/
# Environment: PYTHON (default python3), CMAKE (default cmake).
#
# A full run takes about 30 minutes on one core. Timings depend on the machine and its
# load: the ratios are formed within rounds, and the machine's load is written down
# before every part (results/machine.txt). Nothing here is a test.
set -eu

root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"

quick=0
only="scaling,memory,scipy,dilute,row"
wait_quiet=""
build="build/bench-chain"
do_build=1
sundials7=""
while [ $# -gt 0 ]; do
    case "$1" in
        --quick) quick=1 ;;
        --only) shift; only="$1" ;;
        --wait-quiet) shift; wait_quiet="$1" ;;
        --build) shift; build="$1" ;;
        --no-build) do_build=0 ;;
        --sundials7) shift; sundials7=$(cd "$1" && pwd) ;;
        -h|--help) sed -n '4,35p' "$0"; exit 0 ;;
        *) echo "run.sh: unknown option $1" >&2; exit 2 ;;
    esac
    shift
done
PYTHON=${PYTHON:-python3}
CMAKE=${CMAKE:-cmake}
# one thread for NumPy and SciPy, as for our side
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1

if [ "$quick" -eq 1 ]; then
    out="${TMPDIR:-/tmp}/hcimpact_chain_quick"
    doc="$out/chains-bench.md"
    figures="$out"
    mkdir -p "$out"
    cp doc/chains-bench.md "$doc"
elif [ -n "$sundials7" ]; then
    out="bench/chain/results-sundials7"
    doc="doc/chains-bench-sundials7.md"
    figures="doc/figures/sundials7"
    [ "$build" = "build/bench-chain" ] && build="build/bench-chain7"
    mkdir -p "$out"
else
    out="bench/chain/results"
    doc="doc/chains-bench.md"
    figures="doc/figures"
    mkdir -p "$out"
fi

# the configuration of the SUNDIALS to build against: Debian's (found by CMake) or the
# one .ci/sundials7-check built (CVODES, static, with its stand-in Fortran modules)
sundials_flags=""
sundials_config=/usr/include/sundials/sundials_config.h
if [ -n "$sundials7" ]; then
    lib="$sundials7/prefix/lib"
    for f in "$lib/libsundials_cvodes.a" "$lib/libhcimpact_sundials7_fmod_shim.a"; do
        [ -f "$f" ] || { echo "run.sh: $f is missing (run bash .ci/sundials7-check)" >&2; exit 2; }
    done
    sundials_config="$sundials7/prefix/include/sundials/sundials_config.h"
    sundials_flags=$(bash .ci/sundials7/configure-flags "$sundials7/prefix" | tr '\n' ' ')
fi

if [ "$do_build" -eq 1 ]; then
    generator=""
    if command -v ninja >/dev/null 2>&1; then
        generator="-G Ninja"
    fi
    set -x
    $CMAKE -S . -B "$build" $generator -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON \
        -DHCIMPACT_BUILD_BENCH=ON -DHCIMPACT_WITH_CVODE=ON -DHCIMPACT_WITH_LAPACK=OFF \
        -DBUILD_TESTING=OFF -DHCIMPACT_BUILD_EXAMPLES=OFF -DHCIMPACT_BUILD_APP=OFF \
        $sundials_flags
    $CMAKE --build "$build" --target bench_chain
    { set +x; } 2>/dev/null
fi
bench="$build/bench/chain/bench_chain"
states="$build/chain_states"

has_part() {
    case ",$only," in *",$1,"*) return 0 ;; *) return 1 ;; esac
}

# the machine, once per run, and its load before every part: a full run writes it anew
# (a partial one adds its loads to it); so does every --sundials7 run, whose page holds
# the SciPy part alone
machine="$out/machine.txt"
if [ "$only" = "scaling,memory,scipy,dilute,row" ] || [ -n "$sundials7" ] ||
    [ ! -f "$machine" ]; then
    {
        echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
        echo "cpu: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)," \
             "$(grep -c '^processor' /proc/cpuinfo) logical CPUs (a virtual machine shared" \
             "with other jobs)"
        echo "memory: $(awk '/MemTotal/ {printf "%.1f GiB", $2 / 1048576}' /proc/meminfo)"
        echo "kernel: $(uname -sr)"
        echo "compiler: $(gfortran --version | head -n 1)"
        echo "sundials: $(sed -n 's/^#define SUNDIALS_VERSION "\(.*\)"/\1/p' \
            "$sundials_config" 2>/dev/null || echo unknown)$([ -n "$sundials7" ] &&
            echo " (CVODES, built by .ci/sundials7-check in Release: -O3)")"
        echo "python: $($PYTHON -c 'import sys, numpy, scipy; print(sys.version.split()[0],
              "numpy", numpy.__version__, "scipy", scipy.__version__)')"
        echo "libraries: $(ls "$build"/libhcimpact.so.*.*.* "$build"/libhcimpact_cvode.so.*.*.* \
            2>/dev/null | sed 's|.*/||' | tr '\n' ' ')(shared, Release, -O2)"
    } > "$machine"
fi

before_part() {
    if [ -n "$wait_quiet" ]; then
        waited=0
        while [ "$waited" -lt 1800 ] && \
            awk -v lim="$wait_quiet" '{ exit !($1 >= lim) }' /proc/loadavg; do
            sleep 30
            waited=$((waited + 30))
        done
    fi
    echo "load before $1: $(cut -d' ' -f1-3 /proc/loadavg) ($(date -u '+%Y-%m-%d %H:%M UTC'))" \
        >> "$machine"
}

if has_part scaling; then
    before_part scaling
    if [ "$quick" -eq 1 ]; then
        set -- --sizes 100,1000 --rounds 2 --min-seconds 0.05
    else
        set -- --sizes 100,1000,10000,100000 --rounds 5 --min-seconds 0.2
    fi
    set -x
    "$bench" scaling "$out/scaling.csv" --t-end 3e-4 --rtol 1e-8 --method integrated "$@"
    "$bench" scaling "$out/scaling_auto.csv" --t-end 1e-3 --rtol 1e-8 "$@"
    "$bench" scaling "$out/scaling_gap.csv" --t-end 1e-3 --rtol 1e-8 --gap 1e-6 "$@"
    { set +x; } 2>/dev/null
fi

if has_part memory; then
    before_part memory
    sizes="100 1000 10000 100000 1000000"
    [ "$quick" -eq 1 ] && sizes="100 1000 10000"
    echo "n,t_end,rtol,status,baseline_kib,peak_kib,steps" > "$out/memory.csv.tmp"
    for n in $sizes; do
        set -x
        "$bench" memory --n "$n" --t-end 1e-5 --rtol 1e-8 --method integrated | tail -n 1 \
            >> "$out/memory.csv.tmp"
        { set +x; } 2>/dev/null
    done
    mv "$out/memory.csv.tmp" "$out/memory.csv"
fi

if has_part scipy; then
    before_part scipy
    if [ "$quick" -eq 1 ]; then
        set -x
        $PYTHON bench/chain/work_precision.py --bench "$bench" --dir "$out" --states "$states" \
            --n 100 --quick
        { set +x; } 2>/dev/null
    else
        set -x
        $PYTHON bench/chain/work_precision.py --bench "$bench" --dir "$out" --states "$states" \
            --n 100 --rounds 5
        { set +x; } 2>/dev/null
        before_part "scipy (N = 1000)"
        set -x
        $PYTHON bench/chain/work_precision.py --bench "$bench" --dir "$out" --states "$states" \
            --n 1000 --rounds 3
        { set +x; } 2>/dev/null
        # 10^4 beads: DOP853 alone (Radau and BDF with SciPy's sparse LU take minutes
        # per solve there; at 1000 beads they were already 12-44 times slower than ours)
        before_part "scipy (N = 10000)"
        set -x
        $PYTHON bench/chain/work_precision.py --bench "$bench" --dir "$out" --states "$states" \
            --n 10000 --rounds 3 --scipy-methods DOP853
        { set +x; } 2>/dev/null
        # 10^5 beads, DOP853 alone: the wave reaches the same 97 beads by 1 ms, which is
        # all ours integrates, while DOP853 steps the whole chain (about 5 minutes)
        before_part "scipy (N = 100000)"
        set -x
        $PYTHON bench/chain/work_precision.py --bench "$bench" --dir "$out" --states "$states" \
            --n 100000 --rounds 3 --scipy-methods DOP853
        { set +x; } 2>/dev/null
    fi
fi

if has_part dilute; then
    before_part dilute
    if [ "$quick" -eq 1 ]; then
        set -- --rounds 1 --rtols 1e-6,1e-8 --min-seconds 0.02
    else
        set -- --rounds 7 --rtols 1e-6,1e-7,1e-8,1e-9,1e-10,1e-11,1e-12 --min-seconds 0.05
    fi
    set -x
    "$bench" dilute "$out/dilute_times.csv" "$out/dilute_accuracy.csv" --rtol 1e-10 "$@"
    { set +x; } 2>/dev/null
fi

if has_part row; then
    before_part row
    if [ "$quick" -eq 1 ]; then
        set -- --sizes 100,1000 --rounds 1 --t-end 0.02
    else
        set -- --sizes 1000,10000,100000 --rounds 3 --t-end 0.02
    fi
    set -x
    "$bench" row "$out/row.csv" --rtol 1e-10 "$@"
    { set +x; } 2>/dev/null
fi
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg) ($(date -u '+%H:%M UTC'))" >> "$machine"

set -x
$PYTHON bench/chain/report.py --dir "$out" --doc "$doc" --figures "$figures"
{ set +x; } 2>/dev/null
echo "run.sh: results in $out, $doc and $figures"
