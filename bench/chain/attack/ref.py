# SPDX-License-Identifier: Apache-2.0
"""Independent reference for hcimpact.chain: SciPy solve_ivp (DOP853 or Radau) with
event functions at every contact's start and end and at every damping clamp's switch.

Written from the model only (m x'' = -c x^n (1 + b x') per pair, the force clamped at 0,
walls at -gap_left and at sum(gaps) + gap_right, constant acceleration g), not from the
library's code. Positions are points: body 0 at 0, body i+1 at body i + gaps[i].

Pair p (0..N): 0 the left wall and body 0, p (1..N-1) bodies p-1 and p, N the last body
and the right wall. A pair absent (no wall) is never active.
"""
import math

import numpy as np
from scipy.integrate import solve_ivp


class System:
    def __init__(self, masses, velocities, gaps=None, stiffness=None, exponent=1.5,
                 damping=0.0, wall_left=None, wall_right=None, gravity=0.0):
        self.m = np.asarray(masses, float)
        n = self.n = self.m.size
        self.v0 = np.asarray(velocities, float)
        pairs = n - 1
        self.gaps = np.zeros(pairs) if gaps is None else np.broadcast_to(
            np.asarray(gaps, float), (pairs,)).copy()
        self.p0 = np.concatenate([[0.0], np.cumsum(self.gaps)]) if n > 1 else np.zeros(1)
        # laws for pairs 0..N
        self.c = np.zeros(n + 1)
        self.e = np.ones(n + 1)
        self.b = np.zeros(n + 1)
        self.present = np.zeros(n + 1, bool)
        if pairs > 0:
            self.c[1:n] = np.broadcast_to(np.asarray(stiffness, float), (pairs,))
            self.e[1:n] = np.broadcast_to(np.asarray(exponent, float), (pairs,))
            self.b[1:n] = np.broadcast_to(np.asarray(damping, float), (pairs,))
            self.present[1:n] = True
        self.wl, self.wr = None, None
        if wall_left is not None:
            self.present[0] = True
            self.c[0] = wall_left["stiffness"]
            self.e[0] = wall_left.get("exponent", 1.5)
            self.b[0] = wall_left.get("damping", 0.0)
            self.wl = -wall_left.get("gap", 0.0)
        if wall_right is not None:
            self.present[n] = True
            self.c[n] = wall_right["stiffness"]
            self.e[n] = wall_right.get("exponent", 1.5)
            self.b[n] = wall_right.get("damping", 0.0)
            self.wr = self.p0[-1] + wall_right.get("gap", 0.0)
        self.g = float(gravity)

    # deformation and its rate of pair p
    def x_xd(self, p, y):
        n = self.n
        pos, vel = y[:n], y[n:2 * n]
        if p == 0:
            return self.wl - pos[0], -vel[0]
        if p == n:
            return pos[n - 1] - self.wr, vel[n - 1]
        return pos[p - 1] - pos[p], vel[p - 1] - vel[p]

    def force(self, p, x, xd):
        if x <= 0.0:
            return 0.0
        return self.c[p] * x ** self.e[p] * max(0.0, 1.0 + self.b[p] * xd)

    def rhs(self, t, y):
        n = self.n
        dy = np.zeros_like(y)
        dy[:n] = y[n:2 * n]
        acc = np.full(n, self.g)
        for p in range(n + 1):
            if not self.present[p]:
                continue
            x, xd = self.x_xd(p, y)
            f = self.force(p, x, xd)
            if f == 0.0 and x <= 0:
                continue
            # dissipated power: f xd - elastic power c x^n xd
            dy[2 * n + p] = f * xd - (self.c[p] * x ** self.e[p] * xd if x > 0 else 0.0)
            if p == 0:
                acc[0] += f / self.m[0]
            elif p == n:
                acc[n - 1] -= f / self.m[n - 1]
            else:
                acc[p - 1] -= f / self.m[p - 1]
                acc[p] += f / self.m[p]
        dy[n:2 * n] = acc
        return dy

    def energy(self, y):
        n = self.n
        pos, vel = y[:n], y[n:2 * n]
        ke = 0.5 * np.sum(self.m * vel ** 2)
        pe = 0.0
        for p in range(n + 1):
            if self.present[p]:
                x, _ = self.x_xd(p, y)
                if x > 0:
                    pe += self.c[p] * x ** (self.e[p] + 1) / (self.e[p] + 1)
        grav = -self.g * np.sum(self.m * pos)
        return ke + pe + grav, np.sum(y[2 * n:])


def simulate(sys, t_end=None, rtol=1e-12, atol_scale=1e-16, method="DOP853",
             max_segments=200000, horizon=None):
    """Integrate to t_end, or (None) until no contact can happen again.
    Returns dict: t, pos, vel, contacts (list of dicts), energy error, segments."""
    n = sys.n
    y = np.concatenate([sys.p0, sys.v0, np.zeros(n + 1)])
    t = 0.0
    # scales for atol: positions by the largest conceivable deformation
    vmax = max(np.max(np.abs(sys.v0)), 1e-30)
    xs = []
    for p in range(n + 1):
        if sys.present[p]:
            mu = sys.m[max(p - 1, 0)] if p in (0, n) else sys.m[p - 1] * sys.m[p] / (sys.m[p - 1] + sys.m[p])
            xs.append((mu * vmax ** 2 * (sys.e[p] + 1) / (2 * sys.c[p])) ** (1 / (sys.e[p] + 1)))
    xscale = min(xs) if xs else 1.0
    e0 = sys.energy(y)[0]
    escale = max(abs(e0), 0.5 * np.sum(sys.m * sys.v0 ** 2), 1e-300)
    atol = np.concatenate([np.full(n, atol_scale * xscale), np.full(n, atol_scale * vmax),
                           np.full(n + 1, atol_scale * escale)])
    # flags
    inside = np.zeros(n + 1, bool)
    clamped = np.zeros(n + 1, bool)
    open_rec = {}
    contacts = []
    for p in range(n + 1):
        if sys.present[p]:
            x, xd = sys.x_xd(p, y)
            if x > 0 or (x == 0 and xd > 0):
                inside[p] = True
                open_rec[p] = dict(pair=p, t_start=0.0, approach_speed=xd, max_def=max(x, 0),
                                   peak_force=0.0)
    if horizon is None:
        # a time long enough to cover a few contacts; segments of this length
        horizon = 1.0
    segments = 0

    def make_events():
        evs = []
        for p in range(n + 1):
            if not sys.present[p]:
                continue

            sgn = 1.0 if inside[p] else -1.0

            def fx(t, yy, p=p, sgn=sgn):
                # an exact 0 (touching, not pressed) counts as the side the pair is on,
                # so that a pair touching at rest does not fire at every step
                x = sys.x_xd(p, yy)[0]
                return x if x != 0.0 else sgn * 1e-300
            fx.terminal = True
            fx.direction = -1 if inside[p] else 1
            fx.kind = ("x", p)
            evs.append(fx)
            if sys.b[p] > 0 and inside[p]:
                def fc(t, yy, p=p):
                    return 1.0 + sys.b[p] * sys.x_xd(p, yy)[1]
                fc.terminal = True
                fc.direction = 1 if clamped[p] else -1
                fc.kind = ("c", p)
                evs.append(fc)
            if inside[p]:
                def fv(t, yy, p=p):       # largest deformation (not terminal)
                    return sys.x_xd(p, yy)[1]
                fv.terminal = False
                fv.direction = -1
                fv.kind = ("v", p)
                evs.append(fv)
        return evs

    def done():
        if inside.any():
            return False
        pos, vel = y[:n], y[n:2 * n]
        for p in range(1, n):
            if vel[p - 1] - vel[p] > 0:
                return False
        if sys.present[0]:
            # reaches the left wall?
            v = -vel[0]
            a = -sys.g
            d = pos[0] - sys.wl
            if v > 0 or a > 0:
                if a <= 0 and v > 0:
                    if v * v / (-2 * a) >= d if a < 0 else True:
                        return False
                elif a > 0:
                    return False
        if sys.present[n]:
            v = vel[n - 1]
            a = sys.g
            d = sys.wr - pos[n - 1]
            if v > 0 or a > 0:
                if a <= 0 and v > 0:
                    if (v * v / (-2 * a) >= d) if a < 0 else True:
                        return False
                elif a > 0:
                    return False
        return True

    while True:
        if t_end is None and done():
            break
        if t_end is not None and t >= t_end:
            break
        segments += 1
        if segments > max_segments:
            raise RuntimeError("reference: too many segments")
        tb = t_end if t_end is not None else t + horizon
        evs = make_events()
        sol = solve_ivp(sys.rhs, (t, tb), y, method=method, rtol=rtol, atol=atol,
                        events=evs, dense_output=False)
        if sol.status < 0:
            raise RuntimeError("reference: " + sol.message)
        # largest deformations
        for ev, te, ye in zip(evs, sol.t_events, sol.y_events):
            if ev.kind[0] == "v":
                p = ev.kind[1]
                for yy in ye:
                    x, xd = sys.x_xd(p, yy)
                    open_rec[p]["max_def"] = max(open_rec[p]["max_def"], x)
        t = sol.t[-1]
        y = sol.y[:, -1].copy()
        if sol.status == 1:
            fired = [ev.kind for ev, te in zip(evs, sol.t_events)
                     if ev.terminal and len(te) and te[-1] == t]
            for kind, p in fired:
                x, xd = sys.x_xd(p, y)
                if kind == "x":
                    if inside[p]:
                        inside[p] = False
                        clamped[p] = False
                        rec = open_rec.pop(p)
                        rec["t_end"] = t
                        rec["separation_speed"] = -xd
                        rec["dissipated"] = y[2 * n + p] - rec.pop("d0", 0.0)
                        contacts.append(rec)
                    else:
                        inside[p] = True
                        open_rec[p] = dict(pair=p, t_start=t, approach_speed=xd, max_def=0.0,
                                           d0=y[2 * n + p])
                else:
                    clamped[p] = not clamped[p]
    # contacts still open
    for p, rec in open_rec.items():
        x, xd = sys.x_xd(p, y)
        rec["max_def"] = max(rec["max_def"], x)
        rec["t_end"] = math.nan
        rec["open"] = True
        rec["dissipated"] = y[2 * n + p] - rec.pop("d0", 0.0)
        contacts.append(rec)
    contacts.sort(key=lambda r: (r["t_start"], r["pair"]))
    e, d = sys.energy(y)
    return dict(t=t, pos=y[:n].copy(), vel=y[n:2 * n].copy(), contacts=contacts,
                energy_error=(e + d - e0) / escale, dissipated=d, segments=segments,
                xscale=xscale)


def advance_free(sys, res, t_to):
    """Free flight from res['t'] to t_to (no contact open)."""
    dt = t_to - res["t"]
    pos = res["pos"] + res["vel"] * dt + 0.5 * sys.g * dt * dt
    vel = res["vel"] + sys.g * dt
    return pos, vel
