# SPDX-License-Identifier: Apache-2.0
"""A system of bodies on a line from Python: ``hcimpact.chain``.

A thin layer over ``hcimpact_chain_simulate_monitored`` (include/hcimpact_cvode.h, the
CVODE component; its monitor, which shows progress and stops a run on Ctrl-C, is in
_watch.py): the arrays go to the library as they are, the result comes back in NumPy
arrays, the contacts as a structured array that has the C records' layout. The model,
the two ways of computing and their accuracy are in doc/chains.md; the conventions are
those of the C interface (doc/c-api.md):

- bodies are numbered left to right (index 0 is the leftmost), velocities are positive
  to the right, ``gaps[i]`` is the surface gap between bodies i and i + 1 (0: touching
  without preload);
- the positions are those of points whose distance is the gap: body 0 starts at 0,
  body i + 1 at body i's position + gaps[i]; a left wall stands at -gap, a right wall at
  the last body's position + gap;
- contact pairs are numbered 0 .. n: pair p is the contact on the left of body p, so
  pair 0 is the left wall and body 0, pair p (1 <= p < n) bodies p - 1 and p, pair n
  the last body and the right wall.
"""

from __future__ import annotations

import ctypes
import math
from ctypes import POINTER, byref, c_double
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from . import _library
from ._api import _MESSAGE_SIZE, _c_int, _component_function, _raise, _real, _scalar
from ._force import contact_force
from ._types import (CHAIN_COUNTS, ChainContact, ChainLaw, ChainOptions, ChainOutcome,
                     ChainSamples, ChainWall, InputError)
from ._watch import Watch

__all__ = ["chain", "ChainResult", "has_chain", "BY_CLOSED_FORMS", "BY_INTEGRATION",
           "CONTACT_DTYPE"]

#: ``contacts["method"]`` of a contact computed by the closed forms of one impact
BY_CLOSED_FORMS = 1
#: ``contacts["method"]`` of a contact computed (at least in part) by CVODE
BY_INTEGRATION = 2

#: The NumPy dtype of ``ChainResult.contacts``: the layout of ``hcimpact_chain_contact``
#: (t_start, t_end, approach_speed, separation_speed, peak_force, max_deformation,
#: dissipated, pair, method)
CONTACT_DTYPE = np.dtype(ChainContact)

_WHERE = "hcimpact_chain_simulate"
_FUNCTION = "hcimpact_chain_simulate_monitored"
_METHODS = {"auto": 0, "exact": 1, "integrated": 2}
_INTEGRATORS = {"bdf": 1, "adams": 2}
_METHOD_USED = {1: "exact", 2: "integrated", 3: "both"}
_WALL_KEYS = ("stiffness", "exponent", "damping", "gap")
# contacts recorded on the first try; a run with more is run again with room for all
# of them (up to max_contacts)
_FIRST_CAPACITY = 65536
_INT_MAX = 2**31 - 1
# max_steps and max_events are int64_t, which ctypes would wrap (2**64 + 5 into 5)
_INT64_MAX = 2**63 - 1
_ERR_DOMAIN, _ERR_SIZE = 8, 14


@dataclass(frozen=True, repr=False)
class ChainResult:
    """What :func:`chain` computes (SI units).

    ``positions`` and ``velocities`` are the state at ``time`` (for a system that came
    to rest on a wall, its rest state); ``contacts`` a structured NumPy array, one
    record per contact that ended, in the order they ended (one still in progress at
    ``t_end`` is not listed), with the fields ``pair``, ``t_start``,
    ``t_end``, ``approach_speed``, ``separation_speed``, ``peak_force``,
    ``max_deformation``, ``dissipated`` and ``method`` (:data:`BY_CLOSED_FORMS` or
    :data:`BY_INTEGRATION`); ``n_contacts`` counts every contact (more than
    ``len(contacts)`` only when ``max_contacts`` cut the list). ``method_used`` is
    ``"exact"`` (every contact by the closed forms, also when there was none),
    ``"integrated"`` or ``"both"``. The samples are ``None`` unless sample times were
    given: then ``sample_positions`` and ``sample_velocities`` have the shape
    (samples, n) and ``sample_forces`` (samples, n + 1), one column per pair; NaN at a
    time after ``t_end``.
    """

    #: time reached, s: t_end, the time after which no contact can happen, or rest
    time: float
    #: positions (m) and velocities (m/s) at ``time``
    positions: np.ndarray
    velocities: np.ndarray
    #: the contacts (structured array, :data:`CONTACT_DTYPE`)
    contacts: np.ndarray
    #: every contact, also those not recorded
    n_contacts: int
    #: relative error of kinetic + elastic + gravitational + dissipated energy
    energy_error: float
    #: relative error of the momentum against the initial one plus the outside
    #: impulses: gravity's M g t and the walls'
    momentum_error: float
    #: the impulses the left and the right wall gave the system up to ``time``, N s
    #: along the line (left >= 0, right <= 0; 0 without the wall)
    wall_impulses: tuple
    #: initial kinetic energy and the energy dissipated, J
    initial_energy: float
    dissipated: float
    #: "exact", "integrated" or "both"
    method_used: str
    #: whether the system came to rest on a wall under gravity, and when (else NaN)
    rested: bool
    rest_time: float
    #: work done: closed_form_contacts, integrated_contacts, steps, rhs_evals,
    #: jacobian_evals, roots, clusters
    counters: dict
    #: the samples, or None
    sample_times: Any = None
    sample_positions: Any = None
    sample_velocities: Any = None
    sample_forces: Any = None
    #: the library's account of the run ("success")
    message: str = "success"

    def __repr__(self) -> str:
        return (f"ChainResult(n={self.velocities.size}, time={self.time:.6g} s, "
                f"contacts={self.n_contacts}, method_used={self.method_used!r}, "
                f"energy_error={self.energy_error:.3g})")


def has_chain() -> bool:
    """True when the library has ``hcimpact_chain_simulate_monitored`` (the CVODE
    component), which :func:`chain` calls."""
    return _library.component(_FUNCTION, "hcimpact_cvode") is not None


def _vector(values: Any, name: str, size: int | None = None) -> np.ndarray:
    """A 1-D float64 array (a scalar stands for ``size`` equal values)."""
    a = _real(values, name, _WHERE)
    if a.ndim == 0 and size is not None:
        a = np.full(size, float(a))
    if a.ndim != 1:
        raise InputError(_ERR_SIZE, f"{name} must be a 1-D array (shape {a.shape})", _WHERE)
    if size is not None and a.size != size:
        raise InputError(_ERR_SIZE, f"{name} has {a.size} values, {size} needed "
                         "(one per neighbouring pair, or one for all)" if size != 0 else
                         f"{name} has {a.size} values for a single body (none needed)",
                         _WHERE)
    return np.ascontiguousarray(a)


def _wall(wall: Any, side: str) -> ChainWall | None:
    """The C wall of a dict {stiffness, exponent=1.5, damping=0, gap=0}, or None."""
    if wall is None:
        return None
    name = f"wall_{side}"
    if not isinstance(wall, dict):
        raise InputError(_ERR_DOMAIN, f"{name} must be None or a dict with stiffness, "
                         f"exponent, damping and gap, not {type(wall).__name__}", _WHERE)
    unknown = sorted(set(wall) - set(_WALL_KEYS))
    if unknown:
        raise InputError(_ERR_DOMAIN, f"{name}: unknown keys {unknown} (a wall has "
                         "stiffness, exponent, damping, gap)", _WHERE)
    if "stiffness" not in wall:
        raise InputError(_ERR_DOMAIN, f"{name} needs its stiffness (N/m^n)", _WHERE)
    values = {"exponent": 1.5, "damping": 0.0, "gap": 0.0}
    values.update(wall)
    return ChainWall(*[_scalar(values[key], f"{name}[{key!r}]", _WHERE) for key in _WALL_KEYS])


def _law_of_no_pair(values: tuple) -> None:
    """The law of a single body's pairs, which it has none of: the library reads no law,
    but a bad one is the caller's error all the same. An array must be empty (one value
    per pair, as gaps); scalars are checked by the library's own check of a law, that of
    the contact-force element (:func:`contact_force`, statuses as for a pair's law),
    stiffness None (none given, as it may be for one body) standing for a valid one."""
    law = {}
    for value, name in values:
        if value is None and name == "stiffness":
            continue
        converted = _real(value, name, _WHERE)
        if converted.ndim == 0:
            law[name] = float(converted)
        else:
            _vector(converted, name, 0)
    if not law:
        return
    given = ", ".join(f"{name} {value!r}" for name, value in law.items())
    try:
        contact_force(0.0, 0.0, law.get("stiffness", 1.0), law.get("exponent", 1.5),
                      law.get("damping", 0.0))
    except InputError as error:
        raise InputError(error.status, f"the law of the pairs ({given}): {error.message} (a "
                         "single body has no pair, but the law is checked all the same)",
                         _WHERE) from None


def _choice(value: Any, choices: dict, name: str) -> int:
    if not isinstance(value, str) or value.lower() not in choices:
        raise InputError(_ERR_DOMAIN, f"{name} must be one of {', '.join(choices)}, not "
                         f"{value!r}", _WHERE)
    return choices[value.lower()]


def _limit(value: Any, name: str) -> int:
    """A limit of the library, an int64_t in 1 .. 2**63 - 1 (None: the library's default,
    passed as 0; a 0 given here is refused, not taken for the default)."""
    if value is None:
        return 0
    try:
        count = int(value) if not isinstance(value, (bool, np.bool_)) else None
    except (TypeError, ValueError, OverflowError):
        count = None
    if count is None or count != value or not 1 <= count <= _INT64_MAX:
        raise InputError(_ERR_DOMAIN, f"{name} must be a positive integer (at most "
                         f"2**63 - 1, an int64_t) or None, not {value!r}", _WHERE)
    return count


def chain(masses: Any, velocities: Any, gaps: Any = None, stiffness: Any = None,
          exponent: Any = 1.5, damping: Any = 0.0, wall_left: Any = None,
          wall_right: Any = None, gravity: float = 0.0, t_end: float | None = None,
          rtol: float = 1.0e-10, method: str = "auto", *, integrator: str = "bdf",
          sample_times: Any = None, max_contacts: int | None = None,
          max_steps: int | None = None, max_events: int | None = None,
          progress: Callable[[float, int, int], Any] | None = None) -> ChainResult:
    """A system of bodies on a line: the closed forms of one impact wherever contacts
    are isolated, SUNDIALS CVODE where they overlap (doc/chains.md).

    - ``masses`` (kg, > 0) and ``velocities`` (m/s, positive to the right): one per
      body, left to right;
    - ``gaps`` (m, >= 0): one per neighbouring pair, or a scalar for all; None: all
      touching (0, without preload);
    - ``stiffness`` c (N/m^n), ``exponent`` n, ``damping`` b (s/m) of the pairs' laws
      f = c x^n (1 + b x'): a scalar, or one value per pair (a single body has none:
      an array must be empty, a scalar is checked all the same; stiffness may be None)
      (:func:`hertz_constant` and :func:`damping_for_restitution` give them from
      materials and radii, and from a restitution at a speed; both take arrays);
    - ``wall_left``, ``wall_right``: None (no wall) or a dict with ``stiffness`` and
      optionally ``exponent`` (1.5), ``damping`` (0) and ``gap`` (0: touching);
    - ``gravity``: the constant acceleration along the line in m/s^2 (negative: to the
      left; a stack on a floor is a line with the floor as its left wall and
      gravity = -9.81);
    - ``t_end`` (s, > 0), or None: until no contact can happen again (all bodies
      separating with no wall ahead, or at rest on a wall);
    - ``rtol``: CVODE's relative tolerance in (0, 0.01]; ``method``: ``"auto"``,
      ``"exact"`` (the closed forms only: a cluster is an :class:`InputError`)
      or ``"integrated"`` (CVODE for everything); ``integrator``: ``"bdf"`` or
      ``"adams"``;
    - ``sample_times``: times (s, increasing, >= 0) at which to sample positions,
      velocities and the pairs' forces;
    - ``max_contacts``: record at most this many contacts (all are counted; None: all;
      the room allocated is that of the contacts made, not the cap); ``max_steps``,
      ``max_events``: the library's limits of steps and contacts, integers in
      1 .. 2**63 - 1 (None: 1e8 each; beyond them a :class:`ComputationError`);
    - ``progress``: None, or a function ``progress(time, steps, events)`` that the
      run calls every 64 passes of its loop (steps, events) with the time it has
      reached (s), the integration steps and the events so far (what ``max_events``
      counts: the starts and ends of the contacts the closed forms compute and the
      switches of method, not the contacts inside an integrated cluster); a true answer stops the run (a :class:`ComputationError`,
      "stopped by the caller's monitor"), an exception it raises stops the run and is
      raised.

    Ctrl-C (SIGINT) stops a run within 64 passes and raises
    ``KeyboardInterrupt`` (through the SIGINT handler that was installed before the
    call) once the library has returned; a run in a thread other than the main one is
    stopped by ``progress`` alone.

    Returns a :class:`ChainResult`. Bad input raises :class:`InputError` with the
    library's account ("gap 2 is negative ..."); CVODE's failure a
    :class:`ComputationError`; a system too large for the memory available an
    :class:`OutOfMemoryError` (also a ``MemoryError``); a library without the CVODE
    component an :class:`UnavailableError`.
    """
    function = _component_function(_FUNCTION, "cvode", "CVODE component (hcimpact_chain_simulate)")
    if progress is not None and not callable(progress):
        raise InputError(_ERR_DOMAIN, f"progress must be a function or None, not {progress!r}",
                         _WHERE)
    watch = Watch(progress)
    m = _vector(masses, "masses")
    n = m.size
    if n == 0:
        raise InputError(_ERR_SIZE, "masses is empty: a system needs at least one body", _WHERE)
    _c_int(n, "the number of bodies", _WHERE)
    v = _vector(velocities, "velocities")
    if v.size != n:
        raise InputError(_ERR_SIZE, f"velocities has {v.size} values for {n} bodies", _WHERE)
    pairs = n - 1
    g = _vector(0.0 if gaps is None else gaps, "gaps", pairs)
    if pairs > 0 and stiffness is None:
        raise InputError(_ERR_DOMAIN, "stiffness is needed for the contacts between "
                         "neighbours (N/m^n; hertz_constant gives it for spheres)", _WHERE)
    laws = (ChainLaw * max(pairs, 1))()
    if pairs > 0:
        columns = np.empty((pairs, 3))
        for j, (value, name) in enumerate(((stiffness, "stiffness"), (exponent, "exponent"),
                                           (damping, "damping"))):
            columns[:, j] = _vector(value, name, pairs)
        ctypes.memmove(laws, np.ascontiguousarray(columns).ctypes.data, columns.nbytes)
    else:
        _law_of_no_pair(((stiffness, "stiffness"), (exponent, "exponent"),
                         (damping, "damping")))
    left, right = _wall(wall_left, "left"), _wall(wall_right, "right")
    options = ChainOptions()
    if t_end is not None:
        options.t_end = _scalar(t_end, "t_end", _WHERE)
        if not options.t_end > 0.0:
            raise InputError(_ERR_DOMAIN, f"t_end = {t_end!r} must be positive (None: until "
                             "no contact can happen again)", _WHERE)
    options.rtol = _scalar(rtol, "rtol", _WHERE)
    if not 0.0 < options.rtol <= 1e-2:   # (0 would mean the default to the C interface)
        raise InputError(_ERR_DOMAIN, f"rtol = {rtol!r} must lie in (0, 0.01]", _WHERE)
    options.method = _choice(method, _METHODS, "method")
    options.integrator = _choice(integrator, _INTEGRATORS, "integrator")
    options.max_steps = _limit(max_steps, "max_steps")
    options.max_events = _limit(max_events, "max_events")
    recorded_limit = None if max_contacts is None else _c_int(max_contacts, "max_contacts",
                                                               _WHERE)
    if recorded_limit is not None and recorded_limit < 0:
        raise InputError(_ERR_SIZE, "max_contacts must not be negative", _WHERE)
    samples, times = None, None
    if sample_times is not None:
        times = _vector(sample_times, "sample_times")
        ns = _c_int(times.size, "the number of sample times", _WHERE)
        shape_x, shape_f = (ns, n), (ns, n + 1)
        sx, sv, sf = np.empty(shape_x), np.empty(shape_x), np.empty(shape_f)
        pd = POINTER(c_double)
        samples = ChainSamples(ns, times.ctypes.data_as(pd), sx.ctypes.data_as(pd),
                               sv.ctypes.data_as(pd), sf.ctypes.data_as(pd))

    def run(capacity: int) -> tuple[int, ChainOutcome, np.ndarray, np.ndarray, np.ndarray, str]:
        outcome = ChainOutcome()
        x, vf = np.empty(n), np.empty(n)
        records = np.empty(max(capacity, 1), dtype=CONTACT_DTYPE)
        message = ctypes.create_string_buffer(_MESSAGE_SIZE)
        pd = POINTER(c_double)
        status = function(n, m.ctypes.data_as(pd), v.ctypes.data_as(pd),
                          g.ctypes.data_as(pd) if pairs > 0 else None,
                          laws if pairs > 0 else None,
                          byref(left) if left is not None else None,
                          byref(right) if right is not None else None,
                          _scalar(gravity, "gravity", _WHERE), byref(options), byref(outcome),
                          x.ctypes.data_as(pd), vf.ctypes.data_as(pd), capacity,
                          records.ctypes.data_as(POINTER(ChainContact)),
                          byref(samples) if samples is not None else None,
                          byref(watch.monitor), message, _MESSAGE_SIZE)
        return status, outcome, x, vf, records, message.value.decode(errors="replace")

    # max_contacts caps the list and is not allocated: the first try has room for
    # _FIRST_CAPACITY + 8 n records, and a run that made more is made again with room
    # for them up to the cap (the run is deterministic)
    cap = _INT_MAX if recorded_limit is None else recorded_limit
    capacity = min(_FIRST_CAPACITY + 8 * n, cap)
    with watch:
        status, outcome, x, vf, records, message = run(capacity)
        if status == 0 and outcome.n_contacts > capacity and capacity < cap:
            watch.again()
            status, outcome, x, vf, records, message = run(int(min(outcome.n_contacts, cap)))
    watch.raise_pending()
    if status != 0:
        _raise(status, _WHERE, detail=message)
    contacts = records[:outcome.contacts_recorded].copy()
    sampled = {}
    if samples is not None:
        sampled = {"sample_times": times, "sample_positions": sx, "sample_velocities": sv,
                   "sample_forces": sf}
    return ChainResult(
        time=outcome.time, positions=x, velocities=vf, contacts=contacts,
        n_contacts=int(outcome.n_contacts), energy_error=outcome.energy_error,
        momentum_error=outcome.momentum_error,
        wall_impulses=(outcome.wall_impulse_left, outcome.wall_impulse_right),
        initial_energy=outcome.initial_energy,
        dissipated=outcome.dissipated, method_used=_METHOD_USED.get(outcome.method_used, "?"),
        rested=bool(outcome.rested),
        rest_time=outcome.rest_time if outcome.rested else math.nan,
        counters={name: int(getattr(outcome, name)) for name in CHAIN_COUNTS[2:]},
        message=message, **sampled)
