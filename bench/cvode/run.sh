#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
#
# CVODE benchmark (issue #4): configure a Release build with the CVODE component
# and the benchmarks, build bench_cvode_work_precision and bench_cvode_stability,
# run them and the SciPy script, and write the CSV files (bench/cvode/*.csv), the
# figure doc/figures/work_precision.png and the generated tables of doc/cvode.md.
#
# The goal's speed ratio at rtol = 1e-10 is measured in interleaved rounds
# (bench/cvode/goal_ratio.csv, see work_precision.f90).
#
# Usage (from anywhere): bench/cvode/run.sh [options]
#   --quick        one measurement per setting, short ones; the stability grid on
#                  the steel ball's size only. Writes to $TMPDIR/hcimpact_cvode_quick
#                  (nothing in the source tree changes)
#   --reference    recompute bench/cvode/reference.csv with mpmath first (~10 s)
#   --no-scipy     skip the SciPy curves (keep the existing CSV, if any)
#   --build DIR    build directory (default build/bench-cvode)
#   --no-build     reuse the binaries already in the build directory
# Environment: PYTHON (default python3), CMAKE (default cmake).
#
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
while [ $# -gt 0 ]; do
    case "$1" in
        --quick) quick="--quick" ;;
        --reference) reference=1 ;;
        --no-scipy) scipy=0 ;;
        --build) shift; build="$1" ;;
        --no-build) do_build=0 ;;
        -h|--help) sed -n '4,24p' "$0"; exit 0 ;;
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

if [ "$do_build" -eq 1 ]; then
    generator=""
    if command -v ninja >/dev/null 2>&1; then
        generator="-G Ninja"
    fi
    set -x
    $CMAKE -S . -B "$build" $generator -DCMAKE_BUILD_TYPE=Release \
        -DHCIMPACT_BUILD_BENCH=ON -DHCIMPACT_WITH_CVODE=ON -DHCIMPACT_WITH_LAPACK=OFF \
        -DBUILD_TESTING=OFF -DHCIMPACT_BUILD_EXAMPLES=OFF
    $CMAKE --build "$build" --target bench_cvode_work_precision bench_cvode_stability
    { set +x; } 2>/dev/null
fi
bin="$build/bench/cvode"

if [ "$reference" -eq 1 ]; then
    $PYTHON bench/cvode/make_reference.py
fi
set -x
"$bin/bench_cvode_work_precision" bench/cvode/reference.csv "$out/work_precision.csv" $quick \
    --ratio "$out/goal_ratio.csv"
{ set +x; } 2>/dev/null
if [ "$scipy" -eq 1 ]; then
    set -x
    $PYTHON bench/cvode/scipy_work_precision.py bench/cvode/reference.csv \
        "$out/scipy_work_precision.csv" $quick
    { set +x; } 2>/dev/null
fi
set -x
"$bin/bench_cvode_stability" "$out/stability.csv" $quick
$PYTHON bench/cvode/report.py --dir "$out" --doc "$doc" --figure "$figure"
{ set +x; } 2>/dev/null
echo "run.sh: results in $out, $doc and $figure"
