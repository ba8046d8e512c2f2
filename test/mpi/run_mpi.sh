#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# Run a program under mpirun with N ranks, oversubscribed (more ranks than cores is
# allowed) and, only when run as root (containers, CI), with OpenMPI's consent to
# that. N = 0 runs the program alone, without mpirun (MPI's singleton start).
#
# Usage: run_mpi.sh MPIEXEC N PROGRAM [ARGUMENTS...]
set -uo pipefail
mpiexec="$1"
ranks="$2"
shift 2
if [ "$(id -u)" -eq 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
if [ "$ranks" -eq 0 ]; then
  exec "$@"
fi
exec "$mpiexec" --oversubscribe -n "$ranks" "$@"
