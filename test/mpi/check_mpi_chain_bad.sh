#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# hcimpact_mpi_chain on a scene it must refuse, or a run that must fail: the exit status
# EXIT (default 2, a bad scene; 1, a failed run), also through mpirun, the expected
# message on standard error, no state file (at STATE, default OUTPUT_DIR/state.csv, nor
# STATE.partial)
# and, with CONTACTS (a contact list asked for), no contact list, no CONTACTS.partial.
#
# Usage: check_mpi_chain_bad.sh MPIEXEC N PROGRAM SCENE OUTPUT_DIR MESSAGE [EXIT [STATE
#          [CONTACTS]]]
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mpiexec="$1" ranks="$2" program="$3" scene="$4" out="$5" message="$6"
expected="${7:-2}" state="${8:-$out/state.csv}" contacts="${9:-}"
contacts_arg=()
[ -z "$contacts" ] || contacts_arg=("$contacts")

rm -rf "$out"
mkdir -p "$out"
bash "$here/run_mpi.sh" "$mpiexec" "$ranks" "$program" "$scene" "$state" \
  "${contacts_arg[@]}" > "$out/stdout" 2> "$out/stderr"
status=$?
if [ "$status" -ne "$expected" ]; then
  echo "FAIL: exit status $status, expected $expected" >&2
  cat "$out/stderr" >&2
  exit 1
fi
if ! grep -qF "error: $message" "$out/stderr"; then
  echo "FAIL: no 'error: $message' on standard error:" >&2
  cat "$out/stderr" >&2
  exit 1
fi
if [ -e "$state" ] || [ -e "$state.partial" ]; then
  echo "FAIL: a state file was left behind" >&2
  exit 1
fi
if [ -n "$contacts" ] && { [ -e "$contacts" ] || [ -e "$contacts.partial" ]; }; then
  echo "FAIL: a contact list was left behind" >&2
  exit 1
fi
echo "ended with status $expected: $message"
