# SPDX-License-Identifier: Apache-2.0
"""hcimpact.chain: systems of bodies on a line (CVODE component).

Two bodies against the closed forms of one impact computed by the library's Fortran
(``impact``, ``two_body_velocities``) field by field; a cradle of touching balls
(momentum, energy, not (0, 0, V)); per-pair laws against scalars; walls, gravity and
samples; the contact list and its capacity; and every kind of bad input, each a clear
InputError (the checks of this package, or the library's own account). The C layer
under this package is compared with the Fortran API bit for bit in test/cvode.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import hcimpact
from hcimpact import _chain

pytestmark = pytest.mark.cvode

PAIR = 1.7135e10 / math.sqrt(2.0)     # two steel balls (Hertz), N/m^1.5
PLATE = 1.7135e10                     # a steel ball on a steel plate


@pytest.fixture(autouse=True)
def needs_chain():
    if not hcimpact.has_chain():
        pytest.skip("the library has no hcimpact_chain_simulate (CVODE component)")


def test_two_bodies_against_the_closed_forms():
    m, v, gap, b = (0.1, 0.3), (2.0, -0.5), 1e-4, 0.2
    r = hcimpact.chain(m, v, gaps=[gap], stiffness=PAIR, damping=b)
    assert r.n_contacts == 1 and len(r.contacts) == 1
    assert r.method_used == "exact" and r.counters["steps"] == 0
    c = r.contacts[0]
    assert c["pair"] == 1 and c["method"] == hcimpact.BY_CLOSED_FORMS
    mass = hcimpact.effective_mass(*m)
    out = hcimpact.impact(mass=mass, stiffness=PAIR, exponent=1.5, damping=b,
                          velocity=v[0] - v[1])
    v1, v2 = hcimpact.two_body_velocities(m[0], m[1], v[0], v[1], out.restitution)
    assert c["t_start"] == pytest.approx(gap / (v[0] - v[1]), rel=1e-15)
    assert c["t_end"] - c["t_start"] == pytest.approx(out.contact_time, rel=1e-11)
    assert c["approach_speed"] == pytest.approx(v[0] - v[1], rel=1e-15)
    assert c["separation_speed"] == pytest.approx(-out.rebound_velocity, rel=1e-14)
    assert c["peak_force"] == pytest.approx(out.peak_force, rel=1e-14)
    assert c["max_deformation"] == pytest.approx(out.max_compression, rel=1e-14)
    lost = 0.5 * mass * (v[0] - v[1]) ** 2 * out.energy_loss_ratio
    assert c["dissipated"] == pytest.approx(lost, rel=1e-13)
    assert r.velocities == pytest.approx([v1, v2], rel=1e-14)
    assert r.energy_error < 1e-14 and r.momentum_error < 1e-15
    # the centre of mass moves uniformly
    centre = (m[0] * r.positions[0] + m[1] * r.positions[1]) / sum(m)
    assert centre == pytest.approx((m[1] * gap + (m[0] * v[0] + m[1] * v[1]) * r.time)
                                   / sum(m), rel=1e-12)


def test_cradle_of_touching_balls():
    r = hcimpact.chain([0.1] * 3, [1.0, 0.0, 0.0], stiffness=PAIR, rtol=1e-10)
    assert r.method_used in ("integrated", "both")
    assert r.counters["steps"] > 0 and r.counters["clusters"] >= 1
    assert r.momentum_error < 1e-14
    assert r.energy_error < 1e-8
    # not the (0, 0, V) of instantaneous binary collisions
    assert abs(r.velocities[0]) > 1e-3 and abs(r.velocities[1]) > 1e-3
    assert np.all(np.diff(r.velocities) >= 0)                 # all separating
    assert np.all(np.diff(r.contacts["t_end"]) >= 0)          # in the order they ended
    assert set(r.contacts["pair"]) == {1, 2}
    assert r.contacts.dtype == hcimpact.CONTACT_DTYPE
    assert math.isnan(r.momentum_error) is False and r.rested is False
    assert math.isnan(r.rest_time)


def test_per_pair_laws_equal_scalars():
    args = dict(masses=[0.1, 0.2, 0.1, 0.3], velocities=[1.0, 0.0, -0.2, 0.0],
                gaps=[1e-5, 2e-5, 0.0])
    scalar = hcimpact.chain(**args, stiffness=PAIR, exponent=1.5, damping=0.05)
    arrays = hcimpact.chain(**args, stiffness=[PAIR] * 3, exponent=np.full(3, 1.5),
                            damping=(0.05, 0.05, 0.05))
    assert np.array_equal(scalar.velocities, arrays.velocities)
    assert np.array_equal(scalar.contacts, arrays.contacts)
    # a different law on one pair changes the answer
    other = hcimpact.chain(**args, stiffness=[PAIR, PAIR / 4, PAIR], damping=0.05)
    assert not np.array_equal(scalar.velocities, other.velocities)


def test_walls_gravity_and_samples():
    times = np.linspace(0.0, 0.2, 9)
    r = hcimpact.chain([0.1], [0.0], wall_left={"stiffness": PLATE, "damping": 0.5,
                                                "gap": 0.01},
                       gravity=-9.81, t_end=0.2, sample_times=times)
    assert r.time == pytest.approx(0.2)
    assert r.n_contacts >= 2 and np.all(r.contacts["pair"] == 0)
    first = r.contacts[0]
    # the ball falls 1 cm: it meets the floor at sqrt(2 h/g) with sqrt(2 g h)
    assert first["t_start"] == pytest.approx(math.sqrt(2 * 0.01 / 9.81), rel=1e-9)
    assert first["approach_speed"] == pytest.approx(math.sqrt(2 * 9.81 * 0.01), rel=1e-9)
    assert first["separation_speed"] < first["approach_speed"]
    assert r.sample_positions.shape == (9, 1) and r.sample_forces.shape == (9, 2)
    assert r.sample_positions[0, 0] == 0.0 and r.sample_velocities[0, 0] == 0.0
    assert np.all(r.sample_forces[:, 1] == 0.0)               # no right wall
    assert np.all(r.sample_positions[:, 0] >= -0.01 - 1e-4)   # never through the floor
    # the momentum balance with the floor's impulse: m v = m g t + J_left
    left, right = r.wall_impulses
    assert left > 0.0 and right == 0.0
    assert 0.1 * r.velocities[0] == pytest.approx(0.1 * -9.81 * 0.2 + left, abs=1e-12)
    assert r.momentum_error < 1e-10
    # before the ball reaches the floor, the floor has given nothing
    early = hcimpact.chain([0.1], [0.0], wall_left={"stiffness": PLATE, "gap": 0.01},
                           gravity=-9.81, t_end=0.04)
    assert early.wall_impulses == (0.0, 0.0) and early.momentum_error < 1e-15
    # defaults of a wall: exponent 1.5, damping 0, gap 0
    touching = hcimpact.chain([0.1], [-1.0], wall_left={"stiffness": PLATE})
    full = hcimpact.chain([0.1], [-1.0], wall_left={"stiffness": PLATE, "exponent": 1.5,
                                                    "damping": 0.0, "gap": 0.0})
    assert np.array_equal(touching.velocities, full.velocities)
    assert touching.velocities[0] == pytest.approx(1.0, rel=1e-14)


def test_right_wall_and_methods():
    args = dict(masses=[0.1, 0.1], velocities=[0.0, 1.0], gaps=[1e-4], stiffness=PAIR,
                damping=0.1, wall_right={"stiffness": PLATE, "damping": 0.1, "gap": 1e-4})
    exact = hcimpact.chain(**args, method="exact")
    integrated = hcimpact.chain(**args, method="integrated", rtol=1e-10, integrator="adams")
    assert exact.method_used == "exact" and integrated.method_used == "integrated"
    assert exact.contacts["pair"][0] == 2                    # the right wall first
    # (to a small multiple of rtol times the speed scale, 1 m/s)
    assert integrated.velocities == pytest.approx(exact.velocities, abs=1e-7)
    with pytest.raises(hcimpact.InputError, match="method exact: at t = "):
        hcimpact.chain([0.1] * 3, [1.0, 0.0, 0.0], stiffness=PAIR, method="exact")


def test_contact_list_and_its_capacity(monkeypatch):
    args = dict(masses=[0.1] * 4, velocities=[1.0, 0.0, 0.0, -1.0], gaps=1e-5,
                stiffness=PAIR, damping=0.02)
    full = hcimpact.chain(**args)
    assert full.n_contacts == len(full.contacts) >= 3
    cut = hcimpact.chain(**args, max_contacts=2)
    assert cut.n_contacts == full.n_contacts and len(cut.contacts) == 2
    assert np.array_equal(cut.contacts, full.contacts[:2])
    none = hcimpact.chain(**args, max_contacts=0)
    assert len(none.contacts) == 0 and none.n_contacts == full.n_contacts
    # more contacts than the first array holds: the run is repeated with room for all
    monkeypatch.setattr(_chain, "_FIRST_CAPACITY", 1)
    monkeypatch.setattr(_chain, "_INT_MAX", 1 + 8 * 4 + 100)
    again = hcimpact.chain(**args)
    assert np.array_equal(again.contacts, full.contacts)


def test_limits_up_to_int64_are_passed_as_they_are():
    args = dict(masses=[0.1, 0.1], velocities=[1.0, 0.0], stiffness=PAIR)
    default = hcimpact.chain(**args)
    largest = hcimpact.chain(**args, max_steps=2**63 - 1, max_events=np.int64(2**63 - 1))
    assert np.array_equal(largest.contacts, default.contacts)
    with pytest.raises(hcimpact.ComputationError, match="max_events = 1 contacts"):
        hcimpact.chain([0.1] * 3, [1.0, 0.0, -1.0], gaps=1e-4, stiffness=PAIR, max_events=1)


def test_max_contacts_caps_the_list_without_allocating_it(monkeypatch):
    # a ball between two walls 1 cm away: a contact every 20 ms, 50 in a second
    wall = {"stiffness": PLATE, "gap": 0.01}
    rattle = dict(masses=[0.1], velocities=[1.0], wall_left=wall, wall_right=wall, t_end=1.0)
    full = hcimpact.chain(**rattle)
    assert full.n_contacts == len(full.contacts) == 50
    # a cap far above the contacts made: the list of those made (the cap, 2**31 - 1
    # records of 64 bytes, was allocated: 128 GiB, a MemoryError)
    one = hcimpact.chain([0.1, 0.1], [1.0, 0.0], stiffness=PAIR, max_contacts=2**31 - 1)
    assert one.n_contacts == len(one.contacts) == 1
    assert np.array_equal(hcimpact.chain(**rattle, max_contacts=2**31 - 1).contacts,
                          full.contacts)
    # more contacts than the first array holds (1 + 8 n = 9): run again with room for
    # all of them up to the cap
    monkeypatch.setattr(_chain, "_FIRST_CAPACITY", 1)
    for cap, kept in ((20, 20), (None, 50), (2**31 - 1, 50), (50, 50), (9, 9), (5, 5),
                      (0, 0)):
        again = hcimpact.chain(**rattle, max_contacts=cap)
        assert again.n_contacts == full.n_contacts
        assert np.array_equal(again.contacts, full.contacts[:kept])


def test_hertz_and_damping_helpers_take_arrays():
    radius = np.array([0.01, 0.02, 0.015])
    c = hcimpact.hertz_constant(2e11, 0.3, radius[:-1], 2e11, 0.3, radius[1:])
    assert c.shape == (2,)
    assert c[1] == hcimpact.hertz_constant(2e11, 0.3, 0.02, 2e11, 0.3, 0.015)
    b = hcimpact.damping_for_restitution([0.9, 0.5], 2.0)
    assert b[1] == hcimpact.damping_for_restitution(0.5, 2.0)
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.damping_for_restitution([0.9, 1.5], 2.0)
    assert info.value.index == 1


@pytest.mark.parametrize("kwargs, text", [
    (dict(masses=[], velocities=[]), "at least one body"),
    (dict(masses=[0.1, 0.1], velocities=[1.0]), "velocities has 1 values"),
    (dict(masses=[[0.1, 0.1]], velocities=[1.0, 0.0]), "1-D"),
    (dict(masses=[0.1, 0.1], velocities=[1.0, 0.0]), "stiffness is needed"),
    (dict(masses=[0.1, 0.1], velocities=[1.0, 0.0], stiffness=[PAIR, PAIR]),
     "stiffness has 2 values, 1 needed"),
    (dict(masses=[0.1] * 3, velocities=[1, 0, 0], gaps=[0.0], stiffness=PAIR),
     "gaps has 1 values, 2 needed"),
    (dict(masses=[0.1, 1j], velocities=[1.0, 0.0], stiffness=PAIR), "complex"),
    (dict(masses=[0.1, "x"], velocities=[1.0, 0.0], stiffness=PAIR), "not a real number"),
    (dict(masses=[0.1], velocities=[1.0], wall_left=5.0), "None or a dict"),
    (dict(masses=[0.1], velocities=[1.0], wall_left={"stifness": PLATE}), "unknown keys"),
    (dict(masses=[0.1], velocities=[1.0], wall_right={"gap": 0.0}), "needs its stiffness"),
    (dict(masses=[0.1], velocities=[1.0], method="fast"), "method must be one of"),
    (dict(masses=[0.1], velocities=[1.0], integrator="rk4"), "integrator must be one of"),
    (dict(masses=[0.1], velocities=[1.0], t_end=0.0), "t_end = 0.0 must be positive"),
    (dict(masses=[0.1], velocities=[1.0], rtol=0.0), "rtol = 0.0 must lie in (0, 0.01]"),
    (dict(masses=[0.1], velocities=[1.0], rtol=1.0), "must lie in (0, 0.01]"),
    (dict(masses=[0.1], velocities=[1.0], rtol=0.5), "must lie in (0, 0.01]"),
    (dict(masses=[0.1], velocities=[1.0], max_steps=0), "max_steps must be a positive"),
    (dict(masses=[0.1], velocities=[1.0], max_events=True), "max_events must be a positive"),
    (dict(masses=[0.1], velocities=[1.0], max_events=2.5), "max_events must be a positive"),
    (dict(masses=[0.1], velocities=[1.0], max_contacts=-1), "must not be negative"),
    (dict(masses=[0.1], velocities=[1.0], max_contacts=2**40), "outside the range of a C int"),
    # limits beyond int64_t (ctypes would pass 2**64 + 5 as 5), not numbers, not positive
    (dict(masses=[0.1], velocities=[1.0], max_steps=2**64 + 5), "max_steps must be a positive"),
    (dict(masses=[0.1], velocities=[1.0], max_events=2**64 + 1), "max_events must be a positive"),
    (dict(masses=[0.1], velocities=[1.0], max_steps=2**63), "at most 2**63 - 1"),
    (dict(masses=[0.1], velocities=[1.0], max_events=-2**64), "max_events must be a positive"),
    (dict(masses=[0.1], velocities=[1.0], max_steps=math.inf), "max_steps must be a positive"),
    (dict(masses=[0.1], velocities=[1.0], max_events=math.nan), "max_events must be a positive"),
])
def test_bad_input_checked_here(kwargs, text):
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.chain(**kwargs)
    assert text in str(info.value)
    assert info.value.function == "hcimpact_chain_simulate"


@pytest.mark.parametrize("kwargs, name, text", [
    (dict(masses=[0.1, 0.0], velocities=[1.0, 0.0], stiffness=PAIR), "HCIMPACT_ERR_MASS",
     "body 2"),
    (dict(masses=[0.1, math.nan], velocities=[1.0, 0.0], stiffness=PAIR),
     "HCIMPACT_ERR_NOT_FINITE", "body 2"),
    (dict(masses=[0.1, 0.1], velocities=[math.inf, 0.0], stiffness=PAIR),
     "HCIMPACT_ERR_NOT_FINITE", "body 1"),
    (dict(masses=[0.1, 0.1], velocities=[1.0, 0.0], gaps=[-1e-9], stiffness=PAIR),
     "HCIMPACT_ERR_DOMAIN", "gap 1 is negative"),
    (dict(masses=[0.1, 0.1], velocities=[1.0, 0.0], stiffness=-PAIR),
     "HCIMPACT_ERR_STIFFNESS", "pair 1"),
    (dict(masses=[0.1, 0.1], velocities=[1.0, 0.0], stiffness=PAIR, damping=-0.1),
     "HCIMPACT_ERR_DAMPING", "pair 1"),
    (dict(masses=[0.1], velocities=[1.0], wall_left={"stiffness": PLATE, "gap": -1.0}),
     "HCIMPACT_ERR_DOMAIN", "left wall"),
    (dict(masses=[0.1], velocities=[1.0], gravity=math.nan), "HCIMPACT_ERR_NOT_FINITE",
     "gravity"),
    (dict(masses=[0.1], velocities=[1.0], sample_times=[0.2, 0.1]), "HCIMPACT_ERR_SIZE",
     "must not decrease"),
    (dict(masses=[0.1], velocities=[1.0], sample_times=[-0.1]), "HCIMPACT_ERR_DOMAIN",
     "must not be negative"),
    (dict(masses=[0.1] * 3, velocities=[1.0, 0.0, -1.0], gaps=[1e308, 1e308], stiffness=PAIR),
     "HCIMPACT_ERR_DOMAIN", "add up beyond the range"),
    (dict(masses=[1e308, 1e308], velocities=[1.0, 0.0], gaps=[0.01], stiffness=PAIR),
     "HCIMPACT_ERR_DOMAIN", "masses add up beyond"),
    # (found only at the end: bodies flying apart beyond 1.8e308 m by t_end)
    (dict(masses=[0.1, 0.1], velocities=[-1e10, 1e10], stiffness=PAIR, t_end=1e300),
     "HCIMPACT_ERR_DOMAIN", "a position or a velocity (final or sampled) leaves"),
    # (a sample at the apex beyond the range, the final state within it)
    (dict(masses=[1.0, 1.0], velocities=[1e150, 1e150], gaps=[1.0], stiffness=PAIR,
          gravity=-1e-150, t_end=2e300, sample_times=[1e300]),
     "HCIMPACT_ERR_DOMAIN", "(final or sampled) leaves the range"),
])
def test_bad_input_from_the_library(kwargs, name, text):
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.chain(**kwargs)
    assert info.value.name == name
    assert text in str(info.value)


@pytest.mark.parametrize("kwargs, name", [
    (dict(velocities=[10**400, 0.0]), "velocities"),
    (dict(masses=[0.1, -10**400]), "masses"),
    (dict(gaps=10**400), "gaps"),
    (dict(stiffness=[10**400]), "stiffness"),
    (dict(t_end=10**400), "t_end"),
    (dict(gravity=10**400), "gravity"),
    (dict(rtol=10**400), "rtol"),
    (dict(wall_left={"stiffness": PLATE, "gap": 10**400}), "wall_left['gap']"),
    (dict(sample_times=[0.0, 10**400]), "sample_times"),
    (dict(masses=[[0.1], [0.1, 0.2]]), "masses"),
    (dict(sample_times=[[0.0, 1.0], [2.0]]), "sample_times"),
    (dict(masses=np.ma.masked_array([0.1, 0.1], mask=[False, True])), "masses"),
    (dict(velocities=np.ma.masked_array([1.0, 0.0], mask=[True, False])), "velocities"),
    (dict(gravity=np.ma.masked), "gravity"),
])
def test_arguments_numpy_cannot_convert_are_input_errors(kwargs, name):
    # (were OverflowError, NumPy's ValueError; a masked mass was used as its hidden 0)
    args = dict(masses=[0.1, 0.1], velocities=[1.0, 0.0], stiffness=PAIR)
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.chain(**dict(args, **kwargs))
    assert name in str(info.value) and info.value.function == "hcimpact_chain_simulate"


@pytest.mark.parametrize("kwargs, argument, name", [
    (dict(stiffness="garbage"), "stiffness", "HCIMPACT_ERR_DOMAIN"),
    (dict(stiffness=-PAIR), "stiffness", "HCIMPACT_ERR_STIFFNESS"),
    (dict(stiffness=0.0), "stiffness", "HCIMPACT_ERR_STIFFNESS"),
    (dict(stiffness=math.inf), "stiffness", "HCIMPACT_ERR_NOT_FINITE"),
    (dict(stiffness=PAIR, exponent=math.nan), "exponent", "HCIMPACT_ERR_NOT_FINITE"),
    (dict(stiffness=PAIR, exponent=1e-7), "exponent", "HCIMPACT_ERR_EXPONENT"),
    (dict(stiffness=PAIR, exponent=None), "exponent", "HCIMPACT_ERR_NOT_FINITE"),
    (dict(stiffness=PAIR, damping=-0.1), "damping", "HCIMPACT_ERR_DAMPING"),
    (dict(stiffness=PAIR, damping=1j), "damping", "HCIMPACT_ERR_DOMAIN"),
    # (finiteness first, as the library checks a law)
    (dict(stiffness=-PAIR, damping=math.nan), "damping", "HCIMPACT_ERR_NOT_FINITE"),
])
def test_law_of_a_single_body_is_checked(kwargs, argument, name):
    # one body has no pair and the library reads no law, but a bad law is the
    # caller's error all the same: the status the library gives it between two bodies
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.chain([0.1], [1.0], **kwargs)
    assert info.value.name == name and argument in str(info.value)
    assert info.value.function == "hcimpact_chain_simulate"
    with pytest.raises(hcimpact.InputError) as pair:
        hcimpact.chain([0.1, 0.1], [1.0, 0.0], **kwargs)
    assert pair.value.name == name


@pytest.mark.parametrize("kwargs", [
    dict(stiffness=[PAIR]), dict(stiffness=PAIR, exponent=[1.5]),
    dict(stiffness=PAIR, damping=np.zeros(2)),
])
def test_law_arrays_of_a_single_body_are_empty(kwargs):
    # one value per pair, as gaps: none for a single body
    with pytest.raises(hcimpact.InputError, match="for a single body"):
        hcimpact.chain([0.1], [1.0], **kwargs)
    with pytest.raises(hcimpact.InputError, match="for a single body"):
        hcimpact.chain([0.1], [1.0], gaps=[0.0])


def test_law_of_a_single_body_may_be_given():
    free = hcimpact.chain([0.1], [3.0], t_end=1.0)
    for kwargs in (dict(stiffness=PAIR, exponent=1.0, damping=0.5), dict(stiffness=None),
                   dict(stiffness=[], exponent=[], damping=np.empty(0)),
                   dict(stiffness=np.float32(1e3), exponent=2, damping=0)):
        r = hcimpact.chain([0.1], [3.0], t_end=1.0, **kwargs)
        assert np.array_equal(r.positions, free.positions) and r.n_contacts == 0


def test_without_contacts():
    r = hcimpact.chain([0.1], [3.0])
    assert r.n_contacts == 0 and len(r.contacts) == 0 and r.method_used == "exact"
    assert r.energy_error == 0.0
    r = hcimpact.chain([0.1, 0.2], [-1.0, 1.0], gaps=0.0, stiffness=PAIR)   # separating
    assert r.n_contacts == 0 and np.array_equal(r.velocities, [-1.0, 1.0])
    assert "ChainResult(n=2" in repr(r)
