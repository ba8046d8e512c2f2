#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Build attack_c.c against build/shared and run every case in its own process (60 s each).
set -u
here="$(cd "$(dirname "$0")" && pwd)"; root="$(cd "$here/../../.." && pwd)"
out="$root/build/attack_c"
cc -O1 -g -o "$out" "$here/attack_c.c" -I"$root/include" -I"$root/build/shared" -I"$root/build/shared/include" \
  -L"$root/build/shared" -lhcimpact_cvode -lhcimpact -lpthread -lm -Wl,-rpath,"$root/build/shared" || exit 1
for k in $("$out"); do
  timeout 60 "$out" "$k"; rc=$?
  [ $rc -ne 0 ] && echo "case $k: exit $rc (crash or hang)"
done
timeout 300 "$out" threads
