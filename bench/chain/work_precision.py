#!/usr/bin/env python3
"""Work-precision of the struck chain: hcimpact's chain_simulate (shared library, through
bench_chain) against what a user would otherwise write, SciPy's solve_ivp with Radau and
BDF (analytic sparse Jacobian) and DOP853, on the same chain, initial conditions and end
time, errors against a reference (doc/chains-bench.md).

The chain: N touching elastic Hertz beads, the first struck (bench/chain/chain_cases.f90;
its parameters are read from the header of the state files that bench_chain writes).
Bead i is the point q_i (all q_i(0) = 0, touching), the deformation of pair i is
x_i = q_i - q_(i+1), its force c max(x_i, 0)^1.5. SciPy's state is (q_1..q_N, v_1..v_N);
the right-hand side is vectorised NumPy; the Jacobian [[0, I], [K, 0]] is a CSC matrix
with K tridiagonal, built from the same sparsity every call. No events: the answer is
the state at t_end. Tolerances: rtol, and atol = rtol x_ref for positions and rtol v_ref
for velocities, the scales of hcimpact's error weights (v_ref = 2 V, x_ref the maximum
compression of one pair at v_ref).

Reference: SciPy's DOP853 at its tightest rtol (100 eps), cross-checked against hcimpact
(BDF and Adams) at rtol 1e-13, DOP853 at 1e-13 and (N <= 200) Radau at 1e-12
(reference.csv: the differences, which say how far the reference can be trusted; every
solver loses order where a pair opens and closes again, x^1.5 having no second
derivative at 0). Errors: largest |v_i - v_ref_i| / V (velocity error) and
|q_i - q_ref_i| / x_ref. Above N = 200 Radau runs only at rtol >= 1e-8 (SciPy's sparse
LU makes it take minutes beyond).

Rounds: in every round, hcimpact's BDF and Adams at every rtol (one bench_chain process
each; times from the thread's CPU clock inside it, per call) and every SciPy method at every rtol (time.process_time),
in an order reversed every other round. The ratios at equal error are formed per round
by report.py.

Usage: python3 bench/chain/work_precision.py --bench PATH/bench_chain --dir DIR
           [--states STATES] [--n 100] [--t-end 1e-3] [--rounds 5] [--quick]
           [--scipy-methods Radau,BDF,DOP853]
Writes DIR/work_precision_n<N>.csv and DIR/reference_n<N>.csv (the state files of
bench_chain in STATES/states_n<N>/, --states STATES, default DIR).
"""
import argparse
import csv
import io
import math
import os
import subprocess
import sys
import time
import warnings

import numpy as np
import scipy
import scipy.sparse as sp
from scipy.integrate import solve_ivp

HC_RTOLS = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12]
SCIPY_RTOLS = {
    "Radau": [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11],
    "BDF": [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10],
    "DOP853": [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13],
}
REFERENCE_RTOL = 1e-13
SCIPY_TIGHTEST = 100 * np.finfo(float).eps
MIN_SECONDS = 0.05


def read_state(path):
    """Header parameters and (positions, velocities) of a bench_chain state file."""
    params = {}
    with open(path) as fh:
        lines = fh.readlines()
    body = []
    for line in lines:
        if line.startswith("#"):
            key, value = line[1:].strip().split("=", 1)
            params[key.strip()] = float(value)
        else:
            body.append(line)
    rows = list(csv.DictReader(body))
    q = np.array([float(r["position"]) for r in rows])
    v = np.array([float(r["velocity"]) for r in rows])
    return params, q, v


def run_bench(bench, args):
    """Run bench_chain; its CSV rows on standard output as dicts."""
    out = subprocess.run([bench] + [str(a) for a in args], check=True,
                         stdout=subprocess.PIPE, text=True).stdout
    return list(csv.DictReader(io.StringIO(out)))


class Chain:
    """The struck chain for SciPy (module docstring)."""

    def __init__(self, params):
        self.n = int(params["n"])
        self.m = params["mass"]
        self.c = params["stiffness"]
        self.p = params["exponent"]
        self.speed = params["striker_speed"]
        self.t_end = params["t_end"]
        n = self.n
        v_ref = 2.0 * self.speed
        mu = 0.5 * self.m
        self.v_ref = v_ref
        self.x_ref = ((self.p + 1.0) * mu * v_ref ** 2 / (2.0 * self.c)) ** (1.0 / (self.p + 1.0))
        self.y0 = np.zeros(2 * n)
        self.y0[n] = self.speed
        # the Jacobian's sparsity: dq/dt = v (rows 0..n-1, columns n..2n-1); dv/dt = K q
        # (rows n..2n-1, columns 0..n-1), K tridiagonal
        i = np.arange(n)
        j = np.arange(n - 1)
        self.rows = np.concatenate([i, n + i, n + j, n + j + 1])
        self.cols = np.concatenate([n + i, i, j + 1, j])
        self.data = np.zeros(self.rows.size)
        self.data[:n] = 1.0

    def rhs(self, t, y):
        n = self.n
        q = y[:n]
        x = q[:-1] - q[1:]
        f = (self.c / self.m) * np.maximum(x, 0.0) ** self.p
        a = np.zeros(n)
        a[:-1] -= f
        a[1:] += f
        return np.concatenate([y[n:], a])

    def jac(self, t, y):
        n = self.n
        q = y[:n]
        x = q[:-1] - q[1:]
        # k_j / m = dF_j/dx_j / m
        k = (self.p * self.c / self.m) * np.maximum(x, 0.0) ** (self.p - 1.0)
        diag = np.zeros(n)
        diag[:-1] -= k
        diag[1:] -= k
        d = self.data
        d[n:2 * n] = diag
        d[2 * n:3 * n - 1] = k
        d[3 * n - 1:] = k
        return sp.csc_matrix((d, (self.rows, self.cols)), shape=(2 * n, 2 * n))

    def solve(self, method, rtol):
        n = self.n
        atol = np.concatenate([np.full(n, rtol * self.x_ref), np.full(n, rtol * self.v_ref)])
        kw = {"rtol": rtol, "atol": atol}
        if method in ("Radau", "BDF"):
            kw["jac"] = self.jac
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # rtol at 100 eps is SciPy's own floor
            sol = solve_ivp(self.rhs, (0.0, self.t_end), self.y0, method=method, **kw)
        return sol

    def errors(self, q, v, q_ref, v_ref):
        return (float(np.max(np.abs(v - v_ref)) / self.speed),
                float(np.max(np.abs(q - q_ref)) / self.x_ref))


def time_scipy(chain, method, rtol):
    calls = 0
    t0 = time.process_time()
    while True:
        sol = chain.solve(method, rtol)
        calls += 1
        t1 = time.process_time()
        if t1 - t0 >= MIN_SECONDS or not sol.success:
            break
    return (t1 - t0) / calls, calls, sol


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", required=True)
    ap.add_argument("--dir", required=True)
    ap.add_argument("--states", help="where the state files go (default DIR)")
    ap.add_argument("--n", type=int, default=100)
    ap.add_argument("--t-end", type=float, default=1e-3)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--scipy-methods", default=",".join(SCIPY_RTOLS),
                    help="SciPy's methods to time, comma-separated (default: all)")
    a = ap.parse_args()
    methods = [m for m in a.scipy_methods.split(",") if m]
    if not methods or any(m not in SCIPY_RTOLS for m in methods):
        sys.exit("work_precision.py: --scipy-methods takes some of " + ",".join(SCIPY_RTOLS))
    hc_rtols, rounds = HC_RTOLS, a.rounds
    scipy_rtols = {m: SCIPY_RTOLS[m] for m in methods}
    if a.quick:
        hc_rtols = [1e-6, 1e-8]
        scipy_rtols = {m: [1e-6, 1e-8] for m in scipy_rtols}
        rounds = 1
    states = os.path.join(a.states or a.dir, "states_n%d" % a.n)
    refdir = os.path.join(states, "reference")
    os.makedirs(refdir, exist_ok=True)
    common = ["--n", a.n, "--t-end", a.t_end]

    # the reference (SciPy's DOP853 at its tightest rtol) and its cross-checks
    ours_tight = {}
    for integrator in ("bdf", "adams"):
        rows = run_bench(a.bench, ["struck"] + common + [
            "--rtols", REFERENCE_RTOL, "--integrator", integrator, "--min-seconds", 0,
            "--states", refdir])
        ours_tight[integrator] = (rows[0], read_state(rows[0]["state_file"]))
    params = ours_tight["bdf"][1][0]
    chain = Chain(params)
    n = chain.n
    t0 = time.process_time()
    sol = chain.solve("DOP853", SCIPY_TIGHTEST)
    ref_seconds = time.process_time() - t0
    if not sol.success:
        sys.exit("work_precision.py: the reference failed: " + sol.message)
    q_ref, v_ref = sol.y[:n, -1], sol.y[n:, -1]
    ref_steps = sol.t.size - 1
    checks = []
    for integrator, (row, (_, q, v)) in ours_tight.items():
        checks.append(("hcimpact " + integrator, REFERENCE_RTOL, float(row["seconds"]),
                       *chain.errors(q, v, q_ref, v_ref)))
    for method, rtol in (("DOP853", 1e-13), ("Radau", 1e-12)):
        if method == "Radau" and (n > 200 or a.quick or method not in scipy_rtols):
            continue  # minutes with SciPy's sparse LU at this size
        t0 = time.process_time()
        sol = chain.solve(method, rtol)
        seconds = time.process_time() - t0
        if sol.success:
            y = sol.y[:, -1]
            checks.append(("scipy " + method.lower(), rtol, seconds,
                           *chain.errors(y[:n], y[n:], q_ref, v_ref)))
    with open(os.path.join(a.dir, "reference_n%d.csv" % a.n), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["against", "rtol", "seconds", "err_velocity", "err_position", "n",
                    "t_end", "reference", "reference_rtol", "reference_steps",
                    "reference_seconds", "x_ref", "scipy"])
        for name, rtol, seconds, ev, eq in checks:
            w.writerow([name, "%.3e" % rtol, "%.5e" % seconds, "%.5e" % ev, "%.5e" % eq,
                        n, chain.t_end, "scipy dop853", "%.3e" % SCIPY_TIGHTEST, ref_steps,
                        "%.5e" % ref_seconds, "%.6e" % chain.x_ref, scipy.__version__])
    print("reference: DOP853 at rtol %.2e, %d steps; cross-checks: %s" % (
        SCIPY_TIGHTEST, ref_steps, ", ".join("%s %.1e" % (c[0], c[3]) for c in checks)),
        file=sys.stderr, flush=True)
    if n > 200 and "Radau" in scipy_rtols:
        scipy_rtols = dict(scipy_rtols)
        scipy_rtols["Radau"] = [r for r in scipy_rtols["Radau"] if r >= 1e-8]

    with open(os.path.join(a.dir, "work_precision_n%d.csv" % a.n), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["round", "solver", "rtol", "status", "seconds", "calls", "err_velocity",
                    "err_position", "steps", "rhs_evals", "jacobian_evals", "lu", "front"])
        for r in range(1, rounds + 1):
            def ours():
                for integrator in ("bdf", "adams"):
                    rows = run_bench(a.bench, ["struck"] + common + [
                        "--rtols", ",".join("%.0e" % x for x in hc_rtols),
                        "--integrator", integrator, "--min-seconds", MIN_SECONDS,
                        "--states", states])
                    for row in rows:
                        _, q, v = read_state(row["state_file"])
                        ev, eq = chain.errors(q, v, q_ref, v_ref)
                        w.writerow([r, "hcimpact-" + integrator, "%.1e" % float(row["rtol"]),
                                    row["status"], row["seconds"].strip(), row["calls"],
                                    "%.5e" % ev, "%.5e" % eq, row["steps"], row["rhs_evals"],
                                    row["jacobian_evals"], "", row["front"]])

            def theirs():
                for method, rtols in scipy_rtols.items():
                    for rtol in rtols:
                        seconds, calls, sol = time_scipy(chain, method, rtol)
                        ev = eq = -1.0
                        front = ""
                        if sol.success:
                            y = sol.y[:, -1]
                            ev, eq = chain.errors(y[:n], y[n:], q_ref, v_ref)
                            front = int(np.argmax(y[n:])) + 1
                        w.writerow([r, "scipy-" + method.lower(), "%.1e" % rtol,
                                    0 if sol.success else 1, "%.5e" % seconds, calls,
                                    "%.5e" % ev, "%.5e" % eq, sol.t.size - 1, sol.nfev,
                                    sol.njev, sol.nlu, front])
                        fh.flush()

            for part in ((ours, theirs) if r % 2 == 1 else (theirs, ours)):
                part()
            fh.flush()
            print("work-precision: round %d of %d" % (r, rounds), file=sys.stderr, flush=True)


if __name__ == "__main__":
    main()
