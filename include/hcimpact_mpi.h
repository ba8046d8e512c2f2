/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file hcimpact_mpi.h
 * @brief C interface of the MPI component of hcimpact: sweeps of impacts over the
 *        ranks of an MPI communicator.
 *
 * Part of the optional component libhcimpact_mpi, built where MPI for Fortran with
 * its mpi_f08 module is found (CMake option HCIMPACT_WITH_MPI): link it (CMake:
 * hcimpact::mpi, which brings MPI for Fortran; pkg-config: hcimpact-mpi) as well as
 * libhcimpact, and compile with your MPI's C flags (mpicc, or CMake's MPI::MPI_C):
 * this header includes <mpi.h> for MPI_Fint. libhcimpact itself never links MPI.
 * The conventions (units, statuses) are those of hcimpact.h, which this header
 * includes. Fortran: components/mpi/mpi_sweep.f90 (module hcimpact_mpi_sweep), the C
 * wrapper components/mpi/mpi_sweep_capi.f90; doc/mpi.md.
 */
#ifndef HCIMPACT_MPI_H
#define HCIMPACT_MPI_H

#include <stddef.h>
#include <mpi.h>

#include "hcimpact.h"

#ifdef __cplusplus
extern "C" {
#endif

/** hcimpact_impact for each of n contacts, handed out over the ranks of a
 *  communicator: outcomes[i] from contacts[i], bit for bit what hcimpact_impact
 *  computes for contacts[i] on one process, for any number of ranks.
 *
 *  Collective: every rank of comm calls it (comm is a Fortran handle, e.g.
 *  MPI_Comm_c2f(MPI_COMM_WORLD)). Only rank 0's n, contacts, outcomes and statuses
 *  are read; the other ranks' are ignored (pass 0 and NULL) and those ranks write
 *  nothing. Rank 0 cuts the contacts into chunks and sends them to the other ranks
 *  as they ask for more (point-to-point, on a duplicate of comm), and computes some
 *  itself; the other ranks return when the sweep is over. Where MPI is not
 *  initialized (or is finalized) the impacts are computed on the calling process.
 *
 *  Memory: the caller owns every array; contacts[n] is only read, outcomes[n]
 *  (and statuses[n], which may be NULL) written on rank 0 only. The call allocates
 *  its own working copies (on rank 0 about 140 bytes per contact, 110 kB and
 *  82 kB per other rank; about 400 kB on each other rank) and frees them before it
 *  returns; nothing is kept between
 *  calls, and nothing is allocated for the caller to free.
 *
 *  Returns, on every rank the same value:
 *  HCIMPACT_OK (0)         every impact succeeded (n = 0 included),
 *  the status of the first (lowest index) impact that failed: that impact's outcome
 *                          is NaN and its status in statuses[i]; the others are
 *                          computed regardless (statuses as for hcimpact_impact),
 *  HCIMPACT_ERR_NULL (10)  contacts or outcomes NULL with n > 0 (nothing written),
 *  HCIMPACT_ERR_SIZE (14)  n above INT_MAX (nothing written),
 *  HCIMPACT_ERR_OUT_OF_MEMORY (16) no memory on rank 0 for the working copies
 *                          (nothing written).
 *  A rank that dies ends the job through MPI's error handler. */
HCIMPACT_API int hcimpact_mpi_impact_sweep(MPI_Fint comm, size_t n,
                                           const hcimpact_contact *contacts,
                                           hcimpact_outcome *outcomes, int *statuses);

#ifdef __cplusplus
}
#endif

#endif /* HCIMPACT_MPI_H */
