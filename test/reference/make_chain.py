#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""High-precision references for systems of bodies on a line (issue 15).

Writes chain.csv next to this script: final velocities, the contacts (start, end,
approach and separation speed, largest deformation and force, dissipated energy) and
the energy balance of small systems integrated at about 48 significant digits.

The model (doc/chains.md): bodies 1..N on a line, gaps between neighbours, a contact
law c x^n (1 + b x') per neighbouring pair and per wall, clamped never to pull (the
script stops if the clamp would act), a constant acceleration g.

The method: a Taylor series method in mpmath. The right-hand side is analytic while
no deformation passes through zero, so each step expands the motion in a Taylor
series of order P (recurrences for x^n and the products), and the step is the
largest for which the series' last terms are below TOL. Where a contact starts or
ends, x^n is not analytic (x ~ |t - t0| there), so those instants are located
exactly and stepped over:
  - a start: the first root of the gap's Taylor polynomial in the step (never a sign
    change of sampled doubles); from it, a step of EPS x (the contact's time scale)
    with the new contact's force replaced by its leading term c (1 + b w)(w tau)^n,
    integrated exactly (the neglected part changes the velocities by a relative
    O(EPS^(n + 2)), below 1e-33 for EPS = 1e-10, n = 3/2);
  - an end: once the deformation has fallen below EPS x (its scale), the same leading
    term (c (1 + b w)(x0 + w tau)^n) carries the motion to the instant where the
    deformation vanishes, found by Newton's method on the analytic part plus that term.
Between them, the series' radius of convergence (the distance to the nearest start
or end) sets the steps, which grow and shrink geometrically.
Touching bodies at rest (gap 0, no relative speed) pushed by a neighbour start with
x ~ tau^(7/2); their leading term is 0, and they are followed from the end of the
crossing step on.

Checks in the script (it stops if one fails):
  - one steel ball against a wall and two free bodies against the closed forms of
    impact.csv (make_impact.py: quadrature, not integration): contact time,
    restitution, largest deformation and force to 1e-28 relative;
  - every case twice, at (P, TOL, EPS) = (52, 1e-38, 1e-11) and (44, 1e-34,
    1e-10): the results must agree to 1e-26 relative (velocities to 1e-26 of the
    largest speed);
  - the energy balance (kinetic + elastic + gravitational + dissipated) of every case
    to 1e-30.

Usage: python3 make_chain.py [--quick]   (about 2 minutes with gmpy2 installed, 80 s of
them the two chains of 16; mpmath's own arithmetic is several times slower; --quick:
only the checks and the first case, nothing written)
"""
import math
import os
import sys
import time

import mpmath
from mpmath import mp, mpf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doubles import split_double  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
QUICK = "--quick" in sys.argv
PREC = 170
mp.prec = PREC
try:
    # MPFR through gmpy2: the same correctly rounded arithmetic as mpmath's, about
    # 30 times faster from Python
    import gmpy2
    gmpy2.get_context().precision = PREC
    num = gmpy2.mpfr
    num_sqrt = gmpy2.sqrt
    ARITHMETIC = f"gmpy2 {gmpy2.version()} (MPFR {gmpy2.mpfr_version()}), {PREC} bits"

    def to_mpf(x):
        p, q = x.as_integer_ratio()
        return mpf(p) / q
except ImportError:
    num = mpf
    num_sqrt = mpmath.sqrt
    ARITHMETIC = f"mpmath {mpmath.__version__} (no gmpy2), {PREC} bits"

    def to_mpf(x):
        return x

# deformations (m) below this are rounding: a touching pair pressed only that much
# exerts no force yet (far ahead of a wave in a touching chain, x ~ t^(large power)),
# everywhere alike (the series, `pushed`, the ends). Taking x^n of such an x as a
# force made the steps collapse: its series (x ~ t^p, p ~ 1.5^k for the k-th pair
# ahead) has relative terms like binom(pn, k), so a truncated one dips below zero
# within every step, and a chain of 10 beads made no progress in minutes.
NOISE = num(10) ** -40
# the two settings every case is computed with: order, series tolerance, crossing size
SETTINGS = [(52, num(10) ** -38, num(10) ** -11), (44, num(10) ** -34, num(10) ** -10)]
AGREE = num(10) ** -26
ENERGY_AGREE = num(10) ** -30

STEEL_C = num(1.7135e10)   # the seed's steel ball on a plate (double value, exact)
STEEL_M = num(0.1)


class Law:
    """c x^n (1 + b w)"""

    def __init__(self, c, n, b):
        self.c, self.n, self.b = num(c), num(n), num(b)


class System:
    """Bodies 0..N-1; slot j (1..N-1) between bodies j-1 and j; slot 0 the left wall,
    slot N the right wall (None: absent)."""

    def __init__(self, masses, velocities, gaps, laws, left=None, right=None, gravity=0):
        self.m = [num(x) for x in masses]
        self.v0 = [num(x) for x in velocities]
        self.N = N = len(self.m)
        self.gap = [num(x) for x in gaps]
        assert len(self.gap) == N - 1
        if isinstance(laws, Law):
            laws = [laws] * (N - 1)
        self.law = [None] * (N + 1)
        self.offset = [num(0)] * (N + 1)
        self.lb = [None] * (N + 1)
        self.rb = [None] * (N + 1)
        for j in range(1, N):
            self.law[j] = laws[j - 1]
            self.offset[j] = -self.gap[j - 1]
            self.lb[j], self.rb[j] = j - 1, j
        if left is not None:
            law, gap = left
            self.law[0] = law
            self.offset[0] = -num(gap)
            self.rb[0] = 0
        if right is not None:
            law, gap = right
            self.law[N] = law
            self.offset[N] = -num(gap)
            self.lb[N] = N - 1
        self.g = num(gravity)
        self.slots = [j for j in range(N + 1) if self.law[j] is not None]

    def inv_mass(self, j):
        s = num(0)
        if self.lb[j] is not None:
            s += 1 / self.m[self.lb[j]]
        if self.rb[j] is not None:
            s += 1 / self.m[self.rb[j]]
        return s

    def x_of(self, j, u):
        x = self.offset[j]
        if self.lb[j] is not None:
            x += u[self.lb[j]]
        if self.rb[j] is not None:
            x -= u[self.rb[j]]
        return x

    def w_of(self, j, v):
        w = num(0)
        if self.lb[j] is not None:
            w += v[self.lb[j]]
        if self.rb[j] is not None:
            w -= v[self.rb[j]]
        return w

    def xdd_free(self, j):
        """The deformation's acceleration in free flight (gravity on a wall)"""
        if self.lb[j] is not None and self.rb[j] is not None:
            return num(0)
        return -self.g if self.rb[j] is not None else self.g

    def potential(self, j, x):
        if x <= 0:
            return num(0)
        law = self.law[j]
        return law.c * x ** (law.n + 1) / (law.n + 1)

    def energy(self, u, v):
        e = num(0)
        for i in range(self.N):
            e += self.m[i] * v[i] ** 2 / 2 - self.m[i] * self.g * u[i]
        for j in self.slots:
            e += self.potential(j, self.x_of(j, u))
        return e

    def scales(self, j, w):
        """Largest deformation and contact time of slot j met at the speed w (> 0)"""
        law = self.law[j]
        mu = 1 / self.inv_mass(j)
        x = ((law.n + 1) * mu * w ** 2 / (2 * law.c)) ** (1 / (law.n + 1))
        return x, x / w


def polyval(coef, t):
    s = num(0)
    for c in reversed(coef):
        s = s * t + c
    return s


def polyder(coef):
    return [k * coef[k] for k in range(1, len(coef))]


def first_root(coef, h, rising):
    """The first tau in (0, h] where the polynomial crosses 0 upwards (rising) or
    downwards; None if it does not (64 samples, then bisection and Newton)."""
    samples = 64
    prev_t, prev = num(0), polyval(coef, 0)
    for k in range(1, samples + 1):
        t = h * k / samples
        val = polyval(coef, t)
        if (rising and val > 0 >= prev) or (not rising and val <= 0 < prev):
            lo, hi = prev_t, t
            for _ in range(40):
                mid = (lo + hi) / 2
                vm = polyval(coef, mid)
                if (vm > 0) == rising:
                    hi = mid
                else:
                    lo = mid
            d = polyder(coef)
            t = (lo + hi) / 2
            for _ in range(60):
                dt = polyval(coef, t) / polyval(d, t)
                t -= dt
                if abs(dt) <= abs(t) * num(2) ** (-PREC + 8):
                    break
            return t
        prev_t, prev = t, val
    return None


def interior_max(coef, h):
    """Largest value of the polynomial on [0, h] where its derivative changes sign
    from + to - (or -inf)"""
    d = polyder(coef)
    best = num("-inf")
    if polyval(d, 0) > 0 and polyval(d, h) <= 0:
        t = first_root(d, h, rising=False)
        if t is not None:
            best = polyval(coef, t)
    return best


class Contact:
    def __init__(self, j, t_start, approach, xscale, tscale):
        self.j, self.t_start, self.approach = j, t_start, approach
        self.xscale, self.tscale = xscale, tscale
        self.peak, self.xmax, self.dissipated = num(0), num(0), num(0)
        self.t_end = self.separation = None


def taylor(sys_, u, v, active, P):
    """Taylor coefficients (order P) of displacements, velocities, deformations,
    forces and dissipated energies, with the contacts in `active` only."""
    N = sys_.N
    U = [[u[i]] + [num(0)] * P for i in range(N)]
    V = [[v[i]] + [num(0)] * P for i in range(N)]
    X = {j: [num(0)] * (P + 1) for j in active}
    W = {j: [num(0)] * (P + 1) for j in active}
    Pw = {j: [num(0)] * P for j in active}
    G = {j: [num(0)] * P for j in active}
    F = {j: [num(0)] * P for j in active}
    E = {j: [num(0)] * (P + 1) for j in active}
    idle = set()
    for k in range(P):
        acc = [sys_.g if k == 0 else num(0) for _ in range(N)]
        for j in active:
            law = sys_.law[j]
            lb, rb = sys_.lb[j], sys_.rb[j]
            xk = sys_.offset[j] if k == 0 else num(0)
            wk = num(0)
            if lb is not None:
                xk += U[lb][k]
                wk += V[lb][k]
            if rb is not None:
                xk -= U[rb][k]
                wk -= V[rb][k]
            Xj, Wj, Pj, Gj = X[j], W[j], Pw[j], G[j]
            Xj[k], Wj[k] = xk, wk
            if k == 0:
                if not xk > NOISE:
                    if xk < -NOISE:
                        raise ArithmeticError(f"slot {j}: active with x = {xk}")
                    # a touching pair pressed far ahead of the wave, whose deformation
                    # (below 1e-40 m) is rounding: no force
                    idle.add(j)
                    continue
                Pj[0] = xk ** law.n
            elif j in idle:
                continue
            else:
                s = num(0)
                n = law.n
                for i in range(1, k + 1):
                    s += (n * i - (k - i)) * Xj[i] * Pj[k - i]
                Pj[k] = s / (k * Xj[0])
            if law.b != 0:
                s = num(0)
                for i in range(k + 1):
                    s += Pj[i] * Wj[k - i]
                Gj[k] = s
                F[j][k] = law.c * (Pj[k] + law.b * s)
                s = num(0)
                for i in range(k + 1):
                    s += Gj[i] * Wj[k - i]
                E[j][k + 1] = law.c * law.b * s / (k + 1)
            else:
                F[j][k] = law.c * Pj[k]
            if k == 0 and not (1 + law.b * wk) > 0:
                raise ArithmeticError(f"slot {j}: the clamp 1 + b w > 0 would act")
            if lb is not None:
                acc[lb] -= F[j][k] / sys_.m[lb]
            if rb is not None:
                acc[rb] += F[j][k] / sys_.m[rb]
        for i in range(N):
            V[i][k + 1] = acc[i] / (k + 1)
            U[i][k + 1] = V[i][k] / (k + 1)
    for j in active:
        lb, rb = sys_.lb[j], sys_.rb[j]
        X[j][P] = (U[lb][P] if lb is not None else 0) - (U[rb][P] if rb is not None else 0)
        W[j][P] = (V[lb][P] if lb is not None else 0) - (V[rb][P] if rb is not None else 0)
    return U, V, X, W, F, E


def simulate(sys_, P, TOL, EPS, t_stop=None, max_contacts=10 ** 6):
    """Integrate until no contact can happen again (or t_stop, or max_contacts
    contacts ended). Returns (t, u, v, contacts, total dissipated)."""
    N = sys_.N
    t = num(0)
    u = [num(0)] * N
    v = list(sys_.v0)
    vscale = max([abs(x) for x in v] + [num(0)])
    if vscale == 0:
        vscale = num(1)
    active = {}        # slot -> Contact
    pending = {}       # slot touching and pressed, not yet deformed -> since when
    done = []
    steps = 0
    e0 = sys_.energy(u, v)
    # a time scale of the whole system: the shortest contact at the largest speed
    tmin = min(sys_.scales(j, vscale)[1] for j in sys_.slots)

    def step_bound(U, V):
        """The largest step whose series' last two terms stay below TOL (of the
        speed scale for velocities, of the smallest deformation scale for
        displacements); None if every such term is 0"""
        xs = min([c.xscale for c in active.values() if c.xscale is not None] +
                 [vscale * tmin])
        h = None
        for i in range(N):
            for k in (P - 1, P):
                for series, scale in ((V[i], vscale), (U[i], xs)):
                    if series[k] != 0:
                        hk = (TOL * scale / abs(series[k])) ** (num(1) / k)
                        h = hk if h is None else min(h, hk)
        return h

    def pushed(j):
        """Slot j (open) touches and closes: approaching, or at rest relative
        and pushed together by its neighbours' forces"""
        if not sys_.x_of(j, u) >= 0:
            return False
        w = sys_.w_of(j, v)
        if w != 0:
            return w > 0
        acc = [sys_.g] * N
        for k in active:
            law = sys_.law[k]
            xk = sys_.x_of(k, u)
            if not xk > NOISE:
                continue   # no force below rounding (as in taylor)
            f = law.c * xk ** law.n * (1 + law.b * sys_.w_of(k, v))
            if sys_.lb[k] is not None:
                acc[sys_.lb[k]] -= f / sys_.m[sys_.lb[k]]
            if sys_.rb[k] is not None:
                acc[sys_.rb[k]] += f / sys_.m[sys_.rb[k]]
        a = sys_.xdd_free(j) if not active else \
            (acc[sys_.lb[j]] if sys_.lb[j] is not None else 0) - \
            (acc[sys_.rb[j]] if sys_.rb[j] is not None else 0)
        return a > 0

    def leading(j, w, x0, tau, end):
        """Impulse I, its displacement J over [0, tau], and dissipated energy of
        the leading term of slot j's force"""
        law = sys_.law[j]
        cp = law.c * (1 + law.b * w)
        n = law.n
        if not end:
            if w <= 0:
                return num(0), num(0), num(0)
            imp = cp * w ** n * tau ** (n + 1) / (n + 1)
            disp = cp * w ** n * tau ** (n + 2) / ((n + 1) * (n + 2))
            diss = law.c * law.b * w ** 2 * w ** n * tau ** (n + 1) / (n + 1)
            return imp, disp, diss
        aw = -w
        imp = cp * x0 ** (n + 1) / ((n + 1) * aw)
        disp = tau * imp - cp * x0 ** (n + 2) / ((n + 1) * (n + 2) * aw ** 2)
        diss = law.c * law.b * aw * x0 ** (n + 1) / (n + 1)
        return imp, disp, diss

    def apply(j, imp, disp, uu, vv):
        lb, rb = sys_.lb[j], sys_.rb[j]
        if lb is not None:
            vv[lb] -= imp / sys_.m[lb]
            uu[lb] -= disp / sys_.m[lb]
        if rb is not None:
            vv[rb] += imp / sys_.m[rb]
            uu[rb] += disp / sys_.m[rb]

    def before_ends(slots, X, h):
        """The step h shortened so that no contact of `slots` ends inside it (its
        end is stepped over)"""
        for j in slots:
            if not X[j][0] > NOISE:
                continue   # no force yet: it cannot end (see NOISE)
            r = first_root(X[j], h, rising=False)
            if r is not None:
                h = r / 2
        return h

    def track(slots, X, F, h):
        """The largest deformation and force of the contacts of `slots` over a
        step h of their series"""
        for j in slots:
            c = active[j]
            c.xmax = max(c.xmax, interior_max(X[j], h), polyval(X[j], h))
            c.peak = max(c.peak, interior_max(F[j], h), polyval(F[j], h))

    def start_crossing(starting):
        """Step over the start of the contacts of `starting` at t; every other pair
        that touches without separating joins (a touching pair pressed by the
        start is in contact from now on: its deformation grows like tau^(7/2), or
        stays 0 to the leading order and the pair waits in `pending`)"""
        nonlocal t, u, v
        starting = list(starting) + [j for j in sys_.slots if j not in active and
                                     j not in starting and sys_.x_of(j, u) >= 0 and
                                     sys_.w_of(j, v) >= 0]
        others = list(active)
        tau = None
        info = {}
        for j in starting:
            w = sys_.w_of(j, v)
            info[j] = w
            if w > 0:
                xs, ts = sys_.scales(j, w)
                tau = EPS * ts if tau is None else min(tau, EPS * ts)
        U, V, X, W, F, E = taylor(sys_, u, v, others, P)
        # within the others' radius of convergence (a pair touching at rest,
        # pushed, has a negligible leading term: the step is the others')
        cap = step_bound(U, V) if others else None
        if cap is not None:
            tau = cap if tau is None else min(tau, cap)
        if tau is None:
            return
        # the others go on as in a step: none may end inside it, their largest
        # deformation and force are followed
        tau = before_ends(others, X, tau)
        track(others, X, F, tau)
        uu = [polyval(U[i], tau) for i in range(N)]
        vv = [polyval(V[i], tau) for i in range(N)]
        for j in others:
            active[j].dissipated += polyval(E[j], tau)
        diss = {}
        for j in starting:
            imp, disp, dd = leading(j, info[j], 0, tau, end=False)
            apply(j, imp, disp, uu, vv)
            diss[j] = dd
        t0 = t
        t += tau
        u, v = uu, vv
        for j in starting:
            x = sys_.x_of(j, u)
            if x < 0:
                pending.pop(j, None)
                continue
            if x == 0:
                pending.setdefault(j, t0)
                continue
            w = info[j]
            if w > 0:
                xs, ts = sys_.scales(j, w)
            else:
                xs, ts = None, None
            c = Contact(j, pending.pop(j, t0), w, xs, ts)
            c.dissipated = diss[j]
            active[j] = c
        for j in list(active):
            if active[j].xscale is None:
                # a touching pair: its scales from the largest speed
                xs, ts = sys_.scales(j, vscale)
                active[j].xscale, active[j].tscale = xs, ts

    def end_crossing(j):
        """Step over the end of the contact of slot j (its deformation is small)"""
        nonlocal t, u, v
        others = [k for k in active if k != j]
        x0 = sys_.x_of(j, u)
        w0 = sys_.w_of(j, v)
        U, V, X, W, F, E = taylor(sys_, u, v, others, P)
        lb, rb = sys_.lb[j], sys_.rb[j]

        def xa(tau):
            s = sys_.offset[j]
            if lb is not None:
                s += polyval(U[lb], tau)
            if rb is not None:
                s -= polyval(U[rb], tau)
            return s

        def wa(tau):
            s = num(0)
            if lb is not None:
                s += polyval(V[lb], tau)
            if rb is not None:
                s -= polyval(V[rb], tau)
            return s

        kappa = sys_.inv_mass(j)
        tau = x0 / -w0
        # Newton's method; the deformation is a difference of displacements, known
        # to the working precision of the displacements: stop where dt no longer
        # shrinks, and require |dt| below 1e-30 of the crossing time (far below
        # what moves any result: tau itself is below EPS of the contact time)
        last = None
        for _ in range(100):
            imp, disp, dd = leading(j, w0, x0, tau, end=True)
            f = xa(tau) - kappa * disp
            df = wa(tau) - kappa * imp
            dt = f / df
            tau -= dt
            if last is not None and abs(dt) >= last / 2:
                break
            last = abs(dt)
        if not abs(dt) <= tau * num(10) ** -30:
            raise ArithmeticError(f"end crossing of slot {j} at t = {t}: Newton did not converge (x0 {x0}, w0 {w0}, tau {tau})")
        imp, disp, dd = leading(j, w0, x0, tau, end=True)
        uu = [polyval(U[i], tau) for i in range(N)]
        vv = [polyval(V[i], tau) for i in range(N)]
        apply(j, imp, disp, uu, vv)
        track(others, X, F, tau)
        for k in others:
            active[k].dissipated += polyval(E[k], tau)
        c = active.pop(j)
        c.dissipated += dd
        t += tau
        u, v = uu, vv
        c.t_end = t
        c.separation = -sys_.w_of(j, v)
        done.append(c)

    def next_closing():
        """Free flight: the first slot to close and when (None: never)"""
        best = None
        for j in sys_.slots:
            x0 = sys_.x_of(j, u)
            w = sys_.w_of(j, v)
            a = sys_.xdd_free(j)
            if x0 >= 0 and (w > 0 or (w == 0 and a > 0)):
                tau = num(0)
            elif a == 0:
                tau = -x0 / w if w > 0 else None
            else:
                disc = w * w - 2 * a * x0
                tau = None
                if disc >= 0:
                    r = [(-w + num_sqrt(disc)) / a, (-w - num_sqrt(disc)) / a]
                    r = [x for x in r if x > 0 and a * x + w > 0]
                    tau = min(r) if r else None
            if tau is not None and (best is None or tau < best[0]):
                best = (tau, j)
        return best

    # at the start: touching pairs that approach or are pushed
    starting = [j for j in sys_.slots if pushed(j)]
    if starting:
        start_crossing(starting)
    while True:
        if len(done) >= max_contacts:
            break
        if t_stop is not None and t >= t_stop:
            break
        if not active:
            nc = next_closing()
            if nc is None:
                break
            tau, j = nc
            for i in range(N):
                u[i] += (v[i] + sys_.g * tau / 2) * tau
                v[i] += sys_.g * tau
            t += tau
            # exactly touching now
            if sys_.lb[j] is not None and sys_.rb[j] is not None:
                pass
            u = fix_touch(sys_, u, j)
            start_crossing([k for k in sys_.slots if k == j or pushed(k)])
            continue
        # touching pairs pushed together now: a start without a root
        starting = [j for j in sys_.slots if j not in active and pushed(j)]
        if starting:
            start_crossing(starting)
            continue
        # a touching pair that never pressed beyond rounding and opens again: no
        # contact (yet); it waits as pending
        for j in list(active):
            c = active[j]
            if c.xmax < NOISE and sys_.x_of(j, u) < NOISE and sys_.w_of(j, v) <= 0:
                pending.setdefault(j, c.t_start)
                del active[j]
        # an end close by?
        ending = None
        for j, c in active.items():
            x = sys_.x_of(j, u)
            w = sys_.w_of(j, v)
            if w < 0 and x < EPS * c.xscale:
                ending = j
                break
        if ending is not None:
            end_crossing(ending)
            continue
        steps += 1
        if steps > 2_000_000:
            raise RuntimeError("too many steps")
        U, V, X, W, F, E = taylor(sys_, u, v, list(active), P)
        h = step_bound(U, V)
        if h is None:
            h = min(c.tscale for c in active.values())
        if t_stop is not None:
            h = min(h, t_stop - t)
        h = before_ends(active, X, h)
        # a gap that closes in the step: stop there
        starts = None
        for j in sys_.slots:
            if j in active:
                continue
            lb, rb = sys_.lb[j], sys_.rb[j]
            coef = [(U[lb][k] if lb is not None else 0) - (U[rb][k] if rb is not None else 0)
                    for k in range(P + 1)]
            coef[0] += sys_.offset[j]
            r = first_root(coef, h, rising=True)
            if r is not None and (starts is None or r < starts[0]):
                starts = (r, j)
        if starts is not None:
            h = starts[0]
        track(list(active), X, F, h)
        for j, c in active.items():
            c.dissipated += polyval(E[j], h)
        u = [polyval(U[i], h) for i in range(N)]
        v = [polyval(V[i], h) for i in range(N)]
        t += h
        for j in list(pending):
            if sys_.x_of(j, u) < 0:
                del pending[j]
        if starts is not None:
            j = starts[1]
            u = fix_touch(sys_, u, j)
            start_crossing([j] + [k for k in sys_.slots if k != j and k not in active
                                  and pushed(k)])
    e1 = sys_.energy(u, v) + sum(c.dissipated for c in done) + \
        sum(c.dissipated for c in active.values())
    scale = e0 + sum(abs(sys_.m[i] * sys_.g * u[i]) for i in range(N)) + abs(e0)
    err = abs(e1 - e0) / scale
    return dict(t=t, u=u, v=v, contacts=done, energy_error=err, steps=steps,
                open=list(active.values()))


def fix_touch(sys_, u, j):
    """Make slot j's deformation exactly 0 (the root was found to the working
    precision; the rest is moved onto the right body, or the left one at a wall)"""
    x = sys_.x_of(j, u)
    u = list(u)
    if sys_.rb[j] is not None:
        u[sys_.rb[j]] += x
    else:
        u[sys_.lb[j]] -= x
    return u


# ---------------------------------------------------------------------------
# The cases
# ---------------------------------------------------------------------------

# the steel balls of MODEL.md (m = 0.1 kg, c = 1.7135e10 N/m^1.5 against a plate);
# between two equal balls the Hertz constant is 1/sqrt(2) of the plate's
STEEL_PAIR_C = 1.7135e10 / math.sqrt(2.0)


def case(name, masses, velocities, gaps=(), laws=(), left=None, right=None, gravity=0.0,
         max_contacts=None, note=""):
    """A case: inputs as doubles (the values the Fortran tests use), laws as
    (c, n, b) per pair, walls as (c, n, b, gap)"""
    return dict(name=name, masses=list(masses), velocities=list(velocities),
                gaps=list(gaps), laws=list(laws), left=left, right=right,
                gravity=gravity, max_contacts=max_contacts, note=note)


def cases():
    steel_wall = (1.7135e10, 1.5, 0.1)
    pair = lambda b: (STEEL_PAIR_C, 1.5, b)  # noqa: E731
    out = [
        case("wall_b01", [0.1], [-1.0], left=steel_wall + (0.0,),
             note="one steel ball against a wall at 1 m/s (MODEL.md's row V = 1)"),
        case("wall_b0", [0.1], [-1.0], left=(1.7135e10, 1.5, 0.0, 0.0),
             note="the same, elastic (MODEL.md: b = 0 at V = 1)"),
    ]
    for b, tag in ((0.1, "b01"), (0.0, "b0")):
        out.append(case(f"three_{tag}", [0.1] * 3, [1.0, 0.0, 0.0], [0.0] * 2, [pair(b)] * 2,
                        note="three touching steel balls, the first struck at 1 m/s"))
        out.append(case(f"cradle5_{tag}", [0.1] * 5, [1.0, 0, 0, 0, 0], [0.0] * 4,
                        [pair(b)] * 4, note="Newton's cradle of five touching balls"))
        out.append(case(f"cradle5_gaps_{tag}", [0.1] * 5, [1.0, 0, 0, 0, 0], [1.0e-5] * 4,
                        [pair(b)] * 4,
                        note="Newton's cradle of five balls 10 um apart (contacts overlap)"))
        out.append(case(f"drop2_{tag}", [0.1, 0.01], [-1.0, -1.0], [0.0], [(1.0e10, 1.5, b)],
                        left=(1.7135e10, 1.5, b, 0.0),
                        note="two touching balls (mass ratio 10) dropped together on a "
                             "floor at 1 m/s, gravity neglected"))
    for v in (1.0, 0.1, 0.01):
        out.append(case(f"bounce_g_{v:g}", [0.1], [-v], left=steel_wall + (0.0,),
                        gravity=-9.81, max_contacts=1,
                        note=f"a steel ball hits a floor at {v:g} m/s under gravity: "
                             "its first contact"))
    for b, tag in ((0.0, "b0"), (0.1, "b01")):
        out.append(case(f"chain16_{tag}", [0.1] * 16, [1.0] + [0.0] * 15, [0.0] * 15,
                        [pair(b)] * 15,
                        note="a struck chain of 16 touching steel balls, the first at 1 m/s: "
                             "the wave and the beads left behind it"))
    return out


def build(cs):
    left = right = None
    if cs["left"] is not None:
        c, n, b, gap = cs["left"]
        left = (Law(c, n, b), gap)
    if cs["right"] is not None:
        c, n, b, gap = cs["right"]
        right = (Law(c, n, b), gap)
    laws = [Law(*x) for x in cs["laws"]]
    return System(cs["masses"], cs["velocities"], cs["gaps"], laws, left, right,
                  cs["gravity"])


FIELDS = ("t_start", "t_end", "approach", "separation", "peak", "xmax", "dissipated")
NAMES = dict(t_start="contact_t_start", t_end="contact_t_end", approach="contact_approach",
             separation="contact_separation", peak="contact_peak_force",
             xmax="contact_max_deformation", dissipated="contact_dissipated")


def run_case(cs, setting):
    P, TOL, EPS = setting
    r = simulate(build(cs), P, TOL, EPS, max_contacts=cs["max_contacts"] or 10 ** 6)
    return r


def rel(a, b, scale=None):
    s = abs(b) if scale is None else scale
    if s == 0:
        return abs(a - b)
    return abs(a - b) / s


def compare(cs, r1, r2):
    """The largest disagreement of two runs (relative; velocities against the
    largest speed, times against the last end)"""
    worst = num(0)
    c1, c2 = r1["contacts"], r2["contacts"]
    if len(c1) != len(c2) or any(a.j != b.j for a, b in zip(c1, c2)):
        raise AssertionError(f"{cs['name']}: the two settings give different contacts")
    vmax = max(abs(x) for x in r1["v"])
    tmax = c1[-1].t_end
    if cs["max_contacts"] is None:
        for a, b in zip(r1["v"], r2["v"]):
            worst = max(worst, rel(a, b, vmax))
    for a, b in zip(c1, c2):
        for f in FIELDS:
            x, y = getattr(a, f), getattr(b, f)
            if f in ("t_start", "t_end"):
                worst = max(worst, rel(x, y, tmax))
            elif f in ("approach", "separation"):
                worst = max(worst, rel(x, y, vmax))
            elif f == "dissipated":
                e = sum(num(m) * num(v) ** 2 for m, v in zip(cs["masses"], cs["velocities"]))
                worst = max(worst, rel(x, y, e))
            else:
                worst = max(worst, rel(x, y))
    return worst


def check_one_impact(r, hi_lo, what):
    """A one-contact run against the closed forms (impact.csv): (time, k, xmax, peak)"""
    c = r["contacts"][0]
    got = [c.t_end - c.t_start, c.separation / c.approach, c.xmax, c.peak]
    for g, (hi, lo), name in zip(got, hi_lo, ("contact time", "restitution", "x_max",
                                              "peak force")):
        ref = mpf(hi) + mpf(lo)
        err = abs(to_mpf(g) - ref) / ref
        if not err < mpf(10) ** -28:
            raise AssertionError(f"{what}: {name} {to_mpf(g)} against {ref}: {err}")
        print(f"  {what}: {name} agrees with the closed forms to {mpmath.nstr(err, 3)}")


def impact_row(V, b):
    """contact time, k, x_max, peak force of the steel ball at V, b from impact.csv"""
    with open(os.path.join(HERE, "impact.csv")) as f:
        for line in f:
            if line.startswith("#") or line.startswith("m,"):
                continue
            p = line.strip().split(",")
            if (float(p[0]), float(p[1]), float(p[2]), float(p[3]), float(p[4])) == \
                    (0.1, 1.7135e10, 1.5, V, b):
                col = lambda k: (float(p[k]), float(p[k + 1]))  # noqa: E731
                return [col(15), col(17), col(5), col(7)]
    raise KeyError((V, b))


def main():
    start = time.time()
    print(f"arithmetic: {ARITHMETIC}")
    rows = []
    todo = cases()
    if QUICK:
        todo = todo[:3]
    for cs in todo:
        t0 = time.time()
        runs = [run_case(cs, s) for s in SETTINGS]
        r = runs[0]
        worst = compare(cs, runs[0], runs[1])
        if not worst < AGREE:
            raise AssertionError(f"{cs['name']}: the settings disagree by {worst}")
        for x in runs:
            if not x["energy_error"] < ENERGY_AGREE:
                raise AssertionError(f"{cs['name']}: energy balance {x['energy_error']}")
        if cs["name"] == "wall_b01":
            check_one_impact(r, impact_row(1.0, 0.1), cs["name"])
        print(f"{cs['name']}: {len(r['contacts'])} contacts, {r['steps']} + "
              f"{runs[1]['steps']} steps, settings agree to {float(worst):.1e}, energy "
              f"balance {float(r['energy_error']):.1e}, {time.time() - t0:.1f} s")
        rows += case_rows(cs, r)
    if QUICK:
        print(f"--quick: nothing written ({time.time() - start:.0f} s)")
        return
    path = os.path.join(HERE, "chain.csv")
    with open(path, "w") as f:
        f.write("# hcimpact reference: systems of bodies on a line (doc/chains.md); "
                "generated by make_chain.py\n")
        f.write(f"# {ARITHMETIC}; Taylor series of orders {SETTINGS[0][0]} and "
                f"{SETTINGS[1][0]}, agreeing to {float(AGREE):.0e}\n")
        f.write("# quantity: inputs (mass, velocity, gap, stiffness, exponent, damping "
                "per pair 1..n-1; wall_* with index 0 left, n right; gravity; "
                "max_contacts), then results (final_velocity per body, contact_* per "
                "contact in the order they end, dissipated)\n")
        f.write("# case,quantity,index,hi,lo\n")
        for row in rows:
            f.write(",".join(row) + "\n")
    print(f"wrote {path} ({len(rows)} rows, {time.time() - start:.0f} s)")


def fmt(x):
    return repr(float(x))


def case_rows(cs, r):
    name = cs["name"]
    rows = []

    def put(q, i, value, exact=False):
        if exact:
            rows.append([name, q, str(i), fmt(value), "0.0"])
        else:
            hi, lo = split_double(to_mpf(value))
            rows.append([name, q, str(i), repr(hi), repr(lo)])

    for i, m in enumerate(cs["masses"], 1):
        put("mass", i, m, True)
    for i, v in enumerate(cs["velocities"], 1):
        put("velocity", i, v, True)
    for j, g in enumerate(cs["gaps"], 1):
        put("gap", j, g, True)
    for j, (c, n, b) in enumerate(cs["laws"], 1):
        put("stiffness", j, c, True)
        put("exponent", j, n, True)
        put("damping", j, b, True)
    N = len(cs["masses"])
    for wall, idx in ((cs["left"], 0), (cs["right"], N)):
        if wall is not None:
            c, n, b, gap = wall
            put("wall_stiffness", idx, c, True)
            put("wall_exponent", idx, n, True)
            put("wall_damping", idx, b, True)
            put("wall_gap", idx, gap, True)
    put("gravity", 0, cs["gravity"], True)
    if cs["max_contacts"] is not None:
        put("max_contacts", 0, cs["max_contacts"], True)
    else:
        for i, v in enumerate(r["v"], 1):
            put("final_velocity", i, v)
    for k, c in enumerate(r["contacts"], 1):
        put("contact_pair", k, c.j, True)
        for f in FIELDS:
            put(NAMES[f], k, getattr(c, f))
    put("dissipated", 0, sum(c.dissipated for c in r["contacts"]))
    return rows


if __name__ == "__main__":
    main()
