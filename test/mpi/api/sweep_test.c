/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The C interface of the MPI component (hcimpact_mpi.h), run under mpirun with any
 * number of ranks: hcimpact_mpi_impact_sweep's outcomes and statuses on rank 0, byte
 * for byte those of hcimpact_impact called for each contact, with failing contacts
 * among good ones; the result the same on every rank; statuses NULL; n = 0 with NULL
 * arrays; fewer items than ranks; NULL arrays with n > 0 and n above INT_MAX
 * (HCIMPACT_ERR_NULL, HCIMPACT_ERR_SIZE on every rank, nothing written); the other
 * ranks' arguments never read (they pass garbage counts and NULL). Exit status 1 on
 * any failure.
 */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hcimpact_mpi.h"

static int rank, failures;

static void expect(const char *what, int ok)
{
    if (ok) return;
    failures++;
    fprintf(stderr, "FAIL (rank %d): %s\n", rank, what);
}

/* n contacts of many costs, every 89th one bad (negative mass, NaN velocity,
 * negative damping, an exponent beyond the quadrature's bound) */
static void fill(hcimpact_contact *c, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        c[i].mass = 0.05;
        c[i].stiffness = 2.0e7;
        c[i].exponent = 1.0 + (double)(i % 7) / 4.0;
        c[i].damping = 0.1 * (double)(i % 5);
        c[i].velocity = pow(10.0, -3.0 + 6.0 * (double)i / (double)(n > 0 ? n : 1));
        if (i % 89 != 88) continue;
        switch ((i / 89) % 4) {
        case 0: c[i].mass = -1.0; break;
        case 1: c[i].velocity = nan(""); break;
        case 2: c[i].damping = -0.5; break;
        default: c[i].exponent = 150.0; break;
        }
    }
}

/* A sweep of n contacts against hcimpact_impact on rank 0; the other ranks pass
 * `other_n` and NULL. */
static void check_sweep(const char *what, size_t n, size_t other_n, int with_statuses)
{
    hcimpact_contact *contacts = NULL;
    hcimpact_outcome *outcomes = NULL, *expected = NULL;
    int *statuses = NULL, *expected_statuses = NULL;
    int result, expected_result = HCIMPACT_OK, all_same, lowest, highest;
    char text[200];
    if (rank == 0 && n > 0) {
        contacts = malloc(n * sizeof *contacts);
        outcomes = malloc(n * sizeof *outcomes);
        expected = malloc(n * sizeof *expected);
        statuses = malloc(n * sizeof *statuses);
        expected_statuses = malloc(n * sizeof *expected_statuses);
        if (!contacts || !outcomes || !expected || !statuses || !expected_statuses) {
            fprintf(stderr, "out of memory\n");
            MPI_Abort(MPI_COMM_WORLD, 1);
        }
        fill(contacts, n);
        memset(outcomes, 0xab, n * sizeof *outcomes);
        for (size_t i = 0; i < n; i++) statuses[i] = -1;
    }
    result = hcimpact_mpi_impact_sweep(MPI_Comm_c2f(MPI_COMM_WORLD), rank == 0 ? n : other_n,
                                       contacts, outcomes, with_statuses ? statuses : NULL);
    MPI_Allreduce(&result, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(&result, &highest, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    snprintf(text, sizeof text, "%s: the same result on every rank", what);
    expect(text, lowest == highest);
    if (rank == 0) {
        all_same = 1;
        for (size_t i = 0; i < n; i++) {
            expected_statuses[i] = hcimpact_impact(&contacts[i], &expected[i]);
            if (expected_statuses[i] != HCIMPACT_OK && expected_result == HCIMPACT_OK)
                expected_result = expected_statuses[i];
            if (memcmp(&outcomes[i], &expected[i], sizeof expected[i]) != 0) all_same = 0;
            if (with_statuses && statuses[i] != expected_statuses[i]) all_same = 0;
            if (!with_statuses && statuses[i] != -1) all_same = 0;
        }
        snprintf(text, sizeof text, "%s: outcomes and statuses byte for byte", what);
        expect(text, all_same);
        snprintf(text, sizeof text, "%s: result %d, expected %d", what, result,
                 expected_result);
        expect(text, result == expected_result);
    }
    free(contacts);
    free(outcomes);
    free(expected);
    free(statuses);
    free(expected_statuses);
}

/* Arguments refused on rank 0: every rank gets `status`, nothing is written. */
static void check_refused(const char *what, size_t n, int null_contacts, int null_outcomes,
                          int status)
{
    hcimpact_contact contacts[4];
    hcimpact_outcome outcomes[4], untouched[4];
    int statuses[4] = {-1, -1, -1, -1};
    int result, lowest, highest;
    char text[200];
    fill(contacts, 4);
    memset(outcomes, 0xab, sizeof outcomes);
    memcpy(untouched, outcomes, sizeof outcomes);
    result = hcimpact_mpi_impact_sweep(MPI_Comm_c2f(MPI_COMM_WORLD), rank == 0 ? n : 0,
                                       null_contacts ? NULL : contacts,
                                       null_outcomes ? NULL : outcomes, statuses);
    MPI_Allreduce(&result, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(&result, &highest, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    snprintf(text, sizeof text, "%s: status %d on every rank (lowest %d, highest %d)", what,
             status, lowest, highest);
    expect(text, lowest == status && highest == status);
    snprintf(text, sizeof text, "%s: nothing written", what);
    expect(text, memcmp(outcomes, untouched, sizeof outcomes) == 0 && statuses[0] == -1
                 && statuses[3] == -1);
}

int main(int argc, char **argv)
{
    int ranks, worst;
    MPI_Init(&argc, &argv);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);

    check_sweep("3000 contacts, failures among them", 3000, 12345, 1);
    check_sweep("statuses NULL", 700, 0, 0);
    check_sweep("n = 0, NULL arrays", 0, 99, 1);
    check_sweep("one contact", 1, 5, 1);
    check_sweep("two contacts", 2, 0, 1);
    check_refused("contacts NULL", 4, 1, 0, HCIMPACT_ERR_NULL);
    check_refused("outcomes NULL", 4, 0, 1, HCIMPACT_ERR_NULL);
    check_refused("n above INT_MAX", (size_t)INT_MAX + 1, 0, 0, HCIMPACT_ERR_SIZE);

    MPI_Allreduce(&failures, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (rank == 0) printf("mpi sweep C test: %d ranks, %d failures\n", ranks, worst);
    MPI_Finalize();
    return worst == 0 ? 0 : 1;
}
