/* SPDX-License-Identifier: Apache-2.0 */
/* Consumer of an installed hcimpact, from C: hcimpact.h must be found and the
 * program must link against the Fortran library. Exit status 1 on a wrong value. */
#include <math.h>
#include <stdio.h>

#include "hcimpact.h"

int main(void)
{
  /* W0(1), the omega constant (mpmath, 30 digits) */
  const double omega = 0.56714329040978387;
  const double w0 = hcimpact_lambert_w0(1.0);

  printf("hcimpact %d.%d.%d (HCIMPACT_VERSION %d)\n", HCIMPACT_VERSION_MAJOR,
         HCIMPACT_VERSION_MINOR, HCIMPACT_VERSION_PATCH, HCIMPACT_VERSION);
  printf("W0(1) = %.17g\n", w0);
  if (!(fabs(w0 - omega) <= 1.0e-14)) {
    printf("FAIL: wrong value\n");
    return 1;
  }
  printf("ok\n");
  return 0;
}
