#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# A successful run writes nothing on standard error: no note of the run-time library
# (gfortran's STOP reports the floating-point flags raised, e.g. the underflows of a
# soft contact's quadrature, unless told to be quiet).
#
# Usage: check_quiet_stderr.sh PROGRAM SCENE OUTPUT_DIR
set -uo pipefail
program="$1" scene="$2" out="$3"
rm -rf "$out"
err="$("$program" "$scene" -q -o "$out" 2>&1 >/dev/null)"
code=$?
if [ "$code" -ne 0 ]; then
  echo "FAIL: exit code $code: $err" >&2
  exit 1
fi
if [ -n "$err" ]; then
  echo "FAIL: the successful run wrote on standard error: $err" >&2
  exit 1
fi
echo "nothing on standard error"
