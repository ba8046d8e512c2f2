/* SPDX-License-Identifier: Apache-2.0 */
/* Consumer of an installed (or fetched) hcimpact's CVODE component, from C:
 * hcimpact_cvode.h must be found and the program must link libhcimpact_cvode and,
 * for a static library, every SUNDIALS library it needs. Exit status 1 on a wrong
 * value. */
#include <math.h>
#include <stdio.h>

#include "hcimpact_cvode.h"

int main(void)
{
  /* the steel ball of doc/model.md at V = 1 m/s: contact time 1.0399469349496538e-4 s */
  const hcimpact_contact ball = {0.1, 1.7135e10, 1.5, 0.1, 1.0};
  const double rtol = 1e-8;
  hcimpact_outcome out;
  char message[256];
  const int status = hcimpact_simulate_message(&ball, rtol, &out, message, sizeof message);

  printf("hcimpact_simulate: status %d (%s), contact time %.17g s\n", status, message,
         out.contact_time);
  if (status != HCIMPACT_OK
      || !(fabs(out.contact_time - 1.0399469349496538e-4) <= 100 * rtol * 1.04e-4)) {
    printf("FAIL: wrong value\n");
    return 1;
  }
  printf("ok\n");
  return 0;
}
