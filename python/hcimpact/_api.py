# SPDX-License-Identifier: Apache-2.0
"""The functions of the ``hcimpact`` package: thin wrappers over the C interface.

Conventions (those of ``include/hcimpact.h``):

- Functions that return a number in C return NaN outside their domain here too; they
  accept a scalar (and return a ``float``) or anything array-like (and return a NumPy
  array of the same shape, computed by one call of the C array form).
- Functions that return a status in C raise an :class:`~hcimpact.HcimpactError`
  subclass on an error status: :class:`~hcimpact.InputError` (also a ``ValueError``),
  :class:`~hcimpact.ComputationError`, :class:`~hcimpact.UnavailableError`.
- SI units throughout: kg, m, s, N, Pa.
"""

from __future__ import annotations

import ctypes
import math
from ctypes import POINTER, byref, c_double, c_int
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from . import _library
from ._types import (OUTCOME_FIELDS, Contact, ElasticLaw, ImpactResult, LawFunction,
                     Outcome, UnavailableError,
                     error_class)

__all__ = [
    "lambert_w0", "lambert_wm1", "lambert_w0p1", "lambert_wm1p1",
    "restitution", "restitution_inverse", "one_minus_restitution", "energy_loss_ratio",
    "restitution_derivative", "u_minus_log1p", "damping_for_restitution",
    "hertz_constant", "effective_mass", "two_body_velocities",
    "impact", "velocity_at_depth", "time_law", "time_law_samples", "simulate",
    "has_simulate", "FitResult", "fit_damping", "fit_damping_linear", "fit_static",
    "fit_elastic", "fit_impact",
    "status_message", "version", "version_number", "library_path",
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
_PD = POINTER(c_double)


# ---------------------------------------------------------------------------
# Helpers
# ---------------------------------------------------------------------------

def _lib() -> ctypes.CDLL:
    return _library.load()


def _raise(status: int, function: str, index: Any = None) -> None:
    message = _lib().hcimpact_status_message(status).decode()
    raise error_class(status)(status, message, function, index)


def _ptr(a: np.ndarray) -> Any:
    return a.ctypes.data_as(_PD)


def _is_scalar(x: Any) -> bool:
    return np.ndim(x) == 0


def _unary(name: str, x: Any) -> Any:
    """f(x) through hcimpact_<name> (scalar) or hcimpact_<name>_array."""
    lib = _lib()
    if _is_scalar(x):
        return float(getattr(lib, f"hcimpact_{name}")(float(x)))
    a = np.ascontiguousarray(x, dtype=np.float64)
    out = np.empty_like(a)
    flat_in, flat_out = a.reshape(-1), out.reshape(-1)
    array_form = getattr(lib, f"hcimpact_{name}_array")
    for start in range(0, flat_in.size, _CHUNK):
        n = min(_CHUNK, flat_in.size - start)
        status = array_form(n, _ptr(flat_in[start:]), _ptr(flat_out[start:]))
        if status != 0:
            _raise(status, f"hcimpact_{name}_array")
    return out


def _contact(mass: float, stiffness: float, exponent: float, damping: float,
             velocity: float) -> Contact:
    return Contact(float(mass), float(stiffness), float(exponent), float(damping),
                   float(velocity))


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
    if _is_scalar(u):
        return float(function(float(u)))
    a = np.asarray(u, dtype=np.float64)
    return np.array([function(float(v)) for v in a.reshape(-1)]).reshape(a.shape)


def damping_for_restitution(e: float, velocity: float,
                            min_velocity: float = DEFAULT_MIN_VELOCITY) -> float:
    """Damping b (s/m) that gives the restitution e at the approach speed ``velocity``.

    b = beta(e)/max(velocity, min_velocity): below ``min_velocity`` (m/s) b is that of
    min_velocity, so that it stays finite as the speed tends to 0.
    Raises InputError for e outside (0, 1], velocity < 0, min_velocity <= 0, NaN.
    """
    damping = c_double()
    status = _lib().hcimpact_damping_for_restitution(float(e), float(velocity),
                                                     float(min_velocity), byref(damping))
    if status != 0:
        _raise(status, "hcimpact_damping_for_restitution")
    return damping.value


# ---------------------------------------------------------------------------
# Two bodies
# ---------------------------------------------------------------------------

def hertz_constant(young1: float, poisson1: float, radius1: float, young2: float,
                   poisson2: float, radius2: float = math.inf) -> float:
    """Hertz's contact constant c (N/m**1.5) of two elastic spheres.

    1/c = (3/4) ((1 - nu1**2)/E1 + (1 - nu2**2)/E2) sqrt(1/R1 + 1/R2). Young's moduli in
    Pa, radii in m (``math.inf``: a flat body; the default for body 2). NaN outside the
    domain (E > 0, -1 < nu <= 1/2, R > 0, not both flat).
    """
    return float(_lib().hcimpact_hertz_constant(float(young1), float(poisson1),
                                                 float(radius1), float(young2),
                                                 float(poisson2), float(radius2)))


def effective_mass(mass1: float, mass2: float = math.inf) -> float:
    """Effective mass m1 m2/(m1 + m2) in kg (mass2 = inf: an immovable obstacle).

    NaN unless mass1 > 0 is finite and mass2 > 0.
    """
    return float(_lib().hcimpact_effective_mass(float(mass1), float(mass2)))


def two_body_velocities(mass1: float, mass2: float, velocity1: float, velocity2: float,
                        restitution: float) -> tuple[float, float]:
    """Velocities (m/s) of both bodies after a collinear impact with restitution k.

    Body 1 moves along +x towards body 2 (velocity1 > velocity2); momentum is conserved
    and the relative velocity becomes -k (velocity1 - velocity2). Returns
    (velocity1_after, velocity2_after). Raises InputError for bad arguments.
    """
    v1, v2 = c_double(), c_double()
    status = _lib().hcimpact_two_body_velocities(float(mass1), float(mass2),
                                                 float(velocity1), float(velocity2),
                                                 float(restitution), byref(v1), byref(v2))
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
    max_compression, peak_force, compression_at_peak_force, compression_time,
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
    arrays = np.broadcast_arrays(*[np.asarray(a, dtype=np.float64) for a in args])
    shape = arrays[0].shape
    n = int(np.prod(shape, dtype=np.int64))
    contacts = np.empty((n, 5), dtype=np.float64)
    for j, a in enumerate(arrays):
        contacts[:, j] = a.reshape(-1)
    outcomes = np.empty((n, 8), dtype=np.float64)
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
    if branch in (COMPRESSION, "compression"):
        return COMPRESSION
    if branch in (RESTITUTION, "restitution"):
        return RESTITUTION
    raise ValueError(f"branch must be 'compression' or 'restitution', not {branch!r}")


def impact_law(force: Callable[[float], float], potential: Callable[[float], float],
               force_derivative: Callable[[float], float], *, mass: float,
               damping: float = 0.0, velocity: float) -> ImpactResult:
    """One impact with your own elastic law, in closed form (``hcimpact_impact_law``).

    ``force(x)`` is f(x) in N (increasing, f(0) = 0), ``potential(x)`` its integral
    from 0 to x in J, ``force_derivative(x)`` f'(x) in N/m, for a compression x >= 0
    in m; ``mass`` in kg, ``damping`` b in s/m, ``velocity`` V in m/s (scalars).
    The functions are called many times and must not change what they read. An
    exception inside one of them makes it return NaN, which the library reports as
    an invalid law (HCIMPACT_ERR_ELASTIC_LAW, an :class:`InputError`).

    >>> c = 1.7135e10
    >>> r = impact_law(lambda x: c * x**1.5, lambda x: c * x**2.5 / 2.5,
    ...                lambda x: 1.5 * c * x**0.5, mass=0.1, damping=0.1, velocity=2.0)
    """
    def wrap(function: Callable[[float], float]) -> Any:
        def callback(x: float, data: Any) -> float:
            try:
                return float(function(x))
            except Exception:           # never let an exception cross the C boundary
                return float("nan")
        return LawFunction(callback)

    callbacks = [wrap(force), wrap(potential), wrap(force_derivative)]
    law = ElasticLaw(callbacks[0], callbacks[1], callbacks[2], None)
    outcome = Outcome()
    status = _lib().hcimpact_impact_law(byref(law), float(mass), float(damping),
                                        float(velocity), byref(outcome))
    if status != 0:
        _raise(status, "hcimpact_impact_law")
    return _result(outcome)


def velocity_at_depth(x: Any, *, mass: float, stiffness: float, exponent: float = 1.5,
                      damping: float = 0.0, velocity: float,
                      branch: Any = "compression") -> Any:
    """Velocity x' (m/s) at the compression x (m, 0 <= x <= x_max): the phase curve.

    ``branch`` is ``"compression"`` (x' >= 0) or ``"restitution"`` (x' <= 0). x may be an
    array (one call of the C array form). Raises InputError for x outside [0, x_max] or
    a bad contact.
    """
    lib = _lib()
    contact = _contact(mass, stiffness, exponent, damping, velocity)
    code = _branch(branch)
    if _is_scalar(x):
        v = c_double()
        status = lib.hcimpact_velocity_at_depth(byref(contact), float(x), code, byref(v))
        if status != 0:
            _raise(status, "hcimpact_velocity_at_depth")
        return v.value
    a = np.ascontiguousarray(x, dtype=np.float64)
    out = np.empty_like(a)
    if a.size:
        status = lib.hcimpact_velocity_at_depth_array(byref(contact), a.size, _ptr(a), code,
                                                      _ptr(out))
        if status != 0:
            _raise(status, "hcimpact_velocity_at_depth_array")
    return out


def time_law(t: Any, *, mass: float, stiffness: float, exponent: float = 1.5,
             damping: float = 0.0, velocity: float) -> tuple[Any, Any, Any]:
    """Compression x(t) (m), velocity x'(t) (m/s) and force F(t) (N) at the times t (s).

    t counts from the start of contact, in any order; before it x = 0, x' = V, F = 0,
    after it x = 0, x' = -k V, F = 0. Returns (x, v, f), each of t's shape (floats for
    a scalar t).
    """
    lib = _lib()
    contact = _contact(mass, stiffness, exponent, damping, velocity)
    a = np.ascontiguousarray(np.atleast_1d(np.asarray(t, dtype=np.float64)))
    x, v, f = np.empty_like(a), np.empty_like(a), np.empty_like(a)
    if a.size:
        status = lib.hcimpact_time_law(byref(contact), a.size, _ptr(a), _ptr(x), _ptr(v),
                                       _ptr(f))
        if status != 0:
            _raise(status, "hcimpact_time_law")
    if _is_scalar(t):
        return float(x[0]), float(v[0]), float(f[0])
    shape = np.shape(t)
    return x.reshape(shape), v.reshape(shape), f.reshape(shape)


def time_law_samples(n: int, *, mass: float, stiffness: float, exponent: float = 1.5,
                     damping: float = 0.0, velocity: float) -> tuple[Any, Any, Any, Any]:
    """The time law on n >= 2 equally spaced times from 0 to the contact time.

    Returns (t, x, v, f), arrays of n elements (s, m, m/s, N).
    """
    lib = _lib()
    contact = _contact(mass, stiffness, exponent, damping, velocity)
    n = int(n)
    arrays = [np.empty(max(n, 0), dtype=np.float64) for _ in range(4)]
    if n < 2:
        _raise(14, "hcimpact_time_law_samples")
    status = lib.hcimpact_time_law_samples(byref(contact), n, *[_ptr(a) for a in arrays])
    if status != 0:
        _raise(status, "hcimpact_time_law_samples")
    return tuple(arrays)


# ---------------------------------------------------------------------------
# Components
# ---------------------------------------------------------------------------

def _component_function(function: str, stem: str, what: str) -> Any:
    lib = _library.component(function, stem)
    if lib is None:
        message = (f"this hcimpact has no {what} (lib{stem} was not found next to "
                   f"{_library.library_path()}); build it with the component on")
        raise UnavailableError(12, message, function)
    return getattr(lib, function)


def has_simulate() -> bool:
    """True when the library has the CVODE component (:func:`simulate` works)."""
    return _library.component("hcimpact_simulate", "hcimpact_cvode") is not None


def simulate(*, mass: float, stiffness: float, exponent: float = 1.5, damping: float = 0.0,
             velocity: float, rtol: float = 1.0e-10) -> ImpactResult:
    """The impact integrated by SUNDIALS CVODE with the relative tolerance ``rtol``.

    Same arguments and result as :func:`impact` (to about rtol). Needs the CVODE
    component (``libhcimpact_cvode``); without it raises :class:`UnavailableError`.
    """
    function = _component_function("hcimpact_simulate", "hcimpact_cvode",
                                    "CVODE component (hcimpact_simulate)")
    outcome = Outcome()
    status = function(byref(_contact(mass, stiffness, exponent, damping, velocity)),
                      float(rtol), byref(outcome))
    if status != 0:
        _raise(status, "hcimpact_simulate")
    return _result(outcome)


@dataclass(frozen=True)
class FitResult:
    """Result of a calibration fit (LAPACK component).

    ``parameters``: the fitted values (a dict, SI units); ``covariance``: their
    covariance matrix (in the order of ``parameters``); ``residuals``: as documented
    for each fit (doc/calibration-c-api.h.txt).
    """

    parameters: dict
    covariance: np.ndarray
    residuals: np.ndarray

    @property
    def standard_errors(self) -> dict:
        """Square roots of the covariance diagonal, by parameter name."""
        return {name: float(math.sqrt(self.covariance[i, i]))
                for i, name in enumerate(self.parameters)}


def _data(x: Any, n: int | None = None, name: str = "") -> np.ndarray:
    a = np.ascontiguousarray(np.asarray(x, dtype=np.float64).reshape(-1))
    if n is not None and a.size != n:
        raise ValueError(f"{name} has {a.size} values, expected {n}")
    return a


def _optional(x: Any, n: int, name: str) -> tuple[Any, Any]:
    if x is None:
        return None, None
    a = _data(x, n, name)
    return a, _ptr(a)


def _fit_damping(function_name: str, velocity: Any, restitution: Any, sigma: Any,
                 absolute_sigma: bool) -> FitResult:
    function = _component_function(function_name, "hcimpact_lapack",
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
    return FitResult({"damping": damping.value}, np.array([[error.value**2]]), residuals)


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
    function = _component_function("hcimpact_fit_static", "hcimpact_lapack",
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
                     covariance, residuals)


def fit_elastic(velocity: Any, *, mass: float, damping: float, contact_time: Any = None,
                peak_force: Any = None, sigma_time: Any = None, sigma_force: Any = None,
                absolute_sigma: bool = False, guess: Any = None) -> FitResult:
    """Elastic law (c, n) from contact times and/or peak forces at the speeds ``velocity``,
    the damping b known. Residuals ln(observed/model), time series first.
    Needs the LAPACK component.
    """
    function = _component_function("hcimpact_fit_elastic", "hcimpact_lapack",
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
    status = function(v.size, float(mass), float(damping), _ptr(v), *[p for _, p in pairs],
                      int(bool(absolute_sigma)), guess_ptr, _ptr(parameters),
                      _ptr(covariance), _ptr(residuals))
    if status != 0:
        _raise(status, "hcimpact_fit_elastic")
    count = v.size * sum(s is not None for s in series)
    return FitResult({"stiffness": float(parameters[0]), "exponent": float(parameters[1])},
                     covariance, residuals[:count])


def fit_impact(velocity: Any, *, mass: float, contact_time: Any = None,
               peak_force: Any = None, restitution: Any = None, sigma_time: Any = None,
               sigma_force: Any = None, sigma_restitution: Any = None,
               absolute_sigma: bool = False, guess: Any = None) -> FitResult:
    """Joint fit of (c, n, b) to contact times, peak forces and restitution measured at
    the speeds ``velocity``. Residuals per series given (time, force, restitution).
    Needs the LAPACK component.
    """
    function = _component_function("hcimpact_fit_impact", "hcimpact_lapack",
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
    status = function(v.size, float(mass), _ptr(v), *[p for _, p in pairs],
                      int(bool(absolute_sigma)), guess_ptr, _ptr(parameters),
                      _ptr(covariance), _ptr(residuals))
    if status != 0:
        _raise(status, "hcimpact_fit_impact")
    return FitResult({"stiffness": float(parameters[0]), "exponent": float(parameters[1]),
                      "damping": float(parameters[2])}, covariance, residuals[:count])


# ---------------------------------------------------------------------------
# Library
# ---------------------------------------------------------------------------

def status_message(status: int) -> str:
    """The library's text for a status code ("unknown status code" for others)."""
    return _lib().hcimpact_status_message(int(status)).decode()


def version() -> str:
    """Version of the loaded library, "major.minor.patch"."""
    return _lib().hcimpact_version().decode()


def version_number() -> int:
    """Version of the loaded library as 10000 major + 100 minor + patch."""
    return int(_lib().hcimpact_version_number())


def library_path() -> str:
    """Path of the shared library in use."""
    return _library.library_path()
