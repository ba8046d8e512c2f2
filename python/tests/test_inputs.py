# SPDX-License-Identifier: Apache-2.0
"""Arguments that ctypes or NumPy would silently change, and exceptions raised inside a
user's elastic law: each must give a clear error, never a wrong number."""

from __future__ import annotations

import numpy as np
import pytest

import hcimpact

BALL = dict(mass=0.1, stiffness=1.7135e10, exponent=1.5, damping=0.1, velocity=5.0)


def test_integers_beyond_c_int_are_not_truncated():
    # ctypes would pass 2**32 + 3 as 3, whose message is that of a real status
    assert hcimpact.status_message(2**32 + 3) == "unknown status code"
    assert hcimpact.status_message(-2**40) == "unknown status code"
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.time_law_samples(2**32 + 3, **BALL)
    assert info.value.status == 14            # HCIMPACT_ERR_SIZE
    with pytest.raises(hcimpact.InputError):
        hcimpact.time_law_samples(2.5, **BALL)   # not an integer


def test_complex_input_is_refused():
    with pytest.raises(hcimpact.InputError, match="complex"):
        hcimpact.restitution(np.array([0.5 + 1j, 1.0]))
    with pytest.raises(hcimpact.InputError, match="complex"):
        hcimpact.restitution(np.complex128(0.5 + 1j))
    with pytest.raises(hcimpact.InputError, match="complex"):
        hcimpact.impact(**dict(BALL, velocity=np.array([1.0 + 2j, 2.0])))
    with pytest.raises(hcimpact.InputError, match="complex"):
        hcimpact.time_law(np.array([1e-5 + 1e-6j]), **BALL)
    # a complex number with a zero imaginary part is still refused: the type is wrong
    with pytest.raises(hcimpact.InputError, match="complex"):
        hcimpact.lambert_w0(np.array([1.0 + 0j]))


# a Python int beyond the range of doubles (NumPy: OverflowError), a ragged list (NumPy:
# ValueError), a masked array with a masked entry (NumPy: its hidden value, silently)
HUGE = 10**400
RAGGED = [[0.5], [0.5, 0.6]]
MASKED = np.ma.masked_array([0.5, 0.6], mask=[False, True])
CONVERSIONS = [
    (lambda a: hcimpact.restitution(a), "the argument"),
    (lambda a: hcimpact.lambert_w0(a), "the argument"),
    (lambda a: hcimpact.u_minus_log1p(a), "u"),
    (lambda a: hcimpact.impact(**dict(BALL, velocity=a)), "velocity"),
    (lambda a: hcimpact.impact(**dict(BALL, mass=a), errors="nan"), "mass"),
    (lambda a: hcimpact.time_law(a, **BALL), "t"),
    (lambda a: hcimpact.velocity_at_depth(a, **BALL), "x"),
    (lambda a: hcimpact.damping_for_restitution(a, 2.0), "e"),
    (lambda a: hcimpact.hertz_constant(2e11, 0.3, a, 2e11, 0.3), "radius1"),
    (lambda a: hcimpact.effective_mass(a), "mass1"),
    (lambda a: hcimpact.two_body_velocities(0.1, 0.2, a, 0.0, 0.5), "velocity1"),
    (lambda a: hcimpact.contact_force(a, 0.0, stiffness=1e10), "x"),
    (lambda a: hcimpact.contact_force(1e-5, 0.0, stiffness=1e10, damping=a), "damping"),
]


@pytest.mark.parametrize("call, name", CONVERSIONS)
@pytest.mark.parametrize("value", [HUGE, -HUGE, [0.5, HUGE], RAGGED, MASKED],
                         ids=["huge", "-huge", "huge-element", "ragged", "masked"])
def test_arguments_numpy_cannot_convert_are_input_errors(call, name, value):
    with pytest.raises(hcimpact.InputError) as info:
        call(value)
    assert name in str(info.value) and info.value.status == 8   # HCIMPACT_ERR_DOMAIN


def test_masked_arrays_without_masked_entries_are_their_values():
    values = np.ma.masked_array([0.5, 0.6], mask=[False, False])
    assert np.array_equal(hcimpact.restitution(values), hcimpact.restitution([0.5, 0.6]))
    assert hcimpact.restitution(np.ma.masked_array(0.5)) == hcimpact.restitution(0.5)
    with pytest.raises(hcimpact.InputError, match="masked"):
        hcimpact.restitution(np.ma.masked)


def test_contact_force_checks_as_the_others():
    # it converted its arguments itself: TypeError for complex, NumPy's ValueError for
    # shapes that do not broadcast
    with pytest.raises(hcimpact.InputError, match="complex"):
        hcimpact.contact_force(1e-5 + 1j, 1.0, stiffness=1.0)
    with pytest.raises(hcimpact.InputError, match="do not broadcast"):
        hcimpact.contact_force([1e-5, 2e-5], [1.0, 2.0, 3.0], stiffness=1.0)
    with pytest.raises(hcimpact.InputError, match="x is not a real number"):
        hcimpact.contact_force("small", 1.0, stiffness=1.0)
    # large integers within the range of doubles are numbers
    r = hcimpact.contact_force(1e-5, 0.0, stiffness=10**20)
    assert r.force == hcimpact.contact_force(1e-5, 0.0, stiffness=1e20).force


@pytest.mark.parametrize("branch", [1.0, 2.0, True, "Compression ", None])
def test_branch_must_be_a_branch(branch):
    x_max = hcimpact.impact(**BALL).max_compression
    with pytest.raises(hcimpact.InputError):
        hcimpact.velocity_at_depth(0.5 * x_max, branch=branch, **BALL)


def test_branch_names_and_codes():
    x_max = hcimpact.impact(**BALL).max_compression
    v1 = hcimpact.velocity_at_depth(0.5 * x_max, branch="compression", **BALL)
    assert v1 == hcimpact.velocity_at_depth(0.5 * x_max, branch=hcimpact.COMPRESSION, **BALL)
    v2 = hcimpact.velocity_at_depth(0.5 * x_max, branch=np.int64(2), **BALL)
    assert v2 == hcimpact.velocity_at_depth(0.5 * x_max, branch="restitution", **BALL)
    assert v1 > 0 > v2


def hertz_law(fail_on=None, error=ZeroDivisionError):
    """The Hertz law as three callbacks; ``fail_on`` raises ``error`` from that one.
    ``calls`` counts the calls of the failing one."""
    c = BALL["stiffness"]
    calls = {"count": 0}

    def make(name, function):
        def law(x):
            if name == fail_on:
                calls["count"] += 1
                raise error("inside the law")
            return function(x)
        return law

    laws = (make("force", lambda x: c * x**1.5), make("potential", lambda x: c * x**2.5 / 2.5),
            make("force_derivative", lambda x: 1.5 * c * x**0.5))
    return laws, calls


def test_law_without_exception_works():
    laws, _ = hertz_law()
    r = hcimpact.impact_law(*laws, mass=0.1, damping=0.1, velocity=5.0)
    assert r.restitution == pytest.approx(hcimpact.impact(**BALL).restitution, rel=1e-12)


@pytest.mark.parametrize("which", ["force", "potential", "force_derivative"])
def test_exception_in_a_law_is_raised_again_at_once(which):
    laws, calls = hertz_law(fail_on=which)
    with pytest.raises(ZeroDivisionError, match="inside the law"):
        hcimpact.impact_law(*laws, mass=0.1, damping=0.1, velocity=5.0)
    assert calls["count"] == 1


def test_system_exit_in_a_law_is_not_swallowed():
    laws, calls = hertz_law(fail_on="force", error=SystemExit)
    with pytest.raises(SystemExit):
        hcimpact.impact_law(*laws, mass=0.1, damping=0.1, velocity=5.0)
    assert calls["count"] == 1


def test_law_returning_nan_is_an_input_error():
    c = BALL["stiffness"]
    laws = (lambda x: float("nan"), lambda x: c * x**2.5 / 2.5, lambda x: 1.5 * c * x**0.5)
    with pytest.raises(hcimpact.InputError) as info:
        hcimpact.impact_law(*laws, mass=0.1, damping=0.1, velocity=5.0)
    assert info.value.status == 13           # HCIMPACT_ERR_ELASTIC_LAW
