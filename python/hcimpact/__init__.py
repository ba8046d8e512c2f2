# SPDX-License-Identifier: Apache-2.0
"""hcimpact: the Hunt-Crossley model of a collinear impact, from Python.

A thin layer over the C interface of the library (``include/hcimpact.h``) through
:mod:`ctypes`: nothing is compiled, but the shared library ``libhcimpact.so`` must be
found (``HCIMPACT_LIBRARY``, ``HCIMPACT_PREFIX``, a build tree; see ``python/README.md``).

>>> import hcimpact
>>> hcimpact.restitution(0.5)                       # k(beta), beta = b V
0.7484349315974341
>>> r = hcimpact.impact(mass=0.1, stiffness=1.7135e10, exponent=1.5, damping=0.1,
...                     velocity=5.0)
>>> r.contact_time                                  # s
7.765538404326971e-05
>>> c = 1.7135e10 / 2**0.5                          # two steel balls (Hertz)
>>> hcimpact.chain([0.1] * 3, [1.0, 0, 0], stiffness=c).velocities   # a cradle
array([-0.07095235,  0.07640303,  0.99454932])

The package imports lazily: ``import hcimpact`` (or ``import hcimpact.plot``) neither
loads the library nor imports NumPy; the first call of a function does.
"""

from __future__ import annotations

import importlib
from typing import Any

__version__ = "0.2.0"

_API = (
    "lambert_w0", "lambert_wm1", "lambert_w0p1", "lambert_wm1p1",
    "restitution", "restitution_inverse", "one_minus_restitution", "energy_loss_ratio",
    "restitution_derivative", "u_minus_log1p", "damping_for_restitution",
    "hertz_constant", "effective_mass", "two_body_velocities",
    "impact", "impact_law", "velocity_at_depth", "time_law", "time_law_samples", "simulate",
    "has_simulate", "FitResult", "fit_damping", "fit_damping_linear", "fit_static",
    "fit_elastic", "fit_impact",
    "status_message", "version", "version_number", "library_path", "array_threads",
    "COMPRESSION", "RESTITUTION", "DEFAULT_MIN_VELOCITY",
)
_TYPES = ("ImpactResult", "HcimpactError", "InputError", "ComputationError", "OutOfMemoryError",
          "UnavailableError", "STATUS_NAMES")
_LIBRARY = ("LibraryNotFoundError",)
_FORCE = ("contact_force", "ContactForce")
_CHAIN = ("chain", "ChainResult", "has_chain", "BY_CLOSED_FORMS", "BY_INTEGRATION",
          "CONTACT_DTYPE")

__all__ = list(_API + _TYPES + _LIBRARY + _FORCE + _CHAIN)


def __getattr__(name: str) -> Any:
    if name in _API:
        module = importlib.import_module("._api", __name__)
    elif name in _TYPES:
        module = importlib.import_module("._types", __name__)
    elif name in _LIBRARY:
        module = importlib.import_module("._library", __name__)
    elif name in _FORCE:
        module = importlib.import_module("._force", __name__)
    elif name in _CHAIN:
        module = importlib.import_module("._chain", __name__)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(module, name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
