#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
#
# Lambert W benchmark: configure a Release build of the shared library with the
# benchmarks, build bench_lambertw_speed, bench_lambertw_peers and
# bench_lambertw_random, run them (the speed program for throughput, latency and,
# with --cache-pressure, throughput under cache pressure; the random-point
# accuracy sweep) and the SciPy script, and write the results to
# doc/lambertw-bench.md.
#
# Usage (from anywhere): bench/lambertw/run.sh [options]
#   --quick          short run (N=4096, 5 ms, 3 rounds; 20000 random points per
#                    family), for smoke tests
#   --cache-pressure MB  also time throughput with one new line of an MB-megabyte
#                    buffer read per call
#   --random N       random points per family of the accuracy sweep (default
#                    1000000; 0 skips it)
#   --csv PATH       reference table (default test/reference/lambertw.csv)
#   --out PATH       output Markdown (default doc/lambertw-bench.md)
#   --build DIR      build directory (default build/bench)
#   --standalone     configure bench/ on its own (it builds the library from
#                    src/ itself) instead of the top-level project; automatic
#                    when there is no top-level CMakeLists.txt
#   --no-build       reuse the binaries already in the build directory
# Environment: PYTHON (default python3), CMAKE (default cmake).
#
# Timings depend on the machine and its load; nothing here is a test.
set -eu

root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"

quick=""
csv="test/reference/lambertw.csv"
out="doc/lambertw-bench.md"
build="build/bench"
standalone=0
do_build=1
pressure=""
random_points=1000000
cmdline="bench/lambertw/run.sh"
while [ $# -gt 0 ]; do
    cmdline="$cmdline $1"
    case "$1" in
        --quick) quick="--quick"; random_points=20000 ;;
        --cache-pressure) shift; pressure="$1"; cmdline="$cmdline $1" ;;
        --random) shift; random_points="$1"; cmdline="$cmdline $1" ;;
        --csv) shift; csv="$1"; cmdline="$cmdline $1" ;;
        --out) shift; out="$1"; cmdline="$cmdline $1" ;;
        --build) shift; build="$1"; cmdline="$cmdline $1" ;;
        --standalone) standalone=1 ;;
        --no-build) do_build=0 ;;
        -h|--help) sed -n '4,27p' "$0"; exit 0 ;;
        *) echo "run.sh: unknown option $1" >&2; exit 2 ;;
    esac
    shift
done
PYTHON=${PYTHON:-python3}
CMAKE=${CMAKE:-cmake}

if [ ! -f CMakeLists.txt ]; then
    standalone=1
fi
if [ "$standalone" -eq 1 ]; then
    src="bench"
else
    src="."
fi

generator=""
# The protocol times the shared library through the C API, as a user gets it.
extra_off="-DBUILD_SHARED_LIBS=ON -DBUILD_TESTING=OFF -DHCIMPACT_BUILD_EXAMPLES=OFF -DHCIMPACT_BUILD_APP=OFF -DHCIMPACT_WITH_CVODE=OFF -DHCIMPACT_WITH_LAPACK=OFF"
if command -v ninja >/dev/null 2>&1; then
    generator="-G Ninja"
fi

if [ "$do_build" -eq 1 ]; then
    # A build directory configured from the other source tree cannot be reused.
    if [ -f "$build/CMakeCache.txt" ]; then
        home=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt")
        want=$(cd "$src" && pwd)
        if [ "$home" != "$want" ]; then
            echo "run.sh: $build was configured from $home; starting it afresh" >&2
            rm -rf "$build/CMakeCache.txt" "$build/CMakeFiles"
        fi
    fi
    configure="$CMAKE -S $src -B $build $generator -DCMAKE_BUILD_TYPE=Release -DHCIMPACT_BUILD_BENCH=ON"
    if [ "$standalone" -eq 0 ]; then
        # only the core library is needed: no tests, examples or components
        configure="$configure $extra_off"
    fi
    echo "+ $configure" >&2
    # shellcheck disable=SC2086
    $configure >&2
    targets="bench_lambertw_speed bench_lambertw_peers"
    if [ "$random_points" != "0" ]; then
        targets="$targets bench_lambertw_random"
    fi
    echo "+ $CMAKE --build $build --target $targets" >&2
    # shellcheck disable=SC2086
    "$CMAKE" --build "$build" --target $targets >&2
fi

find_exe() {
    # The top-level project may set its own RUNTIME_OUTPUT_DIRECTORY, and a
    # build directory reconfigured from the other source tree may still hold
    # an old binary: take the most recently built one.
    # shellcheck disable=SC2046
    ls -t $(find "$build" -type f -name "$1" -perm -u+x 2>/dev/null) /dev/null 2>/dev/null |
        grep -v '^/dev/null$' | head -n 1
}
speed=$(find_exe bench_lambertw_speed)
peers=$(find_exe bench_lambertw_peers)
random_exe=""
if [ "$random_points" != "0" ]; then
    random_exe=$(find_exe bench_lambertw_random)
    if [ -z "$random_exe" ]; then
        echo "run.sh: bench_lambertw_random not found under $build (no real128?): sweep skipped" >&2
    fi
fi
if [ -z "$speed" ] || [ -z "$peers" ]; then
    echo "run.sh: benchmark programs not found under $build (Boost or GSL missing? see the configure output)" >&2
    exit 1
fi

impl="real implementation"
if head -n 5 src/hcimpact/special/lambertw.f90 | grep -q PLACEHOLDER; then
    impl="PLACEHOLDER implementation (our numbers are meaningless; the peers' are real)"
fi
rev=$(git rev-parse --short HEAD 2>/dev/null || echo "no commit")
if [ -n "$(git status --porcelain -- src include 2>/dev/null || true)" ]; then
    rev="$rev + uncommitted changes in src/ or include/"
fi

# the machine's load average now (1, 5, 15 min) and the time, for the record: a table-based
# path suffers more than the peers' series when other jobs thrash the shared caches
load_now() {
    echo "$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown) at $(date -u '+%H:%M UTC')"
}

tmp="$out.tmp.$$"
mkdir -p "$(dirname "$out")"
trap 'rm -f "$tmp"' EXIT INT TERM

{
    echo "# Lambert W: speed and accuracy against Boost, GSL and SciPy"
    echo
    echo "Generated by \`$cmdline\` (from the repository root) on $(date -u '+%Y-%m-%d %H:%M UTC'),"
    echo "source $rev, $impl of \`src/hcimpact/special/lambertw.f90\`."
    if [ "$standalone" -eq 1 ]; then
        echo "Build: \`$CMAKE -S bench -B $build -DCMAKE_BUILD_TYPE=Release\` (standalone bench project, library from src/ at -O2)."
    else
        echo "Build: \`$CMAKE -S . -B $build -DCMAKE_BUILD_TYPE=Release -DHCIMPACT_BUILD_BENCH=ON $extra_off\`, then"
        echo "\`$CMAKE --build $build --target bench_lambertw_speed bench_lambertw_peers bench_lambertw_random\`."
    fi
    echo "Programs: \`$speed${quick:+ $quick}\` (throughput), \`$speed${quick:+ $quick} --latency\`${pressure:+, \`$speed${quick:+ $quick} --cache-pressure $pressure\`},"
    echo "\`$peers $csv\`, \`$PYTHON bench/lambertw/scipy_accuracy.py $csv\`${random_exe:+, \`$random_exe $random_points\`}."
    echo "How the numbers are made, and how to read them: bench/README.md."
    echo "Load average of the machine (1, 5, 15 min; other jobs share it) before the views: $(load_now)."
    echo
    echo "## Speed"
    echo
    echo "Timings on a shared machine are noisy; compare ratios within one run, never across machines."
    echo "Views, each with its goal table: throughput (independent calls, which the processor"
    echo "may overlap), latency (each call waits for the previous result)${pressure:+ and throughput under cache pressure}."
    echo
} >"$tmp"

echo "+ $speed${quick:+ $quick}" >&2
# shellcheck disable=SC2086
"$speed" $quick >>"$tmp"
echo "+ $speed${quick:+ $quick} --latency" >&2
# shellcheck disable=SC2086
"$speed" $quick --latency >>"$tmp"
if [ -n "$pressure" ]; then
    echo "+ $speed${quick:+ $quick} --cache-pressure $pressure" >&2
    # shellcheck disable=SC2086
    "$speed" $quick --cache-pressure "$pressure" >>"$tmp"
fi
echo "Load average after the views: $(load_now)." >>"$tmp"

{
    echo
    echo "## Accuracy"
    echo
} >>"$tmp"
if [ -f "$csv" ]; then
    echo "+ $peers $csv" >&2
    "$peers" "$csv" >>"$tmp"
    echo >>"$tmp"
    if "$PYTHON" -c "import scipy.special, numpy" >/dev/null 2>&1; then
        echo "+ $PYTHON bench/lambertw/scipy_accuracy.py $csv" >&2
        "$PYTHON" bench/lambertw/scipy_accuracy.py "$csv" >>"$tmp"
    else
        echo "SciPy not available to $PYTHON: SciPy table skipped." >>"$tmp"
    fi
else
    echo "run.sh: reference $csv not found: accuracy tables skipped" >&2
    echo "Reference table \`$csv\` not found: accuracy tables skipped." >>"$tmp"
fi

if [ -n "$random_exe" ]; then
    {
        echo
        echo "### Ours on random points against quadruple precision"
        echo
        echo "\`$random_exe $random_points\`: the largest error in ulps over random arguments of each"
        echo "family (splitmix64, fixed seed), against references computed in real128 by methods"
        echo "independent of ours (bench/lambertw/random_accuracy.f90)."
        echo
    } >>"$tmp"
    echo "+ $random_exe $random_points" >&2
    "$random_exe" "$random_points" >>"$tmp"
fi

mv "$tmp" "$out"
trap - EXIT INT TERM
echo "wrote $out" >&2
