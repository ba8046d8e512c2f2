/* SPDX-License-Identifier: Apache-2.0 */
/*
 * include/hcimpact.h, hcimpact_cvode.h and hcimpact_lapack.h must compile cleanly as C99 (gcc -std=c99 -Wall -Wextra
 * -pedantic -Werror) and as C++ (g++ -Wall -Wextra -Werror), and its functions must
 * have C linkage in C++ (the extern "C" guards): CTest compiles this file both ways
 * and links and runs the C++ build against the library. Every declared function is
 * referenced, so that a declaration that does not compile, or a C++ name that does
 * not link, fails the test. The component functions (CVODE, LAPACK) are referenced
 * only with HCIMPACT_CHECK_COMPONENTS (compile-only checks: they are in other
 * libraries).
 */
#include <stdio.h>
#include <string.h>

#include "hcimpact.h"
#include "hcimpact_cvode.h"
#include "hcimpact_lapack.h"
/* each header twice: the include guards */
#include "hcimpact.h"
#include "hcimpact_cvode.h"
#include "hcimpact_lapack.h"

typedef double (*scalar_fn)(double);
typedef int (*array_fn)(int, const double *, double *);

int main(void)
{
  const scalar_fn scalars[] = {
      hcimpact_lambert_w0, hcimpact_lambert_wm1, hcimpact_lambert_w0p1,
      hcimpact_lambert_wm1p1, hcimpact_restitution, hcimpact_restitution_inverse,
      hcimpact_one_minus_restitution, hcimpact_energy_loss_ratio,
      hcimpact_restitution_derivative, hcimpact_u_minus_log1p};
  const array_fn arrays[] = {
      hcimpact_lambert_w0_array, hcimpact_lambert_wm1_array, hcimpact_lambert_w0p1_array,
      hcimpact_lambert_wm1p1_array, hcimpact_restitution_array,
      hcimpact_restitution_inverse_array, hcimpact_one_minus_restitution_array,
      hcimpact_energy_loss_ratio_array, hcimpact_restitution_derivative_array};
  /* the exact signatures (a changed declaration breaks these initialisations) */
  const char *(*status_message)(int) = hcimpact_status_message;
  const char *(*version)(void) = hcimpact_version;
  int (*version_number)(void) = hcimpact_version_number;
  int (*damping_for_restitution)(double, double, double, double *) =
      hcimpact_damping_for_restitution;
  double (*hertz_constant)(double, double, double, double, double, double) =
      hcimpact_hertz_constant;
  double (*effective_mass)(double, double) = hcimpact_effective_mass;
  int (*two_body_velocities)(double, double, double, double, double, double *, double *) =
      hcimpact_two_body_velocities;
  int (*impact)(const hcimpact_contact *, hcimpact_outcome *) = hcimpact_impact;
  int (*impact_array)(int, const hcimpact_contact *, hcimpact_outcome *, int *) =
      hcimpact_impact_array;
  int (*velocity_at_depth)(const hcimpact_contact *, double, int, double *) =
      hcimpact_velocity_at_depth;
  int (*velocity_at_depth_array)(const hcimpact_contact *, int, const double *, int,
                                 double *) = hcimpact_velocity_at_depth_array;
  int (*time_law)(const hcimpact_contact *, int, const double *, double *, double *,
                  double *) = hcimpact_time_law;
  int (*time_law_samples)(const hcimpact_contact *, int, double *, double *, double *,
                          double *) = hcimpact_time_law_samples;
#ifdef HCIMPACT_CHECK_COMPONENTS
  int (*simulate)(const hcimpact_contact *, double, hcimpact_outcome *) = hcimpact_simulate;
  int (*simulate_message)(const hcimpact_contact *, double, hcimpact_outcome *, char *, size_t) =
      hcimpact_simulate_message;
  int (*fit_damping)(int, const double *, const double *, const double *, int, double *,
                     double *, double *) = hcimpact_fit_damping;
  int (*fit_damping_linear)(int, const double *, const double *, const double *, int,
                            double *, double *, double *) = hcimpact_fit_damping_linear;
  int (*fit_static)(int, const double *, const double *, const double *, int, double *,
                    double *, double *) = hcimpact_fit_static;
  int (*fit_elastic)(int, double, double, const double *, const double *, const double *,
                     const double *, const double *, int, const double *, double *,
                     double *, double *) = hcimpact_fit_elastic;
  int (*fit_impact)(int, double, const double *, const double *, const double *,
                    const double *, const double *, const double *, const double *, int,
                    const double *, double *, double *, double *) = hcimpact_fit_impact;
  int (*chain_simulate)(int, const double *, const double *, const double *,
                        const hcimpact_chain_law *, const hcimpact_chain_wall *,
                        const hcimpact_chain_wall *, double, const hcimpact_chain_options *,
                        hcimpact_chain_result *, double *, double *, int,
                        hcimpact_chain_contact *, hcimpact_chain_samples *, char *, size_t) =
      hcimpact_chain_simulate;
  int (*chain_simulate_monitored)(int, const double *, const double *, const double *,
                                  const hcimpact_chain_law *, const hcimpact_chain_wall *,
                                  const hcimpact_chain_wall *, double,
                                  const hcimpact_chain_options *, hcimpact_chain_result *,
                                  double *, double *, int, hcimpact_chain_contact *,
                                  hcimpact_chain_samples *, const hcimpact_chain_monitor *,
                                  char *, size_t) = hcimpact_chain_simulate_monitored;
#endif
  typedef void (*any_fn)(void);
  const any_fn others[] = {
      (any_fn)status_message, (any_fn)version, (any_fn)version_number,
      (any_fn)damping_for_restitution, (any_fn)hertz_constant, (any_fn)effective_mass,
      (any_fn)two_body_velocities, (any_fn)impact, (any_fn)impact_array,
      (any_fn)velocity_at_depth, (any_fn)velocity_at_depth_array, (any_fn)time_law,
      (any_fn)time_law_samples
#ifdef HCIMPACT_CHECK_COMPONENTS
      ,
      (any_fn)simulate, (any_fn)simulate_message, (any_fn)fit_damping, (any_fn)fit_damping_linear, (any_fn)fit_static,
      (any_fn)fit_elastic, (any_fn)fit_impact, (any_fn)chain_simulate,
      (any_fn)chain_simulate_monitored
#endif
  };
  hcimpact_contact contact = {0.1, 1.7135e10, 1.5, 0.1, 5.0};
  hcimpact_outcome outcome;
  double k = 0.0;
  unsigned i;
  int status;

  for (i = 0; i < sizeof scalars / sizeof scalars[0]; ++i) {
    if (scalars[i] == NULL) return 1;
  }
  for (i = 0; i < sizeof arrays / sizeof arrays[0]; ++i) {
    if (arrays[i](1, &contact.damping, &k) != HCIMPACT_OK) return 1;
  }
  for (i = 0; i < sizeof others / sizeof others[0]; ++i) {
    if (others[i] == NULL) return 1;
  }
  status = hcimpact_impact(&contact, &outcome);
  if (status != HCIMPACT_OK || hcimpact_version_number() != HCIMPACT_VERSION
      || strcmp(hcimpact_status_message(HCIMPACT_OK), "success") != 0) {
    printf("header check: hcimpact_impact gave %d (%s)\n", status,
           hcimpact_status_message(status));
    return 1;
  }
  printf("hcimpact.h %d, library %s: k = %.17g at V = 5 m/s\n", HCIMPACT_VERSION,
         hcimpact_version(), outcome.restitution);
  return 0;
}
