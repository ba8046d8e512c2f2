// SPDX-License-Identifier: Apache-2.0
// The C entry point hcimpact_chain_simulate under bad arguments, one case per process
// (argv[1] = case number; no argument: list), and 4 threads computing the same system
// at once (case "threads"), which must agree to the bit with a lone call.
// Build: see run_attack_c.sh.
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hcimpact_cvode.h"

static double m2[2] = {1.0, 1.0}, v2[2] = {1.0, 0.0}, g2[1] = {0.01};
static hcimpact_chain_law law2[1] = {{1e9, 1.5, 0.0}};

static void show(const char *name, int status, const hcimpact_chain_result *r, const char *msg,
                 const double *x, int n) {
  printf("%-34s status %2d", name, status);
  if (r) printf(" time %.6g n_contacts %lld E %.3g", r->time, (long long)r->n_contacts, r->energy_error);
  if (x) {
    printf(" x");
    for (int i = 0; i < n && i < 3; i++) printf(" %.6g", x[i]);
  }
  printf(" msg \"%s\"\n", msg ? msg : "(null)");
}

static void run(int which) {
  hcimpact_chain_result r;
  char msg[256] = "untouched";
  double x[3] = {-7, -7, -7}, v[3] = {-7, -7, -7};
  hcimpact_chain_contact c[4];
  hcimpact_chain_options o = {0};
  hcimpact_chain_samples s = {0};
  int st;
  memset(&r, 0x55, sizeof r);
  switch (which) {
    case 0: st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, NULL, NULL, x, v, 4, c, NULL, msg, sizeof msg);
      show("result NULL", st, NULL, msg, x, 2); break;
    case 1: st = hcimpact_chain_simulate(2, NULL, v2, g2, law2, NULL, NULL, 0, NULL, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("masses NULL", st, &r, msg, x, 2); break;
    case 2: st = hcimpact_chain_simulate(0, m2, v2, g2, law2, NULL, NULL, 0, NULL, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("n = 0", st, &r, msg, x, 0); break;
    case 3: st = hcimpact_chain_simulate(-5, m2, v2, g2, law2, NULL, NULL, 0, NULL, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("n = -5", st, &r, msg, x, 0); break;
    case 4: st = hcimpact_chain_simulate(2, m2, v2, NULL, law2, NULL, NULL, 0, NULL, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("gaps NULL, n = 2", st, &r, msg, x, 2); break;
    case 5: st = hcimpact_chain_simulate(2, m2, v2, g2, NULL, NULL, NULL, 0, NULL, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("laws NULL, n = 2", st, &r, msg, x, 2); break;
    case 6: st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, NULL, &r, x, v, 4, NULL, NULL, msg, sizeof msg);
      show("contacts NULL, capacity 4", st, &r, msg, x, 2); break;
    case 7: st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, NULL, &r, x, v, -1, c, NULL, msg, sizeof msg);
      show("capacity -1", st, &r, msg, x, 2); break;
    case 8: s.count = 3; s.times = NULL; s.positions = x;
      st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, NULL, &r, x, v, 4, c, &s, msg, sizeof msg);
      show("samples count 3, times NULL", st, &r, msg, NULL, 2); break;
    case 9: s.count = -1;
      st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, NULL, &r, x, v, 4, c, &s, msg, sizeof msg);
      show("samples count -1", st, &r, msg, x, 2); break;
    case 10: st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, NULL, &r, x, v, 4, c, NULL, NULL, 100);
      show("message NULL, size 100", st, &r, NULL, x, 2); break;
    case 11: st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, NULL, &r, x, v, 4, c, NULL, msg, 1);
      printf("message size 1: status %d, msg[0] = %d\n", st, msg[0]); break;
    case 12: { double bad[1] = {-1}; st = hcimpact_chain_simulate(2, m2, v2, bad, law2, NULL, NULL, 0, NULL, &r, x, v, 4, c, NULL, msg, 5);
      printf("message size 5 (error): status %d, msg \"%s\" (len %zu)\n", st, msg, strlen(msg)); } break;
    case 13: o.t_end = -1.0;
      st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, &o, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("t_end -1 (documented: to the end)", st, &r, msg, x, 2); break;
    case 14: o.t_end = -INFINITY;
      st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, &o, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("t_end -Inf", st, &r, msg, x, 2); break;
    case 15: o.method = 99;
      st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, &o, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("method 99", st, &r, msg, x, 2); break;
    case 16: o.integrator = -1;
      st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, &o, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("integrator -1", st, &r, msg, x, 2); break;
    case 17: o.rtol = -0.0;
      st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, &o, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("rtol -0.0", st, &r, msg, x, 2); break;
    case 18: o.max_steps = -3;
      st = hcimpact_chain_simulate(2, m2, v2, g2, law2, NULL, NULL, 0, &o, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("max_steps -3", st, &r, msg, x, 2); break;
    case 19: { hcimpact_chain_wall w = {1e9, 1.5, 0.0, NAN};
      st = hcimpact_chain_simulate(2, m2, v2, g2, law2, &w, NULL, 0, NULL, &r, x, v, 4, c, NULL, msg, sizeof msg);
      show("left wall gap NaN", st, &r, msg, x, 2);
      printf("   after the error: result time %g energy %g n_contacts %lld; x[0] %g v[0] %g\n", r.time,
             r.energy_error, (long long)r.n_contacts, x[0], v[0]); } break;
    case 20: st = hcimpact_chain_simulate(1, m2, v2, NULL, NULL, NULL, NULL, 0, NULL, &r, NULL, NULL, 0, NULL, NULL, NULL, 0);
      show("n = 1, every optional NULL", st, &r, NULL, NULL, 1); break;
    case 21: { double gg[1] = {0.0}; double tms[3] = {0, 1e-4, 2e-4}; double sx[6], sv[6];
      s.count = 3; s.times = tms; s.positions = sx; s.velocities = sv; s.forces = NULL;
      st = hcimpact_chain_simulate(2, m2, v2, gg, law2, NULL, NULL, 0, NULL, &r, x, v, 4, c, &s, msg, sizeof msg);
      show("samples, forces NULL", st, &r, msg, x, 2); } break;
    case 22: { hcimpact_chain_law l3[2] = {{1e9, 1.5, 0}, {1e9, 1.5, 0}}; double m3[3] = {1, 1, 1}, v3[3] = {1, 0, 0}, g3[2] = {0, 0};
      st = hcimpact_chain_simulate(3, m3, v3, g3, l3, NULL, NULL, 0, NULL, &r, x, v, 1, c, NULL, msg, sizeof msg);
      show("capacity 1, 2 contacts", st, &r, msg, x, 3);
      printf("   recorded %lld of %lld\n", (long long)r.contacts_recorded, (long long)r.n_contacts); } break;
    default: printf("no case %d\n", which); exit(2);
  }
}

enum { THREADS = 4 };
static double tx[THREADS][8], tv[THREADS][8];
static void *worker(void *arg) {
  int k = (int)(size_t)arg;
  double m[8] = {1, 0.5, 2, 1, 0.3, 1, 1, 4}, v[8] = {1, 0, -0.2, 0, 0.5, 0, -1, 0};
  double g[7] = {0, 1e-4, 0, 0, 1e-3, 0, 0};
  hcimpact_chain_law l[7];
  for (int i = 0; i < 7; i++) l[i] = (hcimpact_chain_law){1e9 * (i + 1), 1.5, 0.05 * i};
  hcimpact_chain_wall w = {2e9, 1.5, 0.1, 1e-3};
  hcimpact_chain_result r;
  hcimpact_chain_options o = {0};
  o.t_end = 5e-3;
  o.integrator = (k % 2) ? HCIMPACT_CHAIN_ADAMS : HCIMPACT_CHAIN_BDF;
  int st = hcimpact_chain_simulate(8, m, v, g, l, &w, NULL, -3.0, &o, &r, tx[k], tv[k], 0, NULL, NULL, NULL, 0);
  if (st) printf("thread %d status %d\n", k, st);
  return NULL;
}

int main(int argc, char **argv) {
  if (argc > 1 && strcmp(argv[1], "threads") == 0) {
    for (int round = 0; round < 20; round++) {
      pthread_t t[THREADS];
      for (int k = 0; k < THREADS; k++) pthread_create(&t[k], NULL, worker, (void *)(size_t)k);
      for (int k = 0; k < THREADS; k++) pthread_join(t[k], NULL);
      double sx[8], sv[8];
      memcpy(sx, tx[0], sizeof sx); memcpy(sv, tv[0], sizeof sv);
      double ax[8], av[8];
      memcpy(ax, tx[1], sizeof ax); memcpy(av, tv[1], sizeof av);
      worker((void *)0); worker((void *)1);   // alone
      if (memcmp(sx, tx[0], sizeof sx) || memcmp(sv, tv[0], sizeof sv) || memcmp(ax, tx[1], sizeof ax) ||
          memcmp(av, tv[1], sizeof av) || memcmp(tx[0], tx[2], sizeof sx) || memcmp(tx[1], tx[3], sizeof sx)) {
        printf("threads: round %d DIFFERS\n", round);
        return 1;
      }
    }
    printf("threads: 20 rounds of 4 threads, bit-identical to lone calls\n");
    return 0;
  }
  if (argc < 2) { for (int i = 0; i <= 22; i++) printf("%d\n", i); return 0; }
  run(atoi(argv[1]));
  return 0;
}
