#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
#
# The work of one impact in instructions (issue 17), which unlike a time does not
# depend on the load of the machine: valgrind's callgrind counts what hcimpact_impact
# of a shared library executes (inclusive) in bench_one_impact, for the regimes of
# beta = b V the rules depend on, and prints the instructions per impact.
#
# Usage: bench/impact/instructions.sh [--count N] BENCH LIB
#   BENCH      the bench_one_impact program (bench/impact/run.sh builds it)
#   LIB        a libhcimpact.so (e.g. build/bench-impact/work/libhcimpact.so after run.sh)
#   --count N  contacts per range (default 2000); bench_one_impact makes two passes
#              over them (--rounds 1: one untimed, one timed), 2 N impacts in all
# Ranges: beta in [1e-3, 1.8] (one rule over the whole contact), [1.8, 8], [8, 100],
# the benchmark's groups "low" (beta <= 100) and "high" (100 < beta <= 1e8).
set -eu

count="2000"
while [ $# -gt 0 ]; do
    case "$1" in
        --count) shift; count="$1" ;;
        -h|--help) sed -n '4,15p' "$0"; exit 0 ;;
        -*) echo "instructions.sh: unknown option $1" >&2; exit 2 ;;
        *) break ;;
    esac
    shift
done
if [ $# -ne 2 ]; then
    echo "usage: instructions.sh [--count N] BENCH LIB" >&2
    exit 2
fi
bench="$1"
lib="$2"
command -v valgrind >/dev/null || { echo "instructions.sh: valgrind not found" >&2; exit 1; }
command -v callgrind_annotate >/dev/null || {
    echo "instructions.sh: callgrind_annotate not found" >&2
    exit 1
}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM

echo "| beta | instructions per impact |"
echo "|---|---:|"
for range in "1e-3 1.8" "1.8 8" "8 100" "low" "high"; do
    case "$range" in
        low|high) select="--group $range"; label="$range" ;;
        *) select="--beta $range"; label=$(echo "$range" | sed 's/ / - /') ;;
    esac
    # shellcheck disable=SC2086
    if ! valgrind --tool=callgrind --callgrind-out-file="$tmp/out" "$bench" --rounds 1 \
        --count "$count" $select "$lib" >"$tmp/log" 2>&1; then
        echo "instructions.sh: valgrind $bench failed:" >&2
        cat "$tmp/log" >&2
        exit 1
    fi
    # the inclusive count of the C entry point, e.g. "60,432,420 (97.1%)  ???:hcimpact_impact [...]"
    total=$(callgrind_annotate --inclusive=yes "$tmp/out" 2>/dev/null \
        | awk '/[^A-Za-z_]hcimpact_impact[ \[]/ && !found { gsub(",", "", $1); print $1; found = 1 }')
    if [ -z "$total" ]; then
        echo "instructions.sh: no hcimpact_impact in the profile of $lib" >&2
        exit 1
    fi
    echo "| $label | $((total / (2 * count))) |"
done
