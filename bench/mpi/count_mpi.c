/* SPDX-License-Identifier: Apache-2.0 */
/* Counts the global reductions of a run (doc/mpi.md, "A model of a cluster"): loaded
 * with LD_PRELOAD into an MPI program, it stands in front of MPI_Allreduce through
 * MPI's profiling interface (PMPI), counts the calls and their bytes, and prints them
 * per rank when the program ends. SUNDIALS' parallel vector (C) calls MPI_Allreduce for
 * every dot product, norm and minimum; the halo exchanges are counted by the program.
 *
 *   mpicc -shared -fPIC -O2 bench/mpi/count_mpi.c -o libcount_mpi.so
 *   mpirun -n 2 -x LD_PRELOAD=$PWD/libcount_mpi.so build/release/app/hcimpact_mpi_chain ...
 *
 * Output on standard error: "count_mpi: rank R allreduce CALLS bytes BYTES". */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

static long long n_allreduce = 0, bytes_allreduce = 0;

int MPI_Allreduce(const void *send, void *receive, int count, MPI_Datatype type, MPI_Op op,
                  MPI_Comm comm)
{
  int size = 0;
  if (PMPI_Type_size(type, &size) == MPI_SUCCESS)
    bytes_allreduce += (long long)count * size;
  n_allreduce++;
  return PMPI_Allreduce(send, receive, count, type, op, comm);
}

/* At unloading: the Fortran program's MPI_Finalize (mpi_f08) does not pass through the
 * C entry point, so the report cannot hang on it. The rank comes from Open MPI's
 * environment. */
__attribute__((destructor)) static void report(void)
{
  const char *rank = getenv("OMPI_COMM_WORLD_RANK");
  fprintf(stderr, "count_mpi: rank %s allreduce %lld bytes %lld\n", rank ? rank : "?",
          n_allreduce, bytes_allreduce);
}
