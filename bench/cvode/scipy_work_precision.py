#!/usr/bin/env python3
"""Error against run time of SciPy's solve_ivp (Radau, LSODA, DOP853) on the contacts of
the CVODE benchmark: the same scaled problem, tolerances and events as hcimpact's CVODE
path (components/cvode), so that the curves can share the axes of doc/cvode.md.

    s'' = -((n+1)/2) s^n (1 + beta s'),  s(0) = 0, s'(0) = 1   (s = x/X, tau = t V/X)

Events: s' = 0 (maximum compression), n s' - ((n+1)/2) beta s^(n+1) = 0 (peak force),
s = 0 downwards (end of contact, terminal). Tolerances: rtol, and the absolute
tolerances rtol * s_max for s and rtol * k for s' (s_max = (2 h(beta)/beta^2)^(1/(n+1)),
k the restitution), as in hcimpact_cvode_solver. Radau and LSODA get the analytic
Jacobian. Time: CPU time of the process (time.process_time) per call, median of the
repeats; one repeat calls solve_ivp until 50 ms have passed.

Usage: python3 bench/cvode/scipy_work_precision.py REFERENCE.csv OUT.csv [--quick]
"""
import csv
import math
import statistics
import sys
import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp
from scipy.special import lambertw

METHODS = ("Radau", "LSODA", "DOP853")
RTOLS = [10.0 ** -k for k in range(3, 14)]


def read_reference(path):
    rows = []
    with open(path) as fh:
        lines = [ln for ln in fh if ln.strip() and not ln.startswith("#")]
    for r in csv.DictReader(lines):
        rows.append({k: float(v) for k, v in r.items()})
    return rows


def restitution(beta):
    """k(beta) = -u-/beta, u- the root of h(u) = h(beta) on (-1, 0] (seed eq. 21)."""
    if beta == 0.0:
        return 1.0
    w = lambertw(-(1.0 + beta) * math.exp(-(1.0 + beta)), 0).real
    return (1.0 + w) / beta


def scaled_max_compression(n, beta):
    if beta < 1e-4:
        h = 0.5 - beta / 3.0 + beta * beta / 4.0
    else:
        h = (beta - math.log1p(beta)) / beta / beta
    return (2.0 * h) ** (1.0 / (n + 1.0))


def make_problem(n, beta):
    a = 0.5 * (n + 1.0)

    def rhs(t, y):
        s = max(y[0], 0.0)
        return [y[1], -a * s ** n * (1.0 + beta * y[1])]

    def jac(t, y):
        s = max(y[0], 0.0)
        w = 1.0 + beta * y[1]
        snm1 = s ** (n - 1.0) if (s > 0.0 or n >= 1.0) else 0.0
        return [[0.0, 1.0], [-a * n * snm1 * w, -a * beta * s ** n]]

    def ev_max(t, y):
        return y[1]
    ev_max.direction = -1

    def ev_peak(t, y):
        s = max(y[0], 0.0)
        return n * y[1] - a * beta * s ** (n + 1.0)
    ev_peak.direction = -1

    def ev_end(t, y):
        return y[0]
    ev_end.direction = -1
    ev_end.terminal = True
    return rhs, jac, [ev_max, ev_peak, ev_end]


def run(case, method, rtol):
    m, c, n, V, b = case["m"], case["c"], case["n"], case["V"], case["b"]
    beta = b * V
    a = 0.5 * (n + 1.0)
    X = (a * m * V * V / c) ** (1.0 / (n + 1.0))
    T = X / V
    force_unit = a * m * V * V / X
    k = restitution(beta)
    s_max = scaled_max_compression(n, beta)
    rhs, jac, events = make_problem(n, beta)
    tau_max = 100.0 * (1.0 + s_max * (1.0 + 1.0 / k))
    kw = {"rtol": rtol, "atol": [rtol * s_max, rtol * k], "events": events}
    if method in ("Radau", "LSODA"):
        kw["jac"] = jac
    sol = solve_ivp(rhs, (0.0, tau_max), [0.0, 1.0], method=method, **kw)
    if sol.status != 1 or len(sol.t_events[2]) == 0 or len(sol.t_events[0]) == 0 \
            or len(sol.t_events[1]) == 0:
        return None, sol
    y_end = sol.y_events[2][0]
    y_max = sol.y_events[0][0]
    y_peak = sol.y_events[1][0]
    out = {
        "contact": sol.t_events[2][0] * T,
        "restitution": -y_end[1],
        "x_max": y_max[0] * X,
        "peak_force": force_unit * max(y_peak[0], 0.0) ** n * (1.0 + beta * y_peak[1]),
    }
    return out, sol


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    cases = read_reference(sys.argv[1])
    quick = "--quick" in sys.argv
    repeats, min_seconds = (1, 0.0) if quick else (3, 0.05)
    refs = {"contact": "contact_time", "restitution": "restitution", "x_max": "x_max",
            "peak_force": "peak_force"}
    with open(sys.argv[2], "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["method", "case", "n", "beta", "V", "rtol", "status", "seconds",
                    "err_contact", "err_restitution", "err_x_max", "err_peak_force",
                    "rhs_evals", "jacobian_evals"])
        for ic, case in enumerate(cases, start=1):
            for method in METHODS:
                for rtol in RTOLS:
                    samples = []
                    out = sol = None
                    for _ in range(repeats):
                        calls = 0
                        t0 = time.process_time()
                        while True:
                            out, sol = run(case, method, rtol)
                            calls += 1
                            t1 = time.process_time()
                            if t1 - t0 >= min_seconds:
                                break
                        samples.append((t1 - t0) / calls)
                    seconds = statistics.median(samples)
                    if out is None:
                        errs = [-1.0] * 4
                        status = 11
                    else:
                        status = 0
                        errs = []
                        for key in ("contact", "restitution", "x_max", "peak_force"):
                            hi = case[refs[key] + "_hi"]
                            lo = case[refs[key] + "_lo"]
                            errs.append(abs((out[key] - hi) - lo) / abs(hi))
                    w.writerow(["scipy-" + method.lower(), ic, case["n"], case["b"] * case["V"],
                                case["V"], rtol, status, "%.5e" % seconds]
                               + ["%.5e" % e for e in errs] + [sol.nfev, sol.njev])
                    fh.flush()
            print("case %d of %d (scipy %s)" % (ic, len(cases), scipy.__version__),
                  file=sys.stderr, flush=True)


if __name__ == "__main__":
    main()
