# SPDX-License-Identifier: Apache-2.0
"""Reproducers of the second attack of 26 November on the changes since 79cb44a (Taylor step
over too short intervals, scaled impacts at tiny speeds, subnormal velocity split,
first_zero, extent check, settling at a far t_end, method exact and clusters).

Run from this directory after `. ./env.sh`:  python3 repro_second_attack.py [NAME ...]
Each case runs in its own process with a timeout (60 s unless said); a case prints
what it expects and what it got. `python3 repro_second_attack.py --list` names them.
"""
from repro_cases import Cases

case = Cases()


@case("settle_below_resolution", timeout=70)
def _():
    """
    # D1: t_end far, a 0.1 kg ball dropped from 10 m onto a steel-like floor (c = 1e9,
    # b = 1 s/m), default rtol 1e-10: without t_end the rest state comes in 0.4 s (rest
    # at 3.14 s); with t_end = 1e300 it never settles: settling needs every displacement
    # within 100 rtol x_s = 1e-14 m of the equilibrium, while the displacement is -10 m
    # (ulp 1.8e-15 m, CVODE's tolerance rtol |u| = 1e-9 m). CVODE steps the resting ball
    # until max_steps (1e6 here: fails at t = 14 s after 3 s; the default 1e8: minutes,
    # then HCIMPACT_ERR_SOLVER). Also: 1 m at rtol 1e-12, 100 m at rtol 1e-10.
    # Expected: the rest state [-10.00000099] at t = 1e300 within seconds.
    import hcimpact, time
    for h, rtol in ((10.0, 1e-10), (1.0, 1e-12), (100.0, 1e-10)):
        kw = dict(masses=[0.1], velocities=[0.0], gravity=-9.81, rtol=rtol,
                  wall_left=dict(stiffness=1e9, damping=1.0, gap=h))
        r = hcimpact.chain(**kw)
        print(f"h {h} m rtol {rtol:g}: until rest:", r.rest_time, r.positions)
        t0 = time.time()
        try:
            r = hcimpact.chain(**kw, t_end=1e300, max_steps=10**6)
            print("  t_end=1e300:", r.positions, f"{time.time() - t0:.1f} s")
        except hcimpact.HcimpactError as e:
            print("  t_end=1e300 GOT:", str(e)[:120], f"({time.time() - t0:.1f} s)")
    """


@case("settle_soft_floor_hang", timeout=70)
def _():
    """
    # D1b: two 0.1 kg balls on a soft floor (c = 1e3) with a stiff contact between them
    # (c = 1e14): until rest answers in 0.1 s (rest at 1.84 s); with t_end = 1e300 it
    # does not settle (100 rtol x_s = 4.6e-18 m against displacements of 0.0157 m, ulp
    # 3.5e-18) and runs for minutes (2e6 steps reach t = 5.3 s).
    import hcimpact, time
    kw = dict(masses=[0.1, 0.1], velocities=[0.0, 0.0], gaps=[0.0], stiffness=1e14, damping=1.0,
              wall_left=dict(stiffness=1e3, damping=1.0, gap=0.0), gravity=-9.81)
    r = hcimpact.chain(**kw)
    print("until rest:", r.rest_time, r.positions)
    t0 = time.time()
    try:
        r = hcimpact.chain(**kw, t_end=1e300, max_steps=2 * 10**6)
        print("t_end=1e300:", r.positions, f"{time.time() - t0:.1f} s")
    except hcimpact.HcimpactError as e:
        print("t_end=1e300 GOT:", e, f"({time.time() - t0:.1f} s)")
    """


@case("settle_low_mode", timeout=120)
def _():
    """
    # D2: a stack whose slow mode (the whole stack on a soft floor, period 44 ms) is
    # far slower than sqrt(g / x_s) of its stiffest contact: `settled` accepts a state
    # whose displacements pass within 100 rtol x_s of the equilibrium while that mode
    # still swings with ~200 times that amplitude (its speed is below the criterion's
    # 100 rtol sqrt(g x_s)). At t_end = 5 s rtol 1e-10 returns the equilibrium exactly,
    # but the state there is 148 x (100 rtol x_s) away: 1.5e4 rtol x_s, where the doc
    # promises 100 rtol. rtol 1e-12 and 1e-13 agree with each other (148.2, 148.2).
    # (Before 79cb44a..HEAD the state at 5 s was integrated.)
    import hcimpact, numpy as np
    g = 9.81
    xf = (0.2 * g / 1e5) ** (2 / 3)
    xp = (0.1 * g / 1e12) ** (2 / 3)
    eq = np.array([-xf, -xf - xp])
    delta = 100 * 1e-10 * xp
    for rtol in (1e-10, 1e-12, 1e-13):
        r = hcimpact.chain([0.1, 0.1], [0, 0], gaps=[0], stiffness=1e12, damping=1,
                           wall_left=dict(stiffness=1e5, damping=1, gap=0), gravity=-g,
                           t_end=5.0, rtol=rtol)
        print(f"rtol {rtol:g}: (positions - equilibrium) / (100 rtol_10 x_s) =",
              (r.positions - eq) / delta, "velocities", r.velocities)
    """


@case("scaled_exponent_below_one")
def _():
    """
    # D3: exponent n < 1 at a tiny speed: scaled_impact forms scale_x = V**p with
    # p = 2/(n+1) > 1, which underflows (V = 1e-250, n = 0.5: 1e-333 -> 0), so
    # scale_t = scale_x / V = 0 and scale_f = 0: the contact lasts 0 s and its peak
    # force is 0, though both are doubles: expected t_end 5.25e-90 s and peak force
    # 1.24e-161 N (the scaling of the same impact at 1 m/s: T V^(1/3), F V^(2/3)).
    # Fix idea: form scale_t = V**(p - 1) and scale_f = V**(n p) directly (or by logs).
    # Before the change: a ComputationError (CVODE); at V = 1e-230 the closed forms give
    # 2.44e-83 s and 2.67e-148 N, consistent with the scaling.
    import hcimpact
    V = 1e-250
    u = hcimpact.impact(mass=2 * 0.3 / 2.3, stiffness=1e9, exponent=0.5, damping=0.3, velocity=1.0)
    print("expected t_end", u.contact_time * V ** (1 / 3), "peak force", u.peak_force * V ** (2 / 3))
    r = hcimpact.chain([2.0, 0.3], [V, 0], gaps=[0], stiffness=1e9, exponent=0.5, damping=0.3 / V)
    print("got", r.contacts[["t_start", "t_end", "peak_force", "max_deformation"]], r.method_used)
    # before it underflows, scale_x is subnormal and carries few digits: at 1e-240 m/s
    # the duration and the peak force are off by 1.1e-5 and 5.6e-6 relative
    for V in (1e-232, 1e-236, 1e-240, 1e-243):
        r = hcimpact.chain([2.0, 0.3], [V, 0], gaps=[0], stiffness=1e9, exponent=0.5,
                           damping=0.3 / V)
        c = r.contacts[0]
        eT = u.contact_time * V ** (1 / 3)
        eF = u.peak_force * V ** (2 / 3)
        print(f"V {V:g}: t_end rel. error {abs(c['t_end'] / eT - 1):.1e}, "
              f"peak force rel. error {abs(c['peak_force'] / eF - 1):.1e}")
    """


@case("subnormal_inside_contact")
def _():
    """
    # D4: subnormal speeds, t_end (or a sample) inside the contact: the state comes from
    # body_state_at, vcm +- (m/M) x' with vcm = 2.5e-324 rounded to 0 (the new split
    # of end_exact is not used there): both bodies stopped, momentum_error 1.0, with
    # success. Expected: momentum kept ([5e-324, 0] or [0, 5e-324]); before the change
    # the answer was [5e-324, 0], momentum_error 0.
    import hcimpact
    r = hcimpact.chain([1.0, 1.0], [5e-324, 0.0], gaps=[0.0], stiffness=1e9, exponent=1.0,
                       t_end=3.5e-5, sample_times=[1e-5, 3e-5])
    print("t_end inside the contact (ends at 7.0e-5 s): velocities", r.velocities,
          "momentum_error", r.momentum_error, "samples", r.sample_velocities.tolist())
    """


@case("scaled_contact_time_overflow")
def _():
    """
    # D5: a large exponent at a subnormal speed: scale_t = V**p / V overflows (n = 100,
    # V = 5e-324: 8e316), the contact's end is +Inf, the event loop sees nothing before
    # huge and stops at t = 0 with both bodies stopped, no contact, success. Expected: an
    # error (the contact ends beyond the range of doubles) or at least the initial state
    # [5e-324, 0] at t = 0. Before the change: ComputationError.
    import hcimpact
    r = hcimpact.chain([1.0, 1.0], [5e-324, 0.0], gaps=[0.0], stiffness=1e9, exponent=100.0)
    print("time", r.time, "velocities", r.velocities, "contacts", r.n_contacts,
          "momentum_error", r.momentum_error, r.message)
    """


@case("sample_beyond_range")
def _():
    """
    # D6: the new final check of finite positions does not cover samples: a body thrown
    # up at 1e150 m/s under g = -1e-150 is back at 0 at t_end = 2e300 s (success, right),
    # but its sample at the apex (1e300 s, 5e449 m) is +Inf, and the pair's sample force
    # NaN, with success.
    import hcimpact
    r = hcimpact.chain([1.0, 1.0], [1e150, 1e150], gaps=[1.0], stiffness=1e9, gravity=-1e-150,
                       t_end=2e300, sample_times=[1e300])
    print(r.message, "positions", r.positions, "sample positions", r.sample_positions,
          "sample forces", r.sample_forces)
    """


@case("freefall_cluster_slow")
def _():
    """
    # Pre-existing (same at 79cb44a), found on the way: three touching balls falling freely
    # (gravity, no wall), the first struck at 1e-50 m/s: CVODE fails at t = 0 with an
    # initial step of 1.8e32 s. region_scales takes the static compression under
    # gravity (total g / c)^(1/n) as a compression scale though no wall holds the
    # weight, so x_ref / v_ref is absurd. The relative motion is that of g = 0 (which
    # succeeds: velocities - g t = (-0.0710, 0.0764, 0.9945) V). At 1e-6 and 1e-10 m/s it
    # succeeds but the relative velocities are off by 1.5e-5 and 2e-3 (rtol 1e-10 of
    # absolute velocities of g t ~ 1 m/s: no Galilean shift of the region's state).
    # Fixed the same evening (the region's own frame, test free-fall-frame): the contacts'
    # separation speeds over V are those without gravity at every V (the final velocities
    # in the engine's frame cannot hold V = 1e-50 m/s next to g t).
    import hcimpact
    r0 = hcimpact.chain([1.0, 1.0, 1.0], [1.0, 0, 0], gaps=[0, 0], stiffness=1e9)
    print("g = 0, V = 1: separation speeds", r0.contacts["separation_speed"])
    for V in (1e-6, 1e-10, 1e-50):
        try:
            r = hcimpact.chain([1.0, 1.0, 1.0], [V, 0, 0], gaps=[0, 0], stiffness=1e9,
                               gravity=-9.81)
            print(V, "(velocities - g t) / V =", (r.velocities - (-9.81) * r.time) / V,
                  "separation speeds / V", r.contacts["separation_speed"] / V)
        except hcimpact.HcimpactError as e:
            print(V, "GOT", str(e)[:160])
    """


if __name__ == "__main__":
    case.main()
