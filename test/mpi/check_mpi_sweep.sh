#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# A scene run under MPI with N ranks writes the same files, byte for byte, as the
# serial program (built without MPI) writes: every file of the results directory but
# log.txt (which holds timings and says how the impacts were computed), and no other.
#
# Usage: check_mpi_sweep.sh MPIEXEC N MPI_PROGRAM SERIAL_PROGRAM SCENE OUTPUT_DIR
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mpiexec="$1" ranks="$2" program="$3" serial="$4" scene="$5" out="$6"

rm -rf "$out"
mkdir -p "$out"
"$serial" "$scene" -q -o "$out/serial" > "$out/serial.stdout"
bash "$here/run_mpi.sh" "$mpiexec" "$ranks" "$program" "$scene" -q -o "$out/mpi" \
  > "$out/mpi.stdout"

serial_files="$(cd "$out/serial" && ls -A | grep -v '^log.txt$')"
mpi_files="$(cd "$out/mpi" && ls -A | grep -v '^log.txt$')"
if [ "$serial_files" != "$mpi_files" ]; then
  echo "FAIL: different files: serial: $serial_files; MPI: $mpi_files" >&2
  exit 1
fi
if [ -z "$serial_files" ]; then
  echo "FAIL: no results in $out/serial" >&2
  exit 1
fi
for file in $serial_files; do
  if ! cmp "$out/serial/$file" "$out/mpi/$file"; then
    echo "FAIL: $file differs between the serial run and $ranks ranks" >&2
    exit 1
  fi
done
# the tables on the console too
cmp "$out/serial.stdout" "$out/mpi.stdout"
# the MPI run did distribute (the plan says over how many ranks)
if [ "$ranks" -ge 2 ] && ! grep -q "over $ranks MPI ranks" "$out/mpi/log.txt"; then
  echo "FAIL: log.txt does not say that the impacts went over $ranks ranks" >&2
  exit 1
fi
echo "identical: $(echo $serial_files | wc -w) files, serial and $ranks ranks"
