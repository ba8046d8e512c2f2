# SPDX-License-Identifier: Apache-2.0
"""Random small systems (N = 2..8): hcimpact.chain against the SciPy reference (ref.py).

Usage: python3 run_random.py FIRST_SEED COUNT [--rtol-ref 1e-12] [--method auto]
Prints one line per case and a summary; cases whose error exceeds 1e-6 are flagged BAD.
"""
import argparse
import json
import math
import signal
import sys
import time

import numpy as np

import hcimpact
import ref


def draw(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 9))
    masses = 10 ** rng.uniform(-3, 0, n)
    vel = rng.uniform(-1, 1, n)
    vel[rng.random(n) < 0.2] = 0.0
    kinds = rng.integers(0, 3, n - 1)
    gaps = np.where(kinds == 0, 0.0, np.where(kinds == 1, 10 ** rng.uniform(-7, -5, n - 1),
                                              10 ** rng.uniform(-3, -2, n - 1)))

    def law():
        c = 10 ** rng.uniform(4, 10)
        e = [1.0, 1.5, 2.0, rng.uniform(1, 3)][int(rng.integers(0, 4))]
        b = 0.0 if rng.random() < 0.5 else 10 ** rng.uniform(-2, 0)
        return c, e, b
    laws = [law() for _ in range(n - 1)]
    finite = rng.random() < 0.5
    g = 0.0
    wl = wr = None
    wallmode = int(rng.integers(0, 4))    # 0 none, 1 left, 2 right, 3 both
    if rng.random() < 0.4:
        g = float(rng.choice([-1, 1]) * rng.uniform(1, 20))

    def wall():
        c, e, b = law()
        kind = int(rng.integers(0, 3))
        gap = [0.0, 10 ** rng.uniform(-7, -5), 10 ** rng.uniform(-3, -2)][kind]
        return {"stiffness": c, "exponent": e, "damping": b, "gap": gap}
    if wallmode in (1, 3):
        wl = wall()
    if wallmode in (2, 3):
        wr = wall()
    if not finite:
        # must end: at most one wall, and none on the side gravity points to
        if wl is not None and wr is not None:
            wr = None
        if g < 0 and wl is not None:
            g = -g if wr is None else 0.0
        if g > 0 and wr is not None:
            g = -g if wl is None else 0.0
        if g < 0 and wl is not None or g > 0 and wr is not None:
            g = 0.0
    t_end = float(10 ** rng.uniform(-3, -1.3)) if finite else None
    return dict(masses=masses.tolist(), velocities=vel.tolist(), gaps=gaps.tolist(),
                stiffness=[l[0] for l in laws], exponent=[l[1] for l in laws],
                damping=[l[2] for l in laws], wall_left=wl, wall_right=wr, gravity=g,
                t_end=t_end)


class Timeout(Exception):
    pass


def alarm(signum, frame):
    raise Timeout()


def compare(case, rtol_lib=1e-10, method="auto", rtol_ref=1e-12, ref_method="DOP853",
            integrator="bdf"):
    lib_t0 = time.time()
    r = hcimpact.chain(**case, rtol=rtol_lib, method=method, integrator=integrator)
    lib_dt = time.time() - lib_t0
    s = ref.System(case["masses"], case["velocities"], case["gaps"], case["stiffness"],
                   case["exponent"], case["damping"], case["wall_left"], case["wall_right"],
                   case["gravity"])
    q = ref.simulate(s, case["t_end"], rtol=rtol_ref, method=ref_method)
    # a common time
    if case["t_end"] is None:
        tc = max(r.time, q["t"])
        dt = tc - r.time
        lp = r.positions + r.velocities * dt + 0.5 * s.g * dt * dt
        lv = r.velocities + s.g * dt
        qp, qv = ref.advance_free(s, q, tc)
    else:
        tc = case["t_end"]
        lp, lv, qp, qv = r.positions, r.velocities, q["pos"], q["vel"]
    vscale = max(np.max(np.abs(s.v0)), abs(s.g) * tc, 1e-300)
    xscale = max(q["xscale"], vscale * tc * 1e-3)
    ev = float(np.max(np.abs(lv - qv)) / vscale)
    # positions against the larger of the deformation scale and the largest position
    ex = float(np.max(np.abs(lp - qp)) / max(q["xscale"], np.max(np.abs(qp)), 1e-300))
    # contacts, matched in order of start (ignoring the reference's contacts that never
    # pressed: begun touching and shallower than 1e-12 of the scale)
    qc = [c for c in q["contacts"] if not c.get("open") and not (abs(c["approach_speed"]) < 1e-12 * vscale
                                           and c["max_def"] < 1e-9 * q["xscale"])]
    lc = r.contacts
    nmatch = len(qc) == r.n_contacts
    ect = 0.0
    ecv = 0.0
    ecx = 0.0
    if nmatch:
        for a, b in zip(sorted(lc, key=lambda c: (c["t_start"], c["pair"])), qc):
            if a["pair"] != b["pair"]:
                nmatch = False
                break
            dur = (b["t_end"] - b["t_start"]) if not math.isnan(b["t_end"]) else 1.0
            ect = max(ect, abs(a["t_start"] - b["t_start"]) / dur)
            if not math.isnan(b["t_end"]):
                ect = max(ect, abs(a["t_end"] - b["t_end"]) / dur)
                ecv = max(ecv, abs(a["separation_speed"] - b["separation_speed"]) / vscale)
            ecv = max(ecv, abs(a["approach_speed"] - b["approach_speed"]) / vscale)
            if b["max_def"] > 0:
                ecx = max(ecx, abs(a["max_deformation"] - b["max_def"]) / b["max_def"])
    return dict(r=r, q=q, ev=ev, ex=ex, nmatch=nmatch, n_lib=r.n_contacts, n_ref=len(qc),
                ect=ect, ecv=ecv, ecx=ecx, lib_energy=r.energy_error, ref_energy=q["energy_error"],
                method_used=r.method_used, lib_time=r.time, ref_time=q["t"], lib_dt=lib_dt)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("first", type=int)
    ap.add_argument("count", type=int)
    ap.add_argument("--rtol-ref", type=float, default=1e-12)
    ap.add_argument("--method", default="auto")
    ap.add_argument("--integrator", default="bdf")
    ap.add_argument("--ref-method", default="DOP853")
    ap.add_argument("--limit", type=int, default=120)
    a = ap.parse_args()
    signal.signal(signal.SIGALRM, alarm)
    bad = 0
    stats = {}
    for seed in range(a.first, a.first + a.count):
        case = draw(seed)
        signal.alarm(a.limit)
        try:
            res = compare(case, method=a.method, rtol_ref=a.rtol_ref, ref_method=a.ref_method,
                          integrator=a.integrator)
        except Timeout:
            print(f"seed {seed}: TIMEOUT", flush=True)
            bad += 1
            continue
        except Exception as exc:  # noqa
            print(f"seed {seed}: EXC {type(exc).__name__}: {exc}", flush=True)
            bad += 1
            continue
        finally:
            signal.alarm(0)
        worst = max(res["ev"], res["ex"], res["ect"], res["ecv"], res["ecx"],
                    abs(res["lib_energy"]))
        flag = "BAD" if (worst > 1e-6 or not res["nmatch"]) else "ok"
        bad += flag == "BAD"
        stats[res["method_used"]] = stats.get(res["method_used"], 0) + 1
        print(f"seed {seed} n={len(case['masses'])} t_end={case['t_end']} g={case['gravity']:.3g} "
              f"walls={case['wall_left'] is not None},{case['wall_right'] is not None} "
              f"{res['method_used']:10s} contacts lib {res['n_lib']} ref {res['n_ref']} "
              f"ev {res['ev']:.2e} ex {res['ex']:.2e} ct {res['ect']:.1e} cv {res['ecv']:.1e} "
              f"cx {res['ecx']:.1e} E lib {res['lib_energy']:.1e} ref {res['ref_energy']:.1e} "
              f"t {res['lib_time']:.6g}/{res['ref_time']:.6g} {res['lib_dt']:.2f}s {flag}",
              flush=True)
    print("summary: cases", a.count, "bad", bad, "methods", json.dumps(stats))


if __name__ == "__main__":
    main()
