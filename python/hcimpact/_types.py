# SPDX-License-Identifier: Apache-2.0
"""The C structures of ``hcimpact.h``, the result type and the exceptions."""

from __future__ import annotations

import ctypes
from dataclasses import dataclass, fields
from typing import Any

__all__ = [
    "Contact", "Outcome", "ImpactResult", "HcimpactError", "InputError", "ComputationError",
    "OutOfMemoryError", "UnavailableError", "STATUS_NAMES", "ChainLaw", "ChainWall",
    "ChainOptions", "ChainOutcome", "ChainContact", "ChainSamples",
]


# The structures mirror include/hcimpact.h field by field, in its order and with its
# types; python/tests/test_layout.py parses the header and fails on any difference.

CONTACT_FIELDS = ("mass", "stiffness", "exponent", "damping", "velocity")


class Contact(ctypes.Structure):
    """``hcimpact_contact``: mass (kg), stiffness (N/m^n), exponent, damping (s/m),
    velocity (m/s)."""

    _fields_ = [(name, ctypes.c_double) for name in CONTACT_FIELDS]


OUTCOME_FIELDS = ("restitution", "energy_loss_ratio", "rebound_velocity", "max_compression",
                  "peak_force", "compression_at_peak_force", "time_at_peak_force",
                  "compression_time",
                  "contact_time")


class Outcome(ctypes.Structure):
    """``hcimpact_outcome``, field by field."""

    _fields_ = [(name, ctypes.c_double) for name in OUTCOME_FIELDS]


#: A callback of an elastic law: double fn(double x, void *data)
LawFunction = ctypes.CFUNCTYPE(ctypes.c_double, ctypes.c_double, ctypes.c_void_p)


class ElasticLaw(ctypes.Structure):
    """struct hcimpact_elastic_law: force, potential, force_derivative, data."""

    _fields_ = [("force", LawFunction), ("potential", LawFunction),
                ("force_derivative", LawFunction), ("data", ctypes.c_void_p)]


# The structures of a system of bodies on a line (include/hcimpact_cvode.h); the same
# test compares them with that header.

class ChainLaw(ctypes.Structure):
    """``hcimpact_chain_law``: stiffness (N/m^n), exponent, damping (s/m) of a pair."""

    _fields_ = [(name, ctypes.c_double) for name in ("stiffness", "exponent", "damping")]


class ChainWall(ctypes.Structure):
    """``hcimpact_chain_wall``: a wall's law and its gap (m) to the end body."""

    _fields_ = [(name, ctypes.c_double)
                for name in ("stiffness", "exponent", "damping", "gap")]


class ChainOptions(ctypes.Structure):
    """``hcimpact_chain_options`` (zeros: the defaults)."""

    _fields_ = [("t_end", ctypes.c_double), ("rtol", ctypes.c_double),
                ("max_steps", ctypes.c_int64), ("max_events", ctypes.c_int64),
                ("method", ctypes.c_int), ("integrator", ctypes.c_int)]


#: The counts of ``hcimpact_chain_result``, in its order
CHAIN_COUNTS = ("n_contacts", "contacts_recorded", "closed_form_contacts",
                "integrated_contacts", "steps", "rhs_evals", "jacobian_evals", "roots",
                "clusters")


class ChainOutcome(ctypes.Structure):
    """``hcimpact_chain_result``, field by field."""

    _fields_ = ([(name, ctypes.c_double) for name in
                 ("time", "rest_time", "initial_energy", "energy_error", "dissipated",
                  "momentum_error", "wall_impulse_left", "wall_impulse_right")]
                + [(name, ctypes.c_int64) for name in CHAIN_COUNTS]
                + [("method_used", ctypes.c_int), ("rested", ctypes.c_int)])


class ChainContact(ctypes.Structure):
    """``hcimpact_chain_contact``: one contact from its start to its end."""

    _fields_ = ([(name, ctypes.c_double) for name in
                 ("t_start", "t_end", "approach_speed", "separation_speed", "peak_force",
                  "max_deformation", "dissipated")]
                + [("pair", ctypes.c_int), ("method", ctypes.c_int)])


#: The poll of a chain's monitor: int fn(void *data, double time, int64_t steps,
#: int64_t events), nonzero to stop the run
ChainPoll = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_double, ctypes.c_int64,
                             ctypes.c_int64)


class ChainMonitor(ctypes.Structure):
    """``hcimpact_chain_monitor``: the poll of a run and the caller's data."""

    _fields_ = [("poll", ChainPoll), ("data", ctypes.c_void_p)]


class ChainSamples(ctypes.Structure):
    """``hcimpact_chain_samples``: the sample times and the caller's arrays."""

    _fields_ = [("count", ctypes.c_int), ("times", ctypes.POINTER(ctypes.c_double)),
                ("positions", ctypes.POINTER(ctypes.c_double)),
                ("velocities", ctypes.POINTER(ctypes.c_double)),
                ("forces", ctypes.POINTER(ctypes.c_double))]


@dataclass(frozen=True, repr=False)
class ImpactResult:
    """What :func:`hcimpact.impact` (and :func:`hcimpact.simulate`) computes.

    SI units. For array inputs every field is a NumPy array of the broadcast shape.
    """

    #: coefficient of restitution k = -(rebound velocity)/V, in (0, 1]
    restitution: Any
    #: share of the kinetic energy lost, 1 - k^2
    energy_loss_ratio: Any
    #: rebound velocity -k V in m/s (negative)
    rebound_velocity: Any
    #: maximum compression x_max in m
    max_compression: Any
    #: largest contact force c x^n (1 + b x') in N
    peak_force: Any
    #: compression at which the peak force acts, in m
    compression_at_peak_force: Any
    #: time from the start of contact to the peak force, in s
    time_at_peak_force: Any
    #: time from the start of contact to x_max, in s
    compression_time: Any
    #: duration of the contact, in s
    contact_time: Any

    def as_dict(self) -> dict[str, Any]:
        """The fields as a dictionary (in their order)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def __repr__(self) -> str:
        """One line: the main outputs with 6 digits, arrays by shape and range."""
        shown = ("restitution", "max_compression", "peak_force", "contact_time")
        units = {"restitution": "", "max_compression": " m", "peak_force": " N",
                 "contact_time": " s"}
        first = getattr(self, shown[0])
        if hasattr(first, "shape") and getattr(first, "shape", ()) != ():
            import numpy as np   # arrays exist only once NumPy is imported

            def text(name: str) -> str:
                a = np.asarray(getattr(self, name))
                if a.size == 0:
                    return f"{name}=[]"
                return (f"{name}=[{np.nanmin(a):.6g} .. {np.nanmax(a):.6g}]{units[name]}"
                        if np.any(np.isfinite(a)) else f"{name}=[nan]")
            return (f"ImpactResult(shape={first.shape}, "
                    + ", ".join(text(name) for name in shown) + ")")
        return ("ImpactResult(" + ", ".join(f"{name}={float(getattr(self, name)):.6g}"
                                            f"{units[name]}" for name in shown) + ")")


#: Names of the status codes (the HCIMPACT_* macros of hcimpact.h)
STATUS_NAMES = {
    0: "HCIMPACT_OK", 1: "HCIMPACT_ERR_NOT_FINITE", 2: "HCIMPACT_ERR_MASS",
    3: "HCIMPACT_ERR_STIFFNESS", 4: "HCIMPACT_ERR_EXPONENT", 5: "HCIMPACT_ERR_VELOCITY",
    6: "HCIMPACT_ERR_DAMPING", 7: "HCIMPACT_ERR_RESTITUTION", 8: "HCIMPACT_ERR_DOMAIN",
    9: "HCIMPACT_ERR_NO_CONVERGENCE", 10: "HCIMPACT_ERR_NULL", 11: "HCIMPACT_ERR_SOLVER",
    12: "HCIMPACT_ERR_UNAVAILABLE", 13: "HCIMPACT_ERR_ELASTIC_LAW", 14: "HCIMPACT_ERR_SIZE",
    15: "HCIMPACT_ERR_UNDERDETERMINED", 16: "HCIMPACT_ERR_OUT_OF_MEMORY",
}


class HcimpactError(Exception):
    """An error status of the library.

    ``status`` is the code (``HCIMPACT_*``), ``name`` its macro name, ``message`` the
    library's text (``hcimpact_status_message``), ``function`` the C function, and
    ``index`` the position of the failing element for array inputs (else None).
    """

    def __init__(self, status: int, message: str, function: str, index: int | None = None):
        self.status = status
        self.name = STATUS_NAMES.get(status, f"status {status}")
        self.message = message
        self.function = function
        self.index = index
        where = f" (element {index})" if index is not None else ""
        super().__init__(f"{function}{where}: {message} [{self.name}]")


class InputError(HcimpactError, ValueError):
    """An argument is invalid: NaN, infinite, or outside its domain (statuses 1-8, 10,
    13, 14)."""


class ComputationError(HcimpactError, ArithmeticError):
    """A computation failed: no convergence (9), the ODE solver failed (11), or the
    data cannot determine a fit (15)."""


class OutOfMemoryError(HcimpactError, MemoryError):
    """The memory available is too small for the computation (status 16,
    ``HCIMPACT_ERR_OUT_OF_MEMORY``: a system of bodies, a time law, a fit too large for
    it; the arguments are valid). Also a ``MemoryError``."""


class UnavailableError(HcimpactError, RuntimeError):
    """The component (CVODE, LAPACK) is not part of this build or installation (12)."""


def error_class(status: int) -> type[HcimpactError]:
    """The exception type of a status code (the one place that decides)."""
    if status in (9, 11, 15):
        return ComputationError
    if status == 12:
        return UnavailableError
    if status == 16:
        return OutOfMemoryError
    return InputError
