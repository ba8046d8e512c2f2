# SPDX-License-Identifier: Apache-2.0
"""The functions of the ``hcimpact`` package: thin wrappers over the C interface.

Conventions (those of ``include/hcimpact.h``):

- Functions that return a number in C return NaN outside their domain here too; they
  accept a scalar (and return a ``float``) or anything array-like (and return a NumPy
  array of the same shape, computed by one call of the C array form).
- Functions that return a status in C raise an :class:`~hcimpact.HcimpactError`
  subclass on an error status: :class:`~hcimpact.InputError` (also a ``ValueError``),
  :class:`~hcimpact.ComputationError`, :class:`~hcimpact.OutOfMemoryError` (also a
  ``MemoryError``), :class:`~hcimpact.UnavailableError`.
- SI units throughout: kg, m, s, N, Pa.
"""

from __future__ import annotations

import ctypes
import math
import operator
from ctypes import POINTER, byref, c_double, c_int
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from . import _library
from ._types import (CONTACT_FIELDS, OUTCOME_FIELDS, Contact, ElasticLaw, ImpactResult,
                     InputError, LawFunction, OutOfMemoryError, Outcome, UnavailableError,
                     error_class)

__all__ = [
    "lambert_w0", "lambert_wm1", "lambert_w0p1", "lambert_wm1p1",
    "restitution", "restitution_inverse", "one_minus_restitution", "energy_loss_ratio",
    "restitution_derivative", "u_minus_log1p", "damping_for_restitution",
    "hertz_constant", "effective_mass", "two_body_velocities",
    "impact", "velocity_at_depth", "time_law", "time_law_samples", "simulate",
    "has_simulate", "FitResult", "fit_damping", "fit_damping_linear", "fit_static",
    "fit_elastic", "fit_impact",
    "status_message", "version", "version_number", "library_path", "array_threads",
    "COMPRESSION", "RESTITUTION", "DEFAULT_MIN_VELOCITY",
]

#: Branch of :func:`velocity_at_depth`: compression (x' >= 0), HCIMPACT_COMPRESSION_BRANCH
COMPRESSION = 1
#: Branch of :func:`velocity_at_depth`: restitution (x' <= 0), HCIMPACT_RESTITUTION_BRANCH
RESTITUTION = 2
#: Default ``min_velocity`` of :func:`damping_for_restitution`, m/s
DEFAULT_MIN_VELOCITY = 1.0e-3

# the C interface counts elements with an int
_CHUNK = 2**30
# bytes for the solver's message (hcimpact_simulate_message); longer ones are cut
_MESSAGE_SIZE = 512
# the range of a C int, which ctypes would wrap silently
_INT_MIN, _INT_MAX = -2**31, 2**31 - 1
# status codes of the checks done here (hcimpact.h)
_ERR_DOMAIN, _ERR_SIZE = 8, 14
_PD = POINTER(c_double)


# ---------------------------------------------------------------------------
# Helpers
# ---------------------------------------------------------------------------

def _lib() -> ctypes.CDLL:
    return _library.load()


def _raise(status: int, function: str, index: Any = None, detail: str = "") -> None:
    """Raise the exception of a status; ``detail`` is the library's account of the
    failure when it gives one (the ODE solver's message), else the status text."""
    kind = error_class(status)
    message = _lib().hcimpact_status_message(status).decode()
    if kind is OutOfMemoryError and detail:
        message = detail    # (it says what did not fit; the status text, what it means)
    elif detail and detail != message:
        message = f"{message}: {detail}"
    raise kind(status, message, function, index)


def _ptr(a: np.ndarray) -> Any:
    return a.ctypes.data_as(_PD)


def _real(x: Any, name: str, function: str) -> np.ndarray:
    """x as float64 (a 0-d array for a scalar): the one conversion of every argument.
    Refused with an InputError naming the argument, where NumPy would change the value
    or raise an exception of its own: complex input (NumPy drops the imaginary part with
    only a warning), a masked array with masked entries (NumPy takes the values under
    the mask), an integer beyond the range of doubles (OverflowError), a ragged list or
    anything else that is not numbers (ValueError, TypeError)."""
    if np.ma.is_masked(x):
        raise InputError(_ERR_DOMAIN, f"{name} has masked entries, whose hidden values "
                         "NumPy would pass on (give the array's .filled(value) or "
                         ".compressed())", function)
    try:
        complex_input = np.iscomplexobj(x)
        if not complex_input:
            return np.asarray(x, dtype=np.float64)
    except OverflowError:
        raise InputError(_ERR_DOMAIN, f"{name} holds an integer beyond the range of doubles "
                         "(about 1.8e308)", function) from None
    except (TypeError, ValueError) as exc:
        raise InputError(_ERR_DOMAIN, f"{name} is not a real number or array: {exc}",
                         function) from None
    raise InputError(_ERR_DOMAIN, f"{name} is complex; hcimpact works on real numbers",
                     function)


def _scalar(x: Any, name: str, function: str) -> float:
    """x as one float; an array is refused with the functions that do take arrays."""
    value = _real(x, name, function)
    if value.ndim != 0:
        raise InputError(_ERR_DOMAIN, f"{name} must be a scalar here (shape {value.shape}); "
                         "impact, time_law and simulate broadcast arrays of contacts",
                         function)
    return float(value)


def _c_int(x: Any, name: str, function: str, status: int = _ERR_SIZE) -> int:
    """An integer argument of the C interface, checked against the range of a C int
    (ctypes would wrap 2**32 + 3 into 3) and refused when it is not an integer."""
    try:
        value = operator.index(x)
    except TypeError:
        raise InputError(status, f"{name} must be an integer, not {x!r}", function) from None
    if not _INT_MIN <= value <= _INT_MAX:
        raise InputError(status, f"{name} = {value} is outside the range of a C int", function)
    return value


def _is_scalar(x: Any) -> bool:
    """Whether x is one value; what NumPy cannot give a shape (a ragged list) is not, and
    _real then says what is wrong with it."""
    try:
        return np.ndim(x) == 0
    except ValueError:
        return False


def _unary(name: str, x: Any) -> Any:
    """f(x) through hcimpact_<name> (scalar) or hcimpact_<name>_array."""
    lib = _lib()
    a = _real(x, "the argument", f"hcimpact_{name}")
    if a.ndim == 0:
        return float(getattr(lib, f"hcimpact_{name}")(float(a)))
    a = np.ascontiguousarray(a)
    out = np.empty_like(a)
    flat_in, flat_out = a.reshape(-1), out.reshape(-1)
    array_form = getattr(lib, f"hcimpact_{name}_array")
    for start in range(0, flat_in.size, _CHUNK):
        n = min(_CHUNK, flat_in.size - start)
        status = array_form(n, _ptr(flat_in[start:]), _ptr(flat_out[start:]))
        if status != 0:
            _raise(status, f"hcimpact_{name}_array")
    return out


def _contact(mass: Any, stiffness: Any, exponent: Any, damping: Any, velocity: Any,
             function: str = "hcimpact_impact") -> Contact:
    """One hcimpact_contact from scalars (an array is refused with a clear message)."""
    values = (mass, stiffness, exponent, damping, velocity)
    return Contact(*[_scalar(v, n, function) for v, n in zip(values, CONTACT_FIELDS)])


def _result(outcome: Outcome) -> ImpactResult:
    return ImpactResult(**{name: float(getattr(outcome, name)) for name in OUTCOME_FIELDS})


# ---------------------------------------------------------------------------
# Lambert W
# ---------------------------------------------------------------------------

def lambert_w0(z: Any) -> Any:
    """Principal branch W0(z) of the Lambert W function, z >= -1/e; NaN outside.

    Accurate to the last bit, also next to the branch point (doc/lambertw.md). The
    double nearest to -1/e and those just below it (down to -1/e - 2**-54) give -1.
    """
    return _unary("lambert_w0", z)


def lambert_wm1(z: Any) -> Any:
    """Lower branch W-1(z), -1/e <= z < 0; -inf for z = +0.0 or -0.0, NaN otherwise outside."""
    return _unary("lambert_wm1", z)


def lambert_w0p1(t: Any) -> Any:
    """1 + W0(-exp(-1 - t)) for t >= 0, computed from t without cancellation.

    In [0, 1); sqrt(2t) - 2t/3 + ... for small t. NaN for t < 0 or NaN, 1 at +inf.
    """
    return _unary("lambert_w0p1", t)


def lambert_wm1p1(t: Any) -> Any:
    """1 + W-1(-exp(-1 - t)) for t >= 0, computed from t without cancellation.

    In (-inf, 0]; -sqrt(2t) - 2t/3 - ... for small t. NaN for t < 0, -inf at +inf.
    """
    return _unary("lambert_wm1p1", t)


# ---------------------------------------------------------------------------
# Restitution
# ---------------------------------------------------------------------------

def restitution(beta: Any) -> Any:
    """Coefficient of restitution k(beta) for beta = b V >= 0 (seed eq. 21).

    Depends on beta alone, for any elastic law and mass. k(0) = 1, k ~ 1/beta for large
    beta; within 2 ulp. NaN for beta < 0 or NaN.
    """
    return _unary("restitution", beta)


def restitution_inverse(e: Any) -> Any:
    """The exact inverse: beta >= 0 with k(beta) = e, for 0 < e <= 1 (then b = beta/V).

    beta(1) = 0, beta(0.5) = 1.4327505332713750; +inf for e below 1/DBL_MAX; NaN for e
    outside (0, 1].
    """
    return _unary("restitution_inverse", e)


def one_minus_restitution(beta: Any) -> Any:
    """1 - k(beta), accurate also where k is close to 1 (2 beta/3 for small beta)."""
    return _unary("one_minus_restitution", beta)


def energy_loss_ratio(beta: Any) -> Any:
    """Share of the kinetic energy lost in the impact, 1 - k(beta)**2."""
    return _unary("energy_loss_ratio", beta)


def restitution_derivative(beta: Any) -> Any:
    """Sensitivity dk/dbeta (negative, -2/3 at 0). dk/db = V dk/dbeta, dk/dV = b dk/dbeta."""
    return _unary("restitution_derivative", beta)


def u_minus_log1p(u: Any) -> Any:
    """h(u) = u - ln(1 + u) for u > -1 (the first integral, MODEL.md); NaN for u < -1."""
    function = _lib().hcimpact_u_minus_log1p
    a = _real(u, "u", "hcimpact_u_minus_log1p")
    if a.ndim == 0:
        return float(function(float(a)))
    return np.array([function(float(v)) for v in a.reshape(-1)]).reshape(a.shape)


def damping_for_restitution(e: Any, velocity: Any,
                            min_velocity: Any = DEFAULT_MIN_VELOCITY) -> Any:
    """Damping b (s/m) that gives the restitution e at the approach speed ``velocity``.

    b = beta(e)/max(velocity, min_velocity): below ``min_velocity`` (m/s) b is that of
    min_velocity, so that it stays finite as the speed tends to 0. Scalars give a
    float; arrays (e.g. one target per pair of a :func:`chain`) broadcast together and
    give an array.
    Raises InputError for e outside (0, 1], velocity < 0, min_velocity <= 0, NaN (with
    the ``index`` of the first bad element for arrays).
    """
    where = "hcimpact_damping_for_restitution"
    args = [(e, "e"), (velocity, "velocity"), (min_velocity, "min_velocity")]
    if all(_is_scalar(a) for a, _ in args):
        damping = c_double()
        status = _lib().hcimpact_damping_for_restitution(
            *[_scalar(a, name, where) for a, name in args], byref(damping))
        if status != 0:
            _raise(status, where)
        return damping.value
    arrays = _broadcast([_real(a, name, where) for a, name in args], where)
    out = np.empty(arrays[0].shape)
    for index in np.ndindex(out.shape):
        damping = c_double()
        status = _lib().hcimpact_damping_for_restitution(
            *[float(a[index]) for a in arrays], byref(damping))
        if status != 0:
            _raise(status, where, index if len(index) > 1 else index[0])
        out[index] = damping.value
    return out


# ---------------------------------------------------------------------------
# Two bodies
# ---------------------------------------------------------------------------

def hertz_constant(young1: Any, poisson1: Any, radius1: Any, young2: Any,
                   poisson2: Any, radius2: Any = math.inf) -> Any:
    """Hertz's contact constant c (N/m**1.5) of two elastic spheres.

    1/c = (3/4) ((1 - nu1**2)/E1 + (1 - nu2**2)/E2) sqrt(1/R1 + 1/R2). Young's moduli in
    Pa, radii in m (``math.inf``: a flat body; the default for body 2). NaN outside the
    domain (E > 0, -1 < nu <= 1/2, R > 0, not both flat). Scalars give a float; arrays
    broadcast together and give an array, e.g. the constants of the neighbouring pairs
    of a chain of spheres: ``hertz_constant(E[:-1], nu[:-1], R[:-1], E[1:], nu[1:],
    R[1:])``.
    """
    where = "hcimpact_hertz_constant"
    args = [(young1, "young1"), (poisson1, "poisson1"), (radius1, "radius1"),
            (young2, "young2"), (poisson2, "poisson2"), (radius2, "radius2")]
    function = _lib().hcimpact_hertz_constant
    if all(_is_scalar(a) for a, _ in args):
        return float(function(*[_scalar(a, name, where) for a, name in args]))
    arrays = _broadcast([_real(a, name, where) for a, name in args], where)
    out = np.empty(arrays[0].shape)
    for index in np.ndindex(out.shape):
        out[index] = function(*[float(a[index]) for a in arrays])
    return out


def effective_mass(mass1: float, mass2: float = math.inf) -> float:
    """Effective mass m1 m2/(m1 + m2) in kg (mass2 = inf: an immovable obstacle).

    NaN unless mass1 > 0 is finite and mass2 > 0.
    """
    where = "hcimpact_effective_mass"
    return float(_lib().hcimpact_effective_mass(_scalar(mass1, "mass1", where),
                                                _scalar(mass2, "mass2", where)))


def two_body_velocities(mass1: float, mass2: float, velocity1: float, velocity2: float,
                        restitution: float) -> tuple[float, float]:
    """Velocities (m/s) of both bodies after a collinear impact with restitution k.

    Body 1 moves along +x towards body 2 (velocity1 > velocity2); momentum is conserved
    and the relative velocity becomes -k (velocity1 - velocity2). Returns
    (velocity1_after, velocity2_after). Raises InputError for bad arguments.
    """
    v1, v2 = c_double(), c_double()
    where = "hcimpact_two_body_velocities"
    status = _lib().hcimpact_two_body_velocities(
        *[_scalar(v, n, where) for v, n in ((mass1, "mass1"), (mass2, "mass2"),
                                            (velocity1, "velocity1"), (velocity2, "velocity2"),
                                            (restitution, "restitution"))],
        byref(v1), byref(v2))
    if status != 0:
        _raise(status, "hcimpact_two_body_velocities")
    return v1.value, v2.value


# ---------------------------------------------------------------------------
# One impact
# ---------------------------------------------------------------------------

def impact(*, mass: Any, stiffness: Any, exponent: Any = 1.5, damping: Any = 0.0,
           velocity: Any, errors: str = "raise") -> ImpactResult:
    """One impact m x'' = -c x**n (1 + b x'), x(0) = 0, x'(0) = V, in closed form.

    Parameters (SI units; scalars, or arrays that broadcast together):

    - ``mass`` m in kg (the effective mass for two bodies), > 0
    - ``stiffness`` c in N/m**n, > 0 (:func:`hertz_constant` for spheres)
    - ``exponent`` n, > 0 (1.5: Hertz, the default)
    - ``damping`` b in s/m, >= 0 (0: elastic, the default)
    - ``velocity`` V in m/s, > 0
    - ``errors``: ``"raise"`` (an InputError or ComputationError for the first impact
      that fails, with its ``index``) or ``"nan"`` (failed impacts get NaN fields)

    Returns an :class:`ImpactResult` (restitution, energy_loss_ratio, rebound_velocity,
    max_compression, peak_force, compression_at_peak_force, time_at_peak_force,
    compression_time,
    contact_time): floats for scalar input, arrays of the broadcast shape otherwise.
    """
    if errors not in ("raise", "nan"):
        raise ValueError(f"errors must be 'raise' or 'nan', not {errors!r}")
    lib = _lib()
    args = (mass, stiffness, exponent, damping, velocity)
    if all(_is_scalar(a) for a in args):
        outcome = Outcome()
        status = lib.hcimpact_impact(byref(_contact(*args)), byref(outcome))
        if status != 0 and errors == "raise":
            _raise(status, "hcimpact_impact")
        return _result(outcome)
    arrays = _broadcast([_real(a, n, "hcimpact_impact_array")
                         for a, n in zip(args, CONTACT_FIELDS)], "hcimpact_impact_array")
    shape = arrays[0].shape
    n = int(np.prod(shape, dtype=np.int64))
    contacts = np.empty((n, len(CONTACT_FIELDS)), dtype=np.float64)
    for j, a in enumerate(arrays):
        contacts[:, j] = a.reshape(-1)
    outcomes = np.empty((n, len(OUTCOME_FIELDS)), dtype=np.float64)
    statuses = np.zeros(n, dtype=np.intc)
    for start in range(0, n, _CHUNK):
        m = min(_CHUNK, n - start)
        lib.hcimpact_impact_array(
            m, contacts[start:].ctypes.data_as(POINTER(Contact)),
            outcomes[start:].ctypes.data_as(POINTER(Outcome)),
            statuses[start:].ctypes.data_as(POINTER(c_int)))
    if errors == "raise" and n > 0 and np.any(statuses != 0):
        first = int(np.flatnonzero(statuses)[0])
        index = np.unravel_index(first, shape) if len(shape) > 1 else first
        _raise(int(statuses[first]), "hcimpact_impact_array", index)
    return ImpactResult(**{name: outcomes[:, j].reshape(shape)
                           for j, name in enumerate(OUTCOME_FIELDS)})


def _branch(branch: Any) -> int:
    """The branch code from its name or from the integer COMPRESSION / RESTITUTION; a
    float or a bool is refused (1.0 == 1 and True == 1 would otherwise pass)."""
    names = {"compression": COMPRESSION, "restitution": RESTITUTION}
    if isinstance(branch, str) and branch in names:
        return names[branch]
    if (isinstance(branch, (int, np.integer)) and not isinstance(branch, (bool, np.bool_))
            and int(branch) in (COMPRESSION, RESTITUTION)):
        return int(branch)
    raise InputError(_ERR_DOMAIN, "branch must be 'compression' or 'restitution' (or "
                     f"hcimpact.COMPRESSION, hcimpact.RESTITUTION), not {branch!r}",
                     "hcimpact_velocity_at_depth")


def impact_law(force: Callable[[float], float], potential: Callable[[float], float],
               force_derivative: Callable[[float], float], *, mass: float,
               damping: float = 0.0, velocity: float) -> ImpactResult:
    """One impact with your own elastic law, in closed form (``hcimpact_impact_law``).

    ``force(x)`` is f(x) in N (increasing, f(0) = 0), ``potential(x)`` its integral
    from 0 to x in J, ``force_derivative(x)`` f'(x) in N/m, for a compression x >= 0
    in m; ``mass`` in kg, ``damping`` b in s/m, ``velocity`` V in m/s (scalars).
    The functions are called many times and must not change what they read. An
    exception raised inside one of them (any, SystemExit and KeyboardInterrupt too)
    stops the computation: the library gets NaN for that call and for every later one,
    gives up, and the exception is raised again here, with its traceback. A function
    that returns a value that is not finite is an invalid law (HCIMPACT_ERR_ELASTIC_LAW,
    an :class:`InputError`).

    >>> c = 1.7135e10
    >>> r = impact_law(lambda x: c * x**1.5, lambda x: c * x**2.5 / 2.5,
    ...                lambda x: 1.5 * c * x**0.5, mass=0.1, damping=0.1, velocity=2.0)
    """
    where = "hcimpact_impact_law"
    # the first exception of any callback; none of them is called again after it
    raised: list[BaseException] = []

    def wrap(function: Callable[[float], float]) -> Any:
        def callback(x: float, data: Any) -> float:
            if raised:
                return math.nan
            try:
                return float(function(x))
            except BaseException as exc:    # never let an exception cross the C boundary
                raised.append(exc)
                return math.nan
        return LawFunction(callback)

    callbacks = [wrap(force), wrap(potential), wrap(force_derivative)]
    law = ElasticLaw(callbacks[0], callbacks[1], callbacks[2], None)
    outcome = Outcome()
    status = _lib().hcimpact_impact_law(byref(law), _scalar(mass, "mass", where),
                                        _scalar(damping, "damping", where),
                                        _scalar(velocity, "velocity", where), byref(outcome))
    if raised:
        raise raised[0]
    if status != 0:
        _raise(status, where)
    return _result(outcome)


def velocity_at_depth(x: Any, *, mass: float, stiffness: float, exponent: float = 1.5,
                      damping: float = 0.0, velocity: float,
                      branch: Any = "compression") -> Any:
    """Velocity x' (m/s) at the compression x (m, 0 <= x <= x_max): the phase curve.

    ``branch`` is ``"compression"`` (x' >= 0) or ``"restitution"`` (x' <= 0), or the
    integer :data:`COMPRESSION` / :data:`RESTITUTION`. x may be an array (one call of
    the C array form). Raises InputError for x outside [0, x_max], a bad contact or a
    bad branch.
    """
    lib = _lib()
    where = "hcimpact_velocity_at_depth"
    contact = _contact(mass, stiffness, exponent, damping, velocity, where)
    code = _branch(branch)
    a = _real(x, "x", where)
    if a.ndim == 0:
        v = c_double()
        status = lib.hcimpact_velocity_at_depth(byref(contact), float(a), code, byref(v))
        if status != 0:
            _raise(status, where)
        return v.value
    a = np.ascontiguousarray(a)
    out = np.empty_like(a)
    if a.size:
        n = _c_int(a.size, "the size of x", where + "_array")
        status = lib.hcimpact_velocity_at_depth_array(byref(contact), n, _ptr(a), code,
                                                      _ptr(out))
        if status != 0:
            _raise(status, where + "_array")
    return out


def _broadcast(arrays: list[np.ndarray], function: str) -> list[np.ndarray]:
    """np.broadcast_arrays, with an InputError that names the shapes when they do not
    broadcast."""
    try:
        return np.broadcast_arrays(*arrays)
    except ValueError:
        shapes = ", ".join(str(a.shape) for a in arrays)
        raise InputError(_ERR_SIZE, f"the arguments' shapes {shapes} do not broadcast "
                         "together", function) from None


def _contact_rows(args: tuple, extra: list[tuple[Any, str]], function: str
                  ) -> tuple[tuple[int, ...], np.ndarray, list[np.ndarray]]:
    """The contact arguments and ``extra`` (value, name) arrays broadcast together:
    (shape, contacts as an (N, 5) array, the extra arrays flattened)."""
    reals = [_real(a, n, function) for a, n in zip(args, CONTACT_FIELDS)]
    reals += [_real(v, n, function) for v, n in extra]
    arrays = _broadcast(reals, function)
    shape = arrays[0].shape
    contacts = np.stack([a.reshape(-1) for a in arrays[:len(CONTACT_FIELDS)]], axis=1)
    return shape, np.ascontiguousarray(contacts), [a.reshape(-1) for a in
                                                   arrays[len(CONTACT_FIELDS):]]


def time_law(t: Any, *, mass: Any, stiffness: Any, exponent: Any = 1.5, damping: Any = 0.0,
             velocity: Any) -> tuple[Any, Any, Any]:
    """Compression x(t) (m), velocity x'(t) (m/s) and force F(t) (N) at the times t (s).

    t counts from the start of contact, in any order; before it x = 0, x' = V, F = 0,
    after it x = 0, x' = -k V, F = 0. The contact's arguments may be arrays too: t and
    they broadcast together (NumPy's rules), and element i is the time law of contact i
    at time t[i] (one C call per distinct contact). Returns (x, v, f) of the broadcast
    shape (floats when everything is scalar). Raises InputError for a bad contact (with
    the element's ``index``) or shapes that do not broadcast, OutOfMemoryError when the
    library cannot hold its copies of the times.
    """
    lib = _lib()
    where = "hcimpact_time_law"
    args = (mass, stiffness, exponent, damping, velocity)
    if all(_is_scalar(a) for a in args):
        # one contact, all the times in one call on the arrays themselves: no rows of
        # contacts to sort (five copies of t and more), so that a t too large for the
        # memory fails in the library, an OutOfMemoryError, rather than in NumPy
        t_real = _real(t, "t", where)
        shape, times = t_real.shape, np.ascontiguousarray(t_real).reshape(-1)
        groups = [(_contact(*args, function=where), None)]
    else:
        shape, contacts, (times,) = _contact_rows(args, [(t, "t")], where)
        # the distinct contacts, each with all its times in one call
        unique, inverse = np.unique(contacts, axis=0, return_inverse=True)
        inverse = np.asarray(inverse).reshape(-1)
        groups = [(Contact(*[float(c) for c in unique[row]]), np.flatnonzero(inverse == row))
                  for row in range(unique.shape[0])]
    x, v, f = (np.empty(times.size) for _ in range(3))
    for contact, members in groups:
        if members is None:
            ts, xs, vs, fs = times, x, v, f
        else:
            ts = np.ascontiguousarray(times[members])
            xs, vs, fs = np.empty_like(ts), np.empty_like(ts), np.empty_like(ts)
        if ts.size == 0:
            continue
        n = _c_int(ts.size, "the number of times", where)
        status = lib.hcimpact_time_law(byref(contact), n, _ptr(ts), _ptr(xs), _ptr(vs),
                                       _ptr(fs))
        if status != 0:
            first = 0 if members is None else int(members[0])
            index = np.unravel_index(first, shape) if len(shape) > 1 else first
            _raise(status, where, index if shape else None)
        if members is not None:
            x[members], v[members], f[members] = xs, vs, fs
    if not shape:
        return float(x[0]), float(v[0]), float(f[0])
    return x.reshape(shape), v.reshape(shape), f.reshape(shape)


def time_law_samples(n: int, *, mass: float, stiffness: float, exponent: float = 1.5,
                     damping: float = 0.0, velocity: float) -> tuple[Any, Any, Any, Any]:
    """The time law on n >= 2 equally spaced times from 0 to the contact time.

    One contact (scalars). Returns (t, x, v, f), arrays of n elements (s, m, m/s, N).
    Raises OutOfMemoryError when the library cannot hold the n samples.
    """
    lib = _lib()
    where = "hcimpact_time_law_samples"
    contact = _contact(mass, stiffness, exponent, damping, velocity, where)
    n = _c_int(n, "n", where)
    if n < 2:
        _raise(_ERR_SIZE, where)
    arrays = [np.empty(n, dtype=np.float64) for _ in range(4)]
    status = lib.hcimpact_time_law_samples(byref(contact), n, *[_ptr(a) for a in arrays])
    if status != 0:
        _raise(status, where)
    return tuple(arrays)


# ---------------------------------------------------------------------------
# Components
# ---------------------------------------------------------------------------

#: What each component needs, for the message when it is missing
_COMPONENT_NEEDS = {
    "cvode": "SUNDIALS CVODE with its Fortran modules (Debian: libsundials-dev "
             "libsundials-fortran-dev)",
    "lapack": "LAPACK (Debian: liblapack-dev)",
}


def _component_function(function: str, component: str, what: str) -> Any:
    stem = f"hcimpact_{component}"
    lib = _library.component(function, stem)
    if lib is None:
        built = _library.build_info().get("components", {}).get(component)
        if built is not None and not built.get("built", False):
            why = (f"this hcimpact was built without it: component {component} "
                   f"{built.get('status', 'OFF')}. Install {_COMPONENT_NEEDS[component]} "
                   "and reinstall hcimpact (pip install ./python)")
        else:
            why = (f"lib{stem} was not found next to {_library.library_path()}; build "
                   f"hcimpact with {_COMPONENT_NEEDS[component]} present "
                   f"(HCIMPACT_WITH_{component.upper()}=ON)")
        raise UnavailableError(12, f"the {what} is not available: {why}", function)
    return getattr(lib, function)


def has_simulate() -> bool:
    """True when the library has the CVODE component (:func:`simulate` works)."""
    return _library.component("hcimpact_simulate", "hcimpact_cvode") is not None


def simulate(*, mass: Any, stiffness: Any, exponent: Any = 1.5, damping: Any = 0.0,
             velocity: Any, rtol: Any = 1.0e-10, errors: str = "raise") -> ImpactResult:
    """The impact integrated by SUNDIALS CVODE with the relative tolerance ``rtol``.

    Same arguments and result as :func:`impact` (to about rtol): scalars, or arrays
    (``rtol`` too) that broadcast together, one integration per element. Needs the CVODE
    component (``libhcimpact_cvode``); without it raises :class:`UnavailableError`
    naming what is missing. When CVODE fails, the :class:`ComputationError` carries its
    flag name and message (``hcimpact_simulate_message``), e.g. ``CV_TOO_MUCH_ACC``.
    ``errors="nan"`` gives NaN fields for the elements that fail instead of raising.
    """
    if errors not in ("raise", "nan"):
        raise ValueError(f"errors must be 'raise' or 'nan', not {errors!r}")
    where = "hcimpact_simulate"
    function = _component_function("hcimpact_simulate_message", "cvode",
                                    "CVODE component (hcimpact_simulate)")
    args = (mass, stiffness, exponent, damping, velocity)
    shape, contacts, (tolerances,) = _contact_rows(args, [(rtol, "rtol")], where)
    outcomes = np.empty((tolerances.size, len(OUTCOME_FIELDS)), dtype=np.float64)
    message = ctypes.create_string_buffer(_MESSAGE_SIZE)
    outcome = Outcome()
    for i in range(tolerances.size):
        contact = Contact(*[float(c) for c in contacts[i]])
        status = function(byref(contact), float(tolerances[i]), byref(outcome), message,
                          _MESSAGE_SIZE)
        if status != 0 and errors == "raise":
            index = (np.unravel_index(i, shape) if len(shape) > 1 else i) if shape else None
            _raise(status, where, index, detail=message.value.decode(errors="replace"))
        outcomes[i] = [getattr(outcome, name) for name in OUTCOME_FIELDS]
    if not shape:
        return ImpactResult(**{name: float(outcomes[0, j])
                               for j, name in enumerate(OUTCOME_FIELDS)})
    return ImpactResult(**{name: outcomes[:, j].reshape(shape)
                           for j, name in enumerate(OUTCOME_FIELDS)})


@dataclass(frozen=True, repr=False)
class FitResult:
    """Result of a calibration fit (LAPACK component).

    ``parameters``: the fitted values (a dict, SI units); ``covariance``: their
    covariance matrix (in the order of ``parameters``); ``residuals``: as documented
    for each fit (include/hcimpact_lapack.h); ``data``: the observations fitted (a dict
    of arrays: ``velocity`` or ``deflection`` and the series given), which
    :func:`hcimpact.plot.plot_fit` draws against the fitted model; ``kind``: the fit
    (``"damping"``, ``"damping_linear"``, ``"static"``, ``"elastic"``, ``"impact"``);
    ``fixed``: the known values the fit used (``mass``, ``damping``).
    """

    parameters: dict
    covariance: np.ndarray
    residuals: np.ndarray
    data: dict = field(default_factory=dict)
    kind: str = ""
    fixed: dict = field(default_factory=dict)

    @property
    def standard_errors(self) -> dict:
        """Square roots of the covariance diagonal, by parameter name."""
        return {name: float(math.sqrt(self.covariance[i, i]))
                for i, name in enumerate(self.parameters)}

    def __repr__(self) -> str:
        errors = self.standard_errors
        values = ", ".join(f"{name}={value:.6g} ± {errors[name]:.2g}"
                           for name, value in self.parameters.items())
        rms = float(np.sqrt(np.mean(self.residuals**2))) if self.residuals.size else 0.0
        kind = f"{self.kind}: " if self.kind else ""
        return (f"FitResult({kind}{values}; {self.residuals.size} residuals, "
                f"rms {rms:.3g})")


def _data(x: Any, n: int | None = None, name: str = "data") -> np.ndarray:
    a = np.ascontiguousarray(_real(x, name, "hcimpact_fit").reshape(-1))
    if n is not None and a.size != n:
        raise InputError(_ERR_SIZE, f"{name} has {a.size} values, expected {n}",
                         "hcimpact_fit")
    _c_int(a.size, f"the size of {name}", "hcimpact_fit")
    return a


def _optional(x: Any, n: int, name: str) -> tuple[Any, Any]:
    if x is None:
        return None, None
    a = _data(x, n, name)
    return a, _ptr(a)


def _fit_damping(function_name: str, velocity: Any, restitution: Any, sigma: Any,
                 absolute_sigma: bool) -> FitResult:
    function = _component_function(function_name, "lapack",
                                   "LAPACK component (calibration)")
    v = _data(velocity)
    e = _data(restitution, v.size, "restitution")
    _, sigma_ptr = _optional(sigma, v.size, "sigma")
    damping, error = c_double(), c_double()
    residuals = np.empty(v.size)
    status = function(v.size, _ptr(v), _ptr(e), sigma_ptr, int(bool(absolute_sigma)),
                      byref(damping), byref(error), _ptr(residuals))
    if status != 0:
        _raise(status, function_name)
    kind = "damping_linear" if function_name.endswith("linear") else "damping"
    return FitResult({"damping": damping.value}, np.array([[error.value**2]]), residuals,
                     data={"velocity": v, "restitution": e}, kind=kind)


def fit_damping(velocity: Any, restitution: Any, sigma: Any = None,
                absolute_sigma: bool = False) -> FitResult:
    """Damping b (s/m) from restitution measured at approach speeds, exact law e = k(b V).

    Residuals e_i - k(b V_i). Needs the LAPACK component.
    """
    return _fit_damping("hcimpact_fit_damping", velocity, restitution, sigma, absolute_sigma)


def fit_damping_linear(velocity: Any, restitution: Any, sigma: Any = None,
                       absolute_sigma: bool = False) -> FitResult:
    """The linear law e = 1 - alpha V, as b = 3 alpha/2 (s/m), for comparison.

    Residuals e_i - (1 - alpha V_i). Needs the LAPACK component.
    """
    return _fit_damping("hcimpact_fit_damping_linear", velocity, restitution, sigma,
                        absolute_sigma)


def fit_static(deflection: Any, force: Any, sigma: Any = None,
               absolute_sigma: bool = False) -> FitResult:
    """Elastic law F = c x**n from a static force-deflection curve (c in N/m**n, n).

    Residuals ln F_i - ln(c x_i**n). Needs the LAPACK component.
    """
    function = _component_function("hcimpact_fit_static", "lapack",
                                   "LAPACK component (calibration)")
    x = _data(deflection)
    f = _data(force, x.size, "force")
    _, sigma_ptr = _optional(sigma, x.size, "sigma")
    parameters, covariance, residuals = np.empty(2), np.empty((2, 2)), np.empty(x.size)
    status = function(x.size, _ptr(x), _ptr(f), sigma_ptr, int(bool(absolute_sigma)),
                      _ptr(parameters), _ptr(covariance), _ptr(residuals))
    if status != 0:
        _raise(status, "hcimpact_fit_static")
    return FitResult({"stiffness": float(parameters[0]), "exponent": float(parameters[1])},
                     covariance, residuals, data={"deflection": x, "force": f},
                     kind="static")


def fit_elastic(velocity: Any, *, mass: float, damping: float, contact_time: Any = None,
                peak_force: Any = None, sigma_time: Any = None, sigma_force: Any = None,
                absolute_sigma: bool = False, guess: Any = None) -> FitResult:
    """Elastic law (c, n) from contact times and/or peak forces at the speeds ``velocity``,
    the damping b known. Residuals ln(observed/model), time series first.
    Needs the LAPACK component.
    """
    function = _component_function("hcimpact_fit_elastic", "lapack",
                                   "LAPACK component (calibration)")
    v = _data(velocity)
    series = [contact_time, peak_force]
    names = ["contact_time", "peak_force", "sigma_time", "sigma_force"]
    pairs = [_optional(s, v.size, name)
             for s, name in zip(series + [sigma_time, sigma_force], names)]
    _, guess_ptr = _optional(guess, 2, "guess")
    parameters, covariance = np.empty(2), np.empty((2, 2))
    count = v.size * sum(s is not None for s in series)
    residuals = np.empty(max(count, 1))
    mass_value = _scalar(mass, "mass", "hcimpact_fit_elastic")
    damping_value = _scalar(damping, "damping", "hcimpact_fit_elastic")
    status = function(v.size, mass_value, damping_value, _ptr(v), *[p for _, p in pairs],
                      int(bool(absolute_sigma)), guess_ptr, _ptr(parameters),
                      _ptr(covariance), _ptr(residuals))
    if status != 0:
        _raise(status, "hcimpact_fit_elastic")
    data = {"velocity": v}
    data.update({name: a for (a, _), name in zip(pairs[:2], names[:2]) if a is not None})
    return FitResult({"stiffness": float(parameters[0]), "exponent": float(parameters[1])},
                     covariance, residuals[:count], data=data, kind="elastic",
                     fixed={"mass": mass_value, "damping": damping_value})


def fit_impact(velocity: Any, *, mass: float, contact_time: Any = None,
               peak_force: Any = None, restitution: Any = None, sigma_time: Any = None,
               sigma_force: Any = None, sigma_restitution: Any = None,
               absolute_sigma: bool = False, guess: Any = None) -> FitResult:
    """Joint fit of (c, n, b) to contact times, peak forces and restitution measured at
    the speeds ``velocity``. Residuals per series given (time, force, restitution).
    Needs the LAPACK component.
    """
    function = _component_function("hcimpact_fit_impact", "lapack",
                                   "LAPACK component (calibration)")
    v = _data(velocity)
    series = [contact_time, peak_force, restitution]
    everything = series + [sigma_time, sigma_force, sigma_restitution]
    names = ["contact_time", "peak_force", "restitution", "sigma_time", "sigma_force",
             "sigma_restitution"]
    pairs = [_optional(s, v.size, name) for s, name in zip(everything, names)]
    _, guess_ptr = _optional(guess, 3, "guess")
    parameters, covariance = np.empty(3), np.empty((3, 3))
    count = v.size * sum(s is not None for s in series)
    residuals = np.empty(max(count, 1))
    mass_value = _scalar(mass, "mass", "hcimpact_fit_impact")
    status = function(v.size, mass_value, _ptr(v), *[p for _, p in pairs],
                      int(bool(absolute_sigma)), guess_ptr, _ptr(parameters),
                      _ptr(covariance), _ptr(residuals))
    if status != 0:
        _raise(status, "hcimpact_fit_impact")
    data = {"velocity": v}
    data.update({name: a for (a, _), name in zip(pairs[:3], names[:3]) if a is not None})
    return FitResult({"stiffness": float(parameters[0]), "exponent": float(parameters[1]),
                      "damping": float(parameters[2])}, covariance, residuals[:count],
                     data=data, kind="impact", fixed={"mass": mass_value})


# ---------------------------------------------------------------------------
# Library
# ---------------------------------------------------------------------------

def status_message(status: int) -> str:
    """The library's text for a status code ("unknown status code" for others, also
    for integers beyond a C int, which ctypes would otherwise wrap into a real code)."""
    code = operator.index(status)
    if not _INT_MIN <= code <= _INT_MAX:
        code = _INT_MIN        # not a status: the library's text for unknown codes
    return _lib().hcimpact_status_message(code).decode()


def version() -> str:
    """Version of the loaded library, "major.minor.patch"."""
    return _lib().hcimpact_version().decode()


def version_number() -> int:
    """Version of the loaded library as 10000 major + 100 minor + patch."""
    return int(_lib().hcimpact_version_number())


def array_threads() -> int:
    """Threads the library shares a large array call among (OpenMP's OMP_NUM_THREADS
    as read when the library was loaded; 1 in a library built without OpenMP). The
    results are the same bit for bit whatever the number."""
    return int(_lib().hcimpact_array_threads())


def library_path() -> str:
    """Path of the shared library in use."""
    return _library.library_path()
