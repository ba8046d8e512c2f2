#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# Fuzz the C interface of hcimpact with libFuzzer, AddressSanitizer and
# UndefinedBehaviorSanitizer, for a fixed time budget, and report executions,
# crashes, hangs and sanitizer findings (doc/robustness.md).
#
# What is instrumented:
#   - the library (every Fortran source of src/, and the CVODE and LAPACK components
#     when they are built): gfortran -fsanitize=address,undefined,float-cast-overflow
#     -fcheck=all (bounds, pointers, recursion...); its objects link against clang's
#     sanitizer runtimes (same ASan interface);
#   - comparisons in the Fortran code: gfortran -fsanitize-coverage=trace-cmp calls
#     libFuzzer's __sanitizer_cov_trace_cmp*/const_cmp*/switch hooks at every integer
#     comparison (and two empty stubs in the target at floating-point ones), which
#     libFuzzer turns into features with -use_value_profile=1: the guidance inside
#     the library (gfortran cannot emit libFuzzer's edge counters);
#   - the fuzz target bench/fuzz/fuzz_api.c: clang -fsanitize=fuzzer,address,undefined
#     (edge coverage of the C side).
#   Not instrumented: SUNDIALS, LAPACK/BLAS, libgfortran, libc.
#
# The committed corpus bench/fuzz/corpus seeds every run (read only; new inputs go to
# the build directory's corpus); --merge-corpus minimises a run's corpus into it.
#
# Usage: bench/fuzz/run.sh [--seconds N] [--build-dir DIR] [--jobs N] [--no-components]
#                          [--fpe] [--quiet] [--no-value-profile] [--no-seed-corpus]
#   --seconds N       fuzzing budget (default 300)
#   --runs N          stop after N executions instead (with --seed: a reproducible run)
#   --seed N          libFuzzer's random seed (default: chosen by libFuzzer)
#   --fresh           start from an empty corpus (default: keep the corpus of earlier
#                     runs in the build directory, which finds old findings again)
#   --build-dir DIR   where the instrumented library, the target, the corpus and the
#                     log go (default build/fuzz)
#   --jobs N          parallel libFuzzer workers (default 1)
#   --no-components   fuzz the core only (no hcimpact_simulate, no fits)
#   --keep-going      do not stop at the first finding (libFuzzer's fork mode):
#                     collect them all, then list the distinct ones
#   --triage-only     do not build or fuzz: classify the artifacts of an earlier run
#   --fpe             also trap floating-point exceptions (invalid, divide by zero,
#                     overflow) in the library, as -ffpe-trap would: a separate finding
#                     class, not part of the default run (see doc/robustness.md)
#   --quiet           only the summary
#   --no-value-profile  no comparison guidance (no trace-cmp, no -use_value_profile):
#                     the C side's edges only, for comparison
#   --no-seed-corpus  do not read the committed corpus bench/fuzz/corpus
#   --with-chain      fuzz hcimpact_chain_simulate with NULL options (the library's
#                     defaults: up to 1e8 steps) for any system (HCIMPACT_FUZZ_CHAIN=1);
#                     by default NULL options go only with calls that fail before any
#                     work, so that the work per input stays bounded (doc/robustness.md)
#   --without-chain   leave hcimpact_chain_simulate out (HCIMPACT_FUZZ_CHAIN=0)
#   --merge-corpus    after the run, add to bench/fuzz/corpus the inputs of the run's
#                     corpus that bring new features (libFuzzer -merge=1)
# Exit status: 0 no finding; 1 a crash, hang, sanitizer report or contract violation;
# 77 clang or libFuzzer missing (CTest: skipped).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
seconds=300
runs=""
seed=""
fresh=0
build="$root/build/fuzz"
jobs=1
components=1
fpe=0
quiet=0
keep_going=0
triage_only=0
value_profile=1
seed_corpus=1
merge_corpus=0
seed_dirs=()
committed="$root/bench/fuzz/corpus"
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --fresh) fresh=1; shift ;;
    --build-dir) build="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --no-components) components=0; shift ;;
    --fpe) fpe=1; shift ;;
    --keep-going) keep_going=1; shift ;;
    --triage-only) triage_only=1; shift ;;
    --quiet) quiet=1; shift ;;
    --no-value-profile) value_profile=0; shift ;;
    --no-seed-corpus) seed_corpus=0; shift ;;
    --merge-corpus) merge_corpus=1; shift ;;
    --with-chain) export HCIMPACT_FUZZ_CHAIN=1; shift ;;
    --without-chain) export HCIMPACT_FUZZ_CHAIN=0; shift ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done

say() { [ "$quiet" = 1 ] || printf '\n---- fuzz: %s\n' "$*"; }
run_quiet() {
  if [ "$quiet" = 1 ]; then "$@" >"$build/step.log" 2>&1 || { cat "$build/step.log"; return 1; }
  else "$@"; fi
}

cc="${CLANG:-clang}"
if ! command -v "$cc" >/dev/null 2>&1; then
  echo "SKIPPED: clang not found (apt-get install clang libclang-rt-14-dev)"
  exit 77
fi
mkdir -p "$build"
build="$(cd "$build" && pwd)"   # absolute: libFuzzer runs inside it
# libFuzzer and the sanitizer runtimes come with libclang-rt-<version>-dev
printf 'int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { (void)d; (void)n; return 0; }\n' \
  >"$build/probe.c"
if ! "$cc" -fsanitize=fuzzer,address,undefined "$build/probe.c" -o "$build/probe" >/dev/null 2>&1; then
  echo "SKIPPED: $cc cannot link -fsanitize=fuzzer,address,undefined (libclang-rt-14-dev missing?)"
  exit 77
fi
fc="${FC:-gfortran}"
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi

if [ "$triage_only" = 0 ]; then
san_flags="-fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer"
# -fcheck=all but recursion: that check is a static flag (not what is fuzzed here)
fflags="-g -O1 $san_flags -fcheck=all -fcheck=no-recursion"
if [ "$value_profile" = 1 ]; then fflags="$fflags -fsanitize-coverage=trace-cmp"; fi
if [ "$components" = 1 ]; then with=AUTO; else with=OFF; fi
if [ "$fpe" = 1 ]; then fpe_flag=ON; else fpe_flag=OFF; fi

say "instrumented library ($fc $fflags) and fuzz target ($cc) in $build/target"
run_quiet cmake -S "$root/bench/fuzz" -B "$build/target" "${generator[@]}" \
  -DCMAKE_BUILD_TYPE=None -DCMAKE_Fortran_COMPILER="$fc" -DCMAKE_C_COMPILER="$cc" \
  -DCMAKE_Fortran_FLAGS="$fflags" -DBUILD_TESTING=OFF -DHCIMPACT_BUILD_EXAMPLES=OFF \
  -DHCIMPACT_DEBUG_CHECKS=OFF -DHCIMPACT_WITH_CVODE="$with" -DHCIMPACT_WITH_LAPACK="$with" \
  -DHCIMPACT_FUZZ_FPE="$fpe_flag"
run_quiet cmake --build "$build/target" --target fuzz_api --parallel "$(nproc 2>/dev/null || echo 2)"
components_built="core"
for component in cvode lapack; do
  if [ -f "$build/target/hcimpact/libhcimpact_$component.a" ]; then
    components_built="$components_built, $component"
  fi
done
cp "$build/target/fuzz_api" "$build/fuzz_api"

corpus="$build/corpus"
artifacts="$build/artifacts"
if [ "$fresh" = 1 ]; then rm -rf "$corpus"; fi
mkdir -p "$corpus" "$artifacts"
rm -f "$artifacts"/crash-* "$artifacts"/timeout-* "$artifacts"/leak-* "$artifacts"/oom-*
log="$build/fuzz.log"
say "running for ${seconds}s${runs:+ or $runs executions}${seed:+, seed $seed} ($jobs worker(s)); log $log"
status=0
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:halt_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1:suppressions=$root/bench/fuzz/ubsan.supp}"
fuzz_args=(-max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 -max_len=512
  -print_final_stats=1 -artifact_prefix="$artifacts/")
if [ -n "$runs" ]; then fuzz_args+=(-runs="$runs"); fi
if [ -n "$seed" ]; then fuzz_args+=(-seed="$seed"); fi
if [ "$value_profile" = 1 ]; then fuzz_args+=(-use_value_profile=1); fi
if [ "$seed_corpus" = 1 ] && [ -d "$committed" ]; then seed_dirs=("$committed"); fi
if [ "$keep_going" = 1 ]; then
  fuzz_args+=(-fork="$jobs" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
elif [ "$jobs" -gt 1 ]; then
  fuzz_args+=(-jobs="$jobs" -workers="$jobs")
fi
started=$(date +%s.%N)
(cd "$build" && ./fuzz_api "${fuzz_args[@]}" "$corpus" "${seed_dirs[@]}") >"$log" 2>&1 || status=$?
elapsed=$(awk -v a="$started" -v b="$(date +%s.%N)" 'BEGIN {printf "%.1f", b - a}')
if [ "$jobs" -gt 1 ]; then cat "$build"/fuzz-*.log >>"$log" 2>/dev/null || true; fi
if [ "$merge_corpus" = 1 ]; then
  say "merging the run's corpus into $committed"
  mkdir -p "$committed"
  merge_args=(-merge=1 -timeout=20 -rss_limit_mb=4096 -max_len=512)
  if [ "$value_profile" = 1 ]; then merge_args+=(-use_value_profile=1); fi
  (cd "$build" && ./fuzz_api "${merge_args[@]}" "$committed" "$corpus") >"$build/merge.log" 2>&1
fi
else
  corpus="$build/corpus"; artifacts="$build/artifacts"; log="$build/fuzz.log"
  components_built="(as built before)"
  status=0; elapsed=0
fi

# summary
execs=$( (grep -h "stat::number_of_executed_units" "$log" || true) | awk '{s += $2} END {print s + 0}')
if [ "$keep_going" = 1 ]; then
  # fork mode prints no final stats: the last status line counts the executions
  execs=$( (grep -hE "^#[0-9]+" "$log" || true) | tail -1 | sed 's/^#\([0-9]*\).*/\1/')
  execs=${execs:-0}
fi
rate=$(awk -v n="$execs" -v t="$elapsed" 'BEGIN {printf "%.0f", (t > 0 ? n / t : 0)}')
cov=$( (grep -hE "^#[0-9]+.*cov: " "$log" || true) | tail -1 \
  | sed -n 's/.*cov: \([0-9]*\) ft: \([0-9]*\).*/\1 edges, \2 features/p')
crashes=$(find "$artifacts" -name 'crash-*' | wc -l)
hangs=$(find "$artifacts" -name 'timeout-*' | wc -l)
leaks=$(find "$artifacts" -name 'leak-*' | wc -l)
ooms=$(find "$artifacts" -name 'oom-*' | wc -l)
# rerun every artifact once to classify it (fork mode keeps the reports elsewhere)
triage="$build/triage.log"
: >"$triage"
for artifact in "$artifacts"/crash-* "$artifacts"/timeout-* "$artifacts"/leak-*; do
  [ -f "$artifact" ] || continue
  output=$("$build/fuzz_api" -timeout=60 "$artifact" 2>&1 || true)
  first=$(printf '%s\n' "$output" \
    | grep -m1 -E "ERROR: (Address|Leak)Sanitizer|runtime error:|contract broken|deadly signal|SEGV|FPE|floating|timeout" \
    | sed 's/^==[0-9]*==//' || true)
  if printf '%s\n' "$first" | grep -q "AddressSanitizer"; then
    # the kind (FPE, SEGV, ...) and where: frame #0 without its address
    kind=$(printf '%s\n' "$first" | sed -n 's/.*AddressSanitizer: \([A-Za-z-]*\).*/\1/p')
    where=$(printf '%s\n' "$output" | grep -m1 -E "^ *#0 " | sed 's/^ *#0 0x[0-9a-f]* in //; s/ (.*BuildId.*//' || true)
    first="AddressSanitizer: $kind in $where"
  fi
  if printf '%s\n' "$first" | grep -q "LeakSanitizer"; then
    # where the first leaked block was allocated: the first frame in hcimpact's code
    where=$(printf '%s\n' "$output" | grep -m1 -E "^ *#[0-9]+ .* in __hcimpact" \
      | sed 's/^ *#[0-9]* 0x[0-9a-f]* in //; s/ (.*BuildId.*//' || true)
    first="LeakSanitizer: leak allocated in ${where:-an unknown frame}"
  fi
  contact=$(printf '%s\n' "$output" | grep -m1 "last contact" | sed 's/^ *//' || true)
  printf '%s\t%s\t%s\n' "$(basename "$artifact")" "${first:-unclassified}" "$contact" >>"$triage"
done
count() { (cut -f2 "$triage" | grep -c -- "$1") || true; }
asan=$(count "AddressSanitizer")
ubsan=$(count "runtime error:")
contract=$(count "contract broken")
fpes=$(count "FPE")
corpus_size=$(find "$corpus" -type f | wc -l)

cat <<EOF

hcimpact fuzz summary ($(date -u +%Y-%m-%dT%H:%MZ), $(uname -m), budget ${seconds} s${runs:+ or $runs runs}${seed:+, seed $seed}, ran ${elapsed} s, $jobs worker(s))
  target            bench/fuzz/fuzz_api.c (entry points of: $components_built)
  executions        $execs ($rate exec/s)
  coverage          ${cov:-n/a} ($( [ "$value_profile" = 1 ] && echo "C edges; features with the Fortran comparisons" || echo "C side only")), corpus $corpus_size inputs$( [ ${#seed_dirs[@]} -gt 0 ] && echo " (+ $(find "$committed" -type f | wc -l) committed)")
  crashes           $crashes
  hangs (> 20 s)    $hangs
  leaks             $leaks
  out of memory     $ooms
  ASan reports      $asan
  UBSan reports     $ubsan
  contract broken   $contract
  FP exceptions     $fpes$( [ "$fpe" = 1 ] || printf ' (not trapped; --fpe to trap)')
  libFuzzer exit    $status
EOF
if [ -s "$triage" ]; then
  echo "  distinct findings (numbers in the messages ignored; every artifact in $triage):"
  # one line per kind of finding: the message with its numbers blanked
  awk -F '\t' '{key = $2; gsub(/[0-9]+/, "#", key); if (!(key in seen)) {seen[key] = 1;
    n[key] = 0; order[++k] = key; first[key] = $0} n[key]++}
    END {for (i = 1; i <= k; i++) {split(first[order[i]], f, "\t");
      printf "    %dx %s\n       e.g. %s %s\n", n[order[i]], f[2], f[1], f[3]}}' "$triage"
fi
if [ "$crashes$hangs$leaks$ooms$asan$ubsan$contract" != "0000000" ] || [ "$status" != 0 ]; then
  echo "FINDINGS: see $log and $artifacts" >&2
  exit 1
fi
echo "no findings"
