#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
#
# CVODE benchmark (issues #4 and 17): configure a Release build of the shared libraries
# (libhcimpact, libhcimpact_cvode) with the benchmarks, build bench_cvode_work_precision,
# bench_cvode_goal_ratio and bench_cvode_stability, run them and the SciPy script, and
# write the CSV files (bench/cvode/*.csv), the machine and load of the speed ratio
# (bench/cvode/goal_ratio_machine.txt), the figure doc/figures/work_precision.png and
# the generated tables of doc/cvode.md.
#
# The goal's speed ratio at rtol = 1e-10 follows issue 17's protocol (shared libraries,
# contacts in a fresh random order every pass, thread CPU time, medians of per-round
# ratios; bench/cvode/goal_ratio.f90) and is written to bench/cvode/goal_ratio.csv.
#
# Usage (from anywhere): bench/cvode/run.sh [options]
#   --quick        one measurement per setting, short ones; five rounds of the ratio; the
#                  stability grid on the steel ball's size only. Writes to
#                  $TMPDIR/hcimpact_cvode_quick (nothing in the source tree changes)
#   --reference    recompute bench/cvode/reference.csv with mpmath first (~10 s)
#   --no-scipy     skip the SciPy curves (keep the existing CSV, if any)
#   --rounds R     rounds of the speed ratio (default 31)
#   --build DIR    build directory (default build/bench-cvode)
#   --no-build     reuse the binaries already in the build directory
# Environment: PYTHON (default python3), CMAKE (default cmake).
#
# Everything runs under nice (the machine may be shared; CPU time is what is measured).
# A full run takes about 10 minutes on one core (SciPy's Radau at rtol = 1e-13 is
# the slowest part). Timings depend on the machine and its load: compare ratios
# within one run. Nothing here is a test.
set -eu

root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"

quick=""
reference=0
scipy=1
build="build/bench-cvode"
do_build=1
rounds=""
while [ $# -gt 0 ]; do
    case "$1" in
        --quick) quick="--quick" ;;
        --reference) reference=1 ;;
        --no-scipy) scipy=0 ;;
        --rounds) shift; rounds="--rounds $1" ;;
        --build) shift; build="$1" ;;
        --no-build) do_build=0 ;;
        -h|--help) sed -n '4,29p' "$0"; exit 0 ;;
        *) echo "run.sh: unknown option $1" >&2; exit 2 ;;
    esac
    shift
done
PYTHON=${PYTHON:-python3}
CMAKE=${CMAKE:-cmake}

if [ -n "$quick" ]; then
    out="${TMPDIR:-/tmp}/hcimpact_cvode_quick"
    doc="$out/cvode.md"
    figure="$out/work_precision.png"
    mkdir -p "$out"
    cp doc/cvode.md "$doc"
else
    out="bench/cvode"
    doc="doc/cvode.md"
    figure="doc/figures/work_precision.png"
fi

configure="$CMAKE -S . -B $build -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON -DHCIMPACT_BUILD_BENCH=ON -DHCIMPACT_WITH_CVODE=ON -DHCIMPACT_WITH_LAPACK=OFF -DHCIMPACT_WITH_OPENMP=OFF -DBUILD_TESTING=OFF -DHCIMPACT_BUILD_EXAMPLES=OFF -DHCIMPACT_BUILD_APP=OFF"
targets="bench_cvode_work_precision bench_cvode_goal_ratio bench_cvode_stability"
if [ "$do_build" -eq 1 ]; then
    generator=""
    if command -v ninja >/dev/null 2>&1; then
        generator="-G Ninja"
    fi
    echo "+ nice $configure $generator" >&2
    # shellcheck disable=SC2086
    nice $configure $generator >/dev/null
    echo "+ nice $CMAKE --build $build -j2 --target $targets" >&2
    # shellcheck disable=SC2086
    nice $CMAKE --build "$build" -j2 --target $targets >/dev/null
fi
bin="$build/bench/cvode"
# the speed ratio is a figure of the shared libraries: refuse a static build
for lib in libhcimpact.so libhcimpact_cvode.so; do
    if ! ldd "$bin/bench_cvode_goal_ratio" 2>/dev/null | grep -q "$lib"; then
        echo "run.sh: $bin/bench_cvode_goal_ratio does not load $lib (build with -DBUILD_SHARED_LIBS=ON)" >&2
        exit 1
    fi
done

if [ "$reference" -eq 1 ]; then
    $PYTHON bench/cvode/make_reference.py
fi
rev=$(git rev-parse --short HEAD 2>/dev/null || echo "no commit")
if [ -n "$(git status --porcelain -- src include components bench/cvode 2>/dev/null || true)" ]; then
    rev="$rev + uncommitted changes"
fi
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -1)
compiler=$(sed -n 's/^CMAKE_Fortran_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt" 2>/dev/null | head -1)
compiler_version=$("${compiler:-gfortran}" -dumpfullversion 2>/dev/null || echo "?")
sundials_include=$(sed -n 's/^HCIMPACT_SUNDIALS_INCLUDE_DIR:[A-Z]*=//p' "$build/CMakeCache.txt" 2>/dev/null | head -1)
sundials=$(sed -n 's/^#define SUNDIALS_VERSION "\(.*\)"/\1/p' "${sundials_include:-/usr/include}/sundials/sundials_config.h" 2>/dev/null | head -1)
load_before=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo "?")
trap 'rm -f "$out/goal_ratio.csv.tmp"' EXIT INT TERM
echo "+ nice $bin/bench_cvode_goal_ratio bench/cvode/reference.csv $out/goal_ratio.csv${quick:+ $quick}${rounds:+ $rounds}" >&2
# shellcheck disable=SC2086
check=$(nice "$bin/bench_cvode_goal_ratio" bench/cvode/reference.csv "$out/goal_ratio.csv.tmp" $quick $rounds)
load_after=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo "?")
mv "$out/goal_ratio.csv.tmp" "$out/goal_ratio.csv"
{
    echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
    echo "source: $rev"
    echo "machine: ${cpu:-unknown CPU}, $(nproc 2>/dev/null || echo '?') logical CPUs, $(uname -sr)"
    echo "software: gfortran $compiler_version -O2, SUNDIALS ${sundials:-?}, shared libraries (Release)"
    echo "load: $load_before before, $load_after after (load average over 1, 5, 15 min)"
    echo "command: bench/cvode/run.sh${quick:+ $quick}${rounds:+ $rounds}"
    echo "check: $check"
} >"$out/goal_ratio_machine.txt"
echo "+ nice $bin/bench_cvode_work_precision bench/cvode/reference.csv $out/work_precision.csv${quick:+ $quick}" >&2
# shellcheck disable=SC2086
nice "$bin/bench_cvode_work_precision" bench/cvode/reference.csv "$out/work_precision.csv" $quick
if [ "$scipy" -eq 1 ]; then
    set -x
    nice $PYTHON bench/cvode/scipy_work_precision.py bench/cvode/reference.csv \
        "$out/scipy_work_precision.csv" $quick
    { set +x; } 2>/dev/null
fi
set -x
nice "$bin/bench_cvode_stability" "$out/stability.csv" $quick
$PYTHON bench/cvode/report.py --dir "$out" --doc "$doc" --figure "$figure"
{ set +x; } 2>/dev/null
echo "run.sh: results in $out, $doc and $figure"
