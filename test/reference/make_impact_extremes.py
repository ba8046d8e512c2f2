#!/usr/bin/env python3
"""High-precision references for one impact at the extremes of its inputs (issue 13).

Writes, next to this script:
  impact_extremes.csv    the outputs of impact.csv (same columns, same methods) for
                         beta = b V up to max_beta = 1e40, masses, stiffnesses and speeds
                         over the double range, exponents 0.05 ... 10
  timelaw_extremes.csv   x(t), x'(t), F(t) (same columns as timelaw.csv; case_id = row
                         of impact_extremes.csv), with points early in compression
  velocity_extremes.csv  x'(x) on both branches at exact double depths x, from x = 0
                         to x_max (case_id, x, branch, v_hi, v_lo)

The impact and time-law values come from make_impact.py's compute_case (method A, the
log-velocity variable at 50 digits, checked against method B, the position variable
with Lambert W at 40 digits, to 1e-25). The velocity at a depth is u(h(beta) Yb)/beta
with Yb = 1 - (x/x_max)^(n+1), u from Lambert W at raised precision (method B's root),
checked by the residual of the first integral h(u) = h(beta) Yb at 80 digits.
Format: IMPACT.md. Deterministic (own seeds). Usage:
    python3 make_impact_extremes.py          # about 15 minutes, 2 processes
"""
import math
import multiprocessing
import os
import random
import sys
import time

import mpmath as M
from mpmath import mp, mpf

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import make_impact as MI   # noqa: E402

SEED = 20250713
DBL_MAX = sys.float_info.max
# points early in compression (fractions of the compression time), beyond make_impact's
EARLY = [1e-12, 1e-6, 1e-5, 1e-4, 3e-3, 0.01, 0.02, 0.1]
VEL_FRACS = [0.0, 1e-300, 1e-12, 1e-6, 1e-3, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.999,
             1 - 1e-6, 1 - 1e-12, 1.0]


def estimate(m, c, n, V, b):
    """log10 of x_max, the time unit x_max/V, the force unit c x_max^n (1 + beta) and
    of the energy (n+1) m V^2 H (doubles, for choosing representable cases)."""
    beta = b * V
    if beta == 0:
        H = 0.5
    elif beta < 1e-4:
        H = 0.5 - beta / 3
    else:
        H = (beta - math.log1p(beta)) / (beta * beta)
    lx = (math.log10(n + 1) + math.log10(m) + 2 * math.log10(V) + math.log10(H)
          - math.log10(c)) / (n + 1)
    lt = lx - math.log10(V) - math.log10(max(H, 1e-300)) + 1
    lf = math.log10(c) + n * lx + math.log10(1 + beta)
    le = math.log10(n + 1) + math.log10(m) + 2 * math.log10(V) + math.log10(H)
    return lx, lt, lf, le


def representable(m, c, n, V, b, margin=20):
    lims = 307 - margin
    return all(abs(v) < lims for v in estimate(m, c, n, V, b))


def make_cases():
    rng = random.Random(SEED)
    cases = []
    # the steel ball of MODEL.md at very large beta: V up to 1e40 (beta = 1e39), and
    # b up to max_beta at V = 1 (issue 13: compression time 0 above beta = 4e33)
    for V in (1e7, 1e13, 1e20, 1e30, 1e40):
        cases.append(dict(m=0.1, c=1.7135e10, n=1.5, V=V, b=0.1, tag="steel-big-beta"))
    for b in (1e33, 4e33, 1e34, 1e40):
        cases.append(dict(m=0.1, c=1.7135e10, n=1.5, V=1.0, b=b, tag="steel-big-beta"))
    # beta log-uniform in [1e6, 1e40]
    fixed_n = [0.1, 0.5, 1.0, 1.5, 3.0, 10.0]
    for j in range(48):
        n = fixed_n[j % 6] if j < 24 else 10.0 ** rng.uniform(-1, 1)
        beta = 10.0 ** rng.uniform(6, 40)
        while True:
            m = 10.0 ** rng.uniform(-6, 3)
            c = 10.0 ** rng.uniform(3, 13)
            V = 10.0 ** rng.uniform(-6, 3)
            if representable(m, c, n, V, beta / V):
                break
        cases.append(dict(m=m, c=c, n=n, V=V, b=beta / V, tag="big-beta"))
    # masses, stiffnesses and speeds over the double range, every beta
    for j in range(64):
        n = 10.0 ** rng.uniform(-1, 1) if j % 4 else rng.choice([1.0, 1.5, 2.0])
        u = rng.random()
        while True:
            m = 10.0 ** rng.uniform(-250, 250)
            c = 10.0 ** rng.uniform(-250, 250)
            V = 10.0 ** rng.uniform(-120, 120)
            if u < 0.1:
                b = 0.0
            elif u < 0.2:
                b = 10.0 ** rng.uniform(-300, -8) / V
            else:
                b = 10.0 ** rng.uniform(-8, 8) / V
            if representable(m, c, n, V, b) and b < DBL_MAX:
                break
        cases.append(dict(m=m, c=c, n=n, V=V, b=b, tag="wide-range"))
    # issue 13's contacts: the peak of a user law (m = 1e300, b = 1e-300, c = 3.2e304
    # with n = 0.05), the damping DBL_MAX
    cases.append(dict(m=1e300, c=1.7135e10, n=1.5, V=5.0, b=0.1, tag="issue13"))
    cases.append(dict(m=0.1, c=1.7135e10, n=1.5, V=5.0, b=1e-300, tag="issue13"))
    cases.append(dict(m=10132144.0, c=3.198e304, n=0.05, V=1.0, b=8.88e-16, tag="issue13"))
    cases.append(dict(m=1.3e-18, c=1.13e-306, n=1.500001, V=2.4e-310, b=DBL_MAX,
                      tag="issue13"))
    # the damping DBL_MAX with every output inside the double range
    cases.append(dict(m=1e300, c=7e-270, n=1.5, V=2.4e-310, b=DBL_MAX, tag="issue13"))
    # large exponents (the quadratures' weight (1 - x^2)^(-n/(n+1)) near its limit)
    for n in (20.0, 50.0, 100.0, 200.0, 1000.0):
        for beta in (0.0, 0.1, 5.0, 1e4):
            cases.append(dict(m=0.1, c=1.7135e10, n=n, V=1.0, b=beta, tag="large-n"))
    # the time law: exponents 0.5 ... 6 at beta = 0.01 ... 1e5, with points early in
    # compression, and issue 13's contact at beta = 1e4 at its time of the peak
    combos = [(2.5e-12, 6e5, 5e-5), (0.1, 1.7e10, 1.0), (30.0, 4e7, 20.0)]
    j = 0
    for n in (0.5, 1.0, 1.5, 3.0, 6.0):
        for beta in (0.01, 1.0, 30.0, 1e3, 1e4, 1e5):
            m, c, V = combos[j % 3]
            j += 1
            beta = beta * (1 + 0.3 * rng.random())
            cases.append(dict(m=m, c=c, n=n, V=V, b=beta / V, tag="timelaw",
                              tl_fracs=EARLY))
    cases.append(dict(m=2.5476085925512183e-12, c=591848.3479628453, n=1.5,
                      V=4.7916356680899754e-05, b=208697002.29078904, tag="timelaw",
                      tl_fracs=EARLY, tl_times=[2.6842756814519497e-08]))
    # two contacts of the trapping build's sweep: x_max = 3.6e282 (the time unit's
    # product with 1/H overflowed before its quotient by V), and beta = 2.1e38 with
    # n = 9.3 (d R(d) underflowed next to the end of contact)
    cases.append(dict(m=2.29562955624599565e183, c=1.72121672058806109e-67,
                      n=0.936194925387041965, V=4.08593997108846904e162,
                      b=8.83804562301416088e-135, tag="timelaw"))
    cases.append(dict(m=1.73107294698573407e-203, c=1.43134534168580123e-57,
                      n=9.33407117475858250, V=5.24414686115013018e165,
                      b=3.94631707913109737e-128, tag="timelaw"))
    for cs in cases:
        for key in ("m", "c", "n", "V", "b"):
            cs[key] = float(cs[key])
        assert cs["b"] * cs["V"] <= 1e40
    return cases


def velocity_points(args):
    """x'(x) at x = to_double(f x_max) on both branches."""
    idx, case = args
    mp.dps = MI.DPS_A
    m, c, n, V, b = (mpf(case[k]) for k in ("m", "c", "n", "V", "b"))
    beta = b * V
    np1 = n + 1
    rows = []
    with mp.workdps(MI.DPS_A + 30):
        hb = MI.hB(beta)
        if beta > 0:
            xmax = (np1 * m * hb / (c * b * b)) ** (1 / np1)
        else:
            xmax = (np1 * m * V * V / (2 * c)) ** (1 / np1)
    for f in VEL_FRACS:
        x = MI.to_double(xmax * f)
        if mpf(x) > xmax:
            x = math.nextafter(x, 0.0)
        for branch in (1, 2):
            ph = 1 if branch == 1 else -1
            with mp.workdps(MI.DPS_A + 40):
                Yb = 1 - (mpf(x) / xmax) ** np1
                if beta == 0:
                    v = ph * V * M.sqrt(Yb)
                else:
                    u = MI.uB(hb * Yb, ph)
                    v = V * u / beta
                    # check: the root of g(L) = e^L - 1 - L = h(beta) Yb in L = ln(1 + u),
                    # L > 0 in compression, L < 0 in restitution (no Lambert W, and no
                    # cancellation where u is near -1)
                    t = hb * Yb
                    if t > 0:
                        def g(L):
                            return L * L * MI.G2(L) - t    # e^L - 1 - L, no cancellation
                        if ph > 0:
                            lo, hi = mpf(0), 2 * M.sqrt(2 * t) + M.log1p(t) + 1
                        else:
                            lo, hi = -(t + 2), mpf(0)
                        for _ in range(5000):
                            mid = (lo + hi) / 2
                            if (g(mid) > 0) == (ph > 0):
                                hi = mid
                            else:
                                lo = mid
                            if hi - lo <= mpf(10) ** (-MI.DPS_A - 20) * abs(mid):
                                break
                        uL = M.expm1((lo + hi) / 2)
                        assert abs(uL - u) <= mpf(10) ** (-MI.DPS_A + 5) * abs(u), (idx, f, u, uL)
            hi, lo = MI.hilo(v)
            rows.append("%d,%r,%d,%r,%r" % (idx + 1, x, branch, hi, lo))
    return idx, rows


def main():
    t_start = time.time()
    print("make_impact_extremes.py -> %s" % HERE, flush=True)
    cases = make_cases()
    jobs = [(i, cs, cs["tag"] == "timelaw") for i, cs in enumerate(cases)]
    jobs_sorted = sorted(jobs, key=lambda j: -int(j[2]))
    pool = multiprocessing.Pool(2)
    results = {}
    for j, out in enumerate(pool.imap_unordered(MI.compute_case, jobs_sorted, chunksize=1)):
        results[out["idx"]] = out
        if (j + 1) % 10 == 0:
            print("  impact %d/%d (%.0f s)" % (j + 1, len(jobs), time.time() - t_start),
                  flush=True)
    vel_ids = [i for i, cs in enumerate(cases) if cs["tag"] != "timelaw"]
    vel = {}
    for idx, rows in pool.imap_unordered(velocity_points, [(i, cases[i]) for i in vel_ids]):
        vel[idx] = rows
    pool.close()
    pool.join()
    res = [results[i] for i in range(len(cases))]
    header = ["m", "c", "n", "V", "b"]
    for key in MI.OUT_NAMES:
        header += [key + "_hi", key + "_lo"]
    stamp = "# generated by make_impact_extremes.py (mpmath %s, %d digits)" % (
        M.__version__, MI.DPS_A)
    with open(os.path.join(HERE, "impact_extremes.csv"), "w") as fh:
        fh.write("# hcimpact reference: one impact at the extremes of its inputs (beta up "
                 "to 1e40, m, c, V over the double range); see IMPACT.md\n")
        fh.write(stamp + "; outputs as hi,lo double pairs (SI units)\n")
        fh.write(",".join(header) + "\n")
        for r in res:
            fh.write(r["row"] + "\n")
    ntl = 0
    with open(os.path.join(HERE, "timelaw_extremes.csv"), "w") as fh:
        fh.write("# hcimpact reference: time law x(t), V(t), F(t) = c x^n (1 + b V) at the "
                 "extremes; case_id = data row of impact_extremes.csv; see IMPACT.md\n")
        fh.write(stamp + "; outputs as hi,lo double pairs (SI units)\n")
        fh.write("case_id,t,x_hi,x_lo,v_hi,v_lo,f_hi,f_lo\n")
        for i, cs in enumerate(cases):
            for line in res[i]["tl"]:
                fh.write(line + "\n")
                ntl += 1
    nv = 0
    with open(os.path.join(HERE, "velocity_extremes.csv"), "w") as fh:
        fh.write("# hcimpact reference: velocity x'(x) at the depth x on the compression "
                 "(branch 1) and restitution (2) branches; case_id = data row of "
                 "impact_extremes.csv; see IMPACT.md\n")
        fh.write(stamp + "; v as hi,lo double pairs (m/s)\n")
        fh.write("case_id,x,branch,v_hi,v_lo\n")
        for i in vel_ids:
            for line in vel[i]:
                fh.write(line + "\n")
                nv += 1
    worst = max(r["worst"] for r in res)
    tlw = max(r["tl_worst"] for r in res)
    print("impact_extremes.csv: %d rows (max A-vs-B %.3g); timelaw_extremes.csv: %d rows "
          "(A-vs-B %.3g); velocity_extremes.csv: %d rows; %.0f s"
          % (len(res), worst, ntl, tlw, nv, time.time() - t_start))


if __name__ == "__main__":
    main()
