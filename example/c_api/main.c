/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The seed's steel ball through the C interface of hcimpact: a steel ball of
 * m = 0.1 kg strikes a massive steel plate (Hertz law c x^1.5, c = 1.7135e10 N/m^1.5,
 * damping b = 0.1 s/m) at V = 0.5 ... 5 m/s. For each speed: the coefficient of
 * restitution k, the maximum compression, the peak force, the contact time and the
 * compression time (MODEL.md, "The seed's worked example").
 *
 * Build against an installed hcimpact:
 *   cc $(pkg-config --cflags hcimpact) main.c $(pkg-config --libs hcimpact) -o steel_ball
 * (with a static libhcimpact.a add: pkg-config --static --libs hcimpact)
 */
#include <stdio.h>

#include "hcimpact.h"

int main(void)
{
  const double speeds[6] = {0.5, 1.0, 2.0, 3.0, 4.0, 5.0};
  hcimpact_contact contacts[6];
  hcimpact_outcome outcomes[6];
  int statuses[6];
  int i, status;

  if (hcimpact_version_number() != HCIMPACT_VERSION) {
    fprintf(stderr, "header %d and library %d differ\n", HCIMPACT_VERSION,
            hcimpact_version_number());
    return 1;
  }
  printf("hcimpact %s: steel ball on a steel plate, m = 0.1 kg, c = 1.7135e10 N/m^1.5,\n"
         "n = 1.5, b = 0.1 s/m\n\n",
         hcimpact_version());

  for (i = 0; i < 6; ++i) {
    contacts[i].mass = 0.1;          /* kg */
    contacts[i].stiffness = 1.7135e10; /* N/m^1.5 */
    contacts[i].exponent = 1.5;      /* Hertz */
    contacts[i].damping = 0.1;       /* s/m */
    contacts[i].velocity = speeds[i]; /* m/s */
  }

  /* one call for the whole table; hcimpact_impact(&contacts[i], &outcomes[i]) does one */
  status = hcimpact_impact_array(6, contacts, outcomes, statuses);
  if (status != HCIMPACT_OK) {
    fprintf(stderr, "hcimpact_impact_array: %s\n", hcimpact_status_message(status));
    return 1;
  }

  printf("%-6s %-20s %-24s %-20s %-24s %-24s\n", "V m/s", "k", "x_max m", "F_max N",
         "t_contact s", "t_compression s");
  for (i = 0; i < 6; ++i) {
    printf("%-6.1f %-20.17g %-24.17g %-20.17g %-24.17g %-24.17g\n", speeds[i],
           outcomes[i].restitution, outcomes[i].max_compression, outcomes[i].peak_force,
           outcomes[i].contact_time, outcomes[i].compression_time);
  }

  /* b for a target restitution: e = 0.5 at 5 m/s */
  {
    double damping;
    status = hcimpact_damping_for_restitution(0.5, 5.0, HCIMPACT_DEFAULT_MIN_VELOCITY,
                                              &damping);
    if (status != HCIMPACT_OK) {
      fprintf(stderr, "hcimpact_damping_for_restitution: %s\n",
              hcimpact_status_message(status));
      return 1;
    }
    printf("\nk = 0.5 at 5 m/s needs b = %.17g s/m\n", damping);
  }
  return 0;
}
