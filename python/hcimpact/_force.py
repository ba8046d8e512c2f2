# SPDX-License-Identifier: Apache-2.0
"""The contact-force element from Python: ``hcimpact.contact_force``.

A thin layer over ``hcimpact_contact_force_array`` (include/hcimpact.h): the force of
one contact at a deformation and a deformation rate, its two derivatives, the elastic
potential energy and the dissipated power, for every element of NumPy-broadcast inputs
in one call. doc/contact-force.md describes the element.
"""

from __future__ import annotations

import ctypes
from ctypes import POINTER, c_double, c_int
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from . import _library
from ._api import _broadcast, _real
from ._types import error_class

__all__ = ["ContactForce", "Force", "contact_force"]

#: The fields of ``hcimpact_force``, in the header's order
FORCE_FIELDS = ("force", "dforce_dx", "dforce_dv", "potential", "dissipation")

_CHUNK = 2**30


class Force(ctypes.Structure):
    """``hcimpact_force``, field by field."""

    _fields_ = [(name, c_double) for name in FORCE_FIELDS]


@dataclass(frozen=True, repr=False)
class ContactForce:
    """What :func:`contact_force` computes (SI units); floats for scalar input, NumPy
    arrays of the broadcast shape otherwise."""

    #: contact force F = f(x) max(0, 1 + b v) in N (>= 0, pushes the bodies apart)
    force: Any
    #: dF/dx in N/m (0 where the force is clamped)
    dforce_dx: Any
    #: dF/dv in N s/m (0 where the force is clamped)
    dforce_dv: Any
    #: elastic potential energy c x^(n+1)/(n+1) in J
    potential: Any
    #: dissipated power (F - f(x)) v in W (>= 0)
    dissipation: Any

    def as_dict(self) -> dict[str, Any]:
        """The fields as a dictionary (in their order)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def __repr__(self) -> str:
        if np.ndim(self.force) == 0:
            inner = ", ".join(f"{name}={getattr(self, name):.6g}" for name in FORCE_FIELDS)
        else:
            inner = f"shape={np.shape(self.force)}"
        return f"ContactForce({inner})"


_declared: set[int] = set()


def _function() -> Any:
    lib = _library.load()
    function = lib.hcimpact_contact_force_array
    if id(lib) not in _declared:
        pd = POINTER(c_double)
        function.restype = c_int
        function.argtypes = [c_int, pd, pd, pd, pd, pd, POINTER(Force), POINTER(c_int)]
        _declared.add(id(lib))
    return function


def contact_force(x: Any, v: Any, stiffness: Any, exponent: Any = 1.5, damping: Any = 0.0,
                  *, errors: str = "raise") -> ContactForce:
    """The contact-force element of a power-law contact f = c x^n with damping b.

    - ``x`` deformation in m (> 0 while the bodies overlap; x <= 0: no contact, every
      field 0)
    - ``v`` deformation rate dx/dt in m/s (> 0 while the bodies approach)
    - ``stiffness`` c in N/m**n (> 0), ``exponent`` n (>= 1e-6, default 1.5: Hertz),
      ``damping`` b in s/m (>= 0, default 0)
    - ``errors``: ``"raise"`` (an :class:`~hcimpact.InputError` for the first element
      with a bad argument, with its ``index``) or ``"nan"`` (NaN fields there)

    All arguments broadcast against each other. The force never pulls: where
    1 + b v < 0 it is clamped at 0, and so are its derivatives. Every field is within a
    few ulps of its exact value, also next to the clamp. Returns a
    :class:`ContactForce` with ``force``, ``dforce_dx``, ``dforce_dv``, ``potential``
    and ``dissipation``.
    """
    if errors not in ("raise", "nan"):
        raise ValueError(f"errors must be 'raise' or 'nan', not {errors!r}")
    where = "hcimpact_contact_force_array"
    args = [_real(a, name, where) for a, name in zip(
        (stiffness, exponent, damping, x, v), ("stiffness", "exponent", "damping", "x", "v"))]
    arrays = _broadcast(args, where)
    shape = arrays[0].shape
    flat = [np.ascontiguousarray(a).reshape(-1) for a in arrays]
    n = flat[0].size
    out = np.empty((n, len(FORCE_FIELDS)), dtype=np.float64)
    statuses = np.zeros(n, dtype=np.intc)
    function = _function()
    pd = POINTER(c_double)
    for start in range(0, n, _CHUNK):
        m = min(_CHUNK, n - start)
        function(m, *[a[start:].ctypes.data_as(pd) for a in flat],
                 out[start:].ctypes.data_as(POINTER(Force)),
                 statuses[start:].ctypes.data_as(POINTER(c_int)))
    if errors == "raise" and n > 0 and np.any(statuses != 0):
        first = int(np.flatnonzero(statuses)[0])
        index = np.unravel_index(first, shape) if len(shape) > 1 else (first if shape else None)
        status = int(statuses[first])
        message = _library.load().hcimpact_status_message(status).decode()
        raise error_class(status)(status, message, where, index)
    if shape == ():
        return ContactForce(*[float(out[0, j]) for j in range(len(FORCE_FIELDS))])
    return ContactForce(*[out[:, j].reshape(shape) for j in range(len(FORCE_FIELDS))])
