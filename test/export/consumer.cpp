// SPDX-License-Identifier: Apache-2.0
// Consumer of hcimpact from C++: the C header with C linkage, linked by the C++
// compiler (which knows nothing of the Fortran runtime the library needs).
#include <cmath>
#include <cstdio>

#include "hcimpact.h"

int main()
{
  // W0(1), the omega constant, and k(0.5) (doc/model.md: the steel ball at 5 m/s)
  const double w0 = hcimpact_lambert_w0(1.0);
  const double k = hcimpact_restitution(0.5);
  std::printf("C++: W0(1) = %.17g, k(0.5) = %.17g\n", w0, k);
  if (!(std::fabs(w0 - 0.56714329040978387) <= 1e-14)
      || !(std::fabs(k - 0.74843493159743416) <= 1e-15)) {
    std::printf("FAIL: wrong value\n");
    return 1;
  }
  std::printf("ok\n");
  return 0;
}
