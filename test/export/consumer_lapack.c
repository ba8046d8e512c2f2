/* SPDX-License-Identifier: Apache-2.0 */
/* Consumer of an installed (or fetched) hcimpact's LAPACK component, from C:
 * hcimpact_lapack.h must be found and the program must link libhcimpact_lapack and,
 * for a static library, LAPACK. Exit status 1 on a wrong value. */
#include <math.h>
#include <stdio.h>

#include "hcimpact_lapack.h"

int main(void)
{
  /* restitution of the exact law at b = 0.1 s/m: the fit must give b back */
  const double damping = 0.1;
  double velocity[5] = {0.5, 1.0, 2.0, 3.0, 5.0};
  double restitution[5];
  double fitted = 0.0;
  int i, status;

  for (i = 0; i < 5; ++i) restitution[i] = hcimpact_restitution(damping * velocity[i]);
  status = hcimpact_fit_damping(5, velocity, restitution, NULL, 0, &fitted, NULL, NULL);
  printf("hcimpact_fit_damping: status %d, b = %.17g s/m\n", status, fitted);
  if (status != HCIMPACT_OK || !(fabs(fitted - damping) <= 1e-12)) {
    printf("FAIL: wrong value\n");
    return 1;
  }
  printf("ok\n");
  return 0;
}
