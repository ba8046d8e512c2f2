/* SPDX-License-Identifier: Apache-2.0 */
/* The latency of the two communications of the distributed chain (doc/mpi.md, "A model
 * of a cluster"): MPI_Allreduce of one double over all ranks (SUNDIALS' parallel vector
 * does one per dot product and norm) and MPI_Sendrecv of one boundary bead's state
 * (2 doubles) with both neighbours in a ring (the halo exchange). Each is timed over
 * batches of `reps` calls; the median over the batches is printed by rank 0, in
 * microseconds per call.
 *
 * Usage: mpirun -n P latency [batches] [reps] */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

static int compare(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n)
{
  qsort(v, (size_t)n, sizeof *v, compare);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int main(int argc, char **argv)
{
  int batches = argc > 1 ? atoi(argv[1]) : 21;
  int reps = argc > 2 ? atoi(argv[2]) : 2000;
  int rank = 0, size = 1;
  if (batches < 1 || reps < 1) {
    fprintf(stderr, "latency: batches and reps must be positive\n");
    return 2;
  }
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  double *t_reduce = malloc(sizeof(double) * (size_t)batches);
  double *t_halo = malloc(sizeof(double) * (size_t)batches);
  if (!t_reduce || !t_halo) {
    fprintf(stderr, "latency: out of memory\n");
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  int left = (rank + size - 1) % size, right = (rank + 1) % size;
  double x = rank, sum = 0.0, out[2] = {rank, 1.0}, in[2];
  for (int b = 0; b < batches; b++) {
    MPI_Barrier(MPI_COMM_WORLD);
    double t0 = MPI_Wtime();
    for (int i = 0; i < reps; i++)
      MPI_Allreduce(&x, &sum, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    t_reduce[b] = (MPI_Wtime() - t0) / reps;
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = MPI_Wtime();
    for (int i = 0; i < reps; i++) {
      MPI_Sendrecv(out, 2, MPI_DOUBLE, right, 1, in, 2, MPI_DOUBLE, left, 1, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE);
      MPI_Sendrecv(out, 2, MPI_DOUBLE, left, 2, in, 2, MPI_DOUBLE, right, 2, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE);
    }
    t_halo[b] = (MPI_Wtime() - t0) / reps;
  }
  if (rank == 0)
    printf("ranks %d allreduce_us %.3f halo_exchange_us %.3f (medians of %d batches of %d)\n",
           size, 1e6 * median(t_reduce, batches), 1e6 * median(t_halo, batches), batches, reps);
  free(t_reduce);
  free(t_halo);
  MPI_Finalize();
  return 0;
}
