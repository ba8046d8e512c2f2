# SPDX-License-Identifier: Apache-2.0
"""Finding and loading the shared library ``libhcimpact`` with :mod:`ctypes`.

The search order (first hit wins; see ``python/README.md``):

1. ``HCIMPACT_LIBRARY``: the path of the shared library itself. When it is set, nothing
   else is tried.
2. ``HCIMPACT_PREFIX``: a CMake install prefix; its ``lib``, ``lib64`` and
   ``lib/<multiarch>`` directories.
3. The package's own ``lib`` directory: where ``pip install ./python`` (the wheel built
   by scikit-build-core) puts the library.
4. The build trees of the source checkout this package sits in
   (``<repo>/build/*/libhcimpact.so``), newest first, when the package is imported
   from ``<repo>/python``.
5. The prefix of the running Python (a virtual environment or conda prefix that
   hcimpact was installed into with ``-DCMAKE_INSTALL_PREFIX=$VIRTUAL_ENV``).
6. The dynamic loader's own search (``LD_LIBRARY_PATH``, ``ldconfig``: e.g. an install
   to ``/usr/local``), then ``/usr/local/lib*``.

When nothing loads, :class:`LibraryNotFoundError` lists every place tried and why each
failed. The optional components live in libraries of their own next to the core:
``libhcimpact_cvode`` provides ``hcimpact_simulate`` and ``hcimpact_chain_simulate``,
``libhcimpact_lapack`` the fits.
They are looked up in the directory of the core library (and, for a library that was
linked with everything inside, in the core library itself). A wheel records which
components it was built with, and why one is missing, in ``hcimpact/_build.json``.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import glob
import json
import os
import sys
import sysconfig
import threading
from ctypes import POINTER, c_char_p, c_double, c_int, c_size_t
from pathlib import Path

__all__ = ["LibraryNotFoundError", "load", "library_path", "component", "build_info"]


class LibraryNotFoundError(ImportError):
    """The shared library ``libhcimpact`` was not found (or could not be loaded)."""


_SUFFIX = ".dylib" if sys.platform == "darwin" else ".so"
_lock = threading.Lock()
_core: ctypes.CDLL | None = None
_core_path: str | None = None
_components: dict[str, ctypes.CDLL | None] = {}


def _library_files(directory: Path, stem: str) -> list[Path]:
    """libhcimpact.so, else the versioned libhcimpact.so.X.Y (without the -dev link)."""
    exact = directory / f"lib{stem}{_SUFFIX}"
    if exact.is_file():
        return [exact]
    return sorted(Path(p) for p in glob.glob(str(directory / f"lib{stem}{_SUFFIX}.*")))


def _prefix_dirs(prefix: Path) -> list[Path]:
    dirs = [prefix / "lib", prefix / "lib64"]
    multiarch = sysconfig.get_config_var("MULTIARCH")
    if multiarch:
        dirs.append(prefix / "lib" / multiarch)
    dirs.extend(Path(p) for p in sorted(glob.glob(str(prefix / "lib" / "*-linux-gnu")))
                if Path(p) not in dirs)
    return dirs


#: The package directory (hcimpact/), where the wheel puts lib/ and _build.json
PACKAGE_DIR = Path(__file__).resolve().parent


def _candidates() -> list[tuple[str, Path | None, str]]:
    """(where, path, detail) of every place tried, in order.

    ``path`` is a library file to load, or None for a place that holds none; then
    ``detail`` says what was looked for there.
    """
    tried: list[tuple[str, Path | None, str]] = []

    def directories(where: str, dirs: list[Path]) -> None:
        for directory in dirs:
            files = _library_files(directory, "hcimpact")
            tried.extend((where, p, "") for p in files)
            if not files:
                tried.append((where, None, f"{directory / ('libhcimpact' + _SUFFIX)}: no such file"))

    prefix = os.environ.get("HCIMPACT_PREFIX")
    if prefix:
        directories("HCIMPACT_PREFIX", _prefix_dirs(Path(prefix)))
    else:
        tried.append(("HCIMPACT_PREFIX", None, "not set"))
    directories("the package (a wheel)", [PACKAGE_DIR / "lib"])
    # <repo>/python/hcimpact/_library.py -> <repo>/build/*/
    repo = PACKAGE_DIR.parents[1]
    if (repo / "include" / "hcimpact.h").is_file():
        pattern = repo / "build" / "*" / f"libhcimpact{_SUFFIX}"
        builds = [Path(p) for p in glob.glob(str(pattern))]
        builds.sort(key=lambda p: p.stat().st_mtime, reverse=True)
        tried.extend(("build tree", p, "") for p in builds)
        if not builds:
            tried.append(("build tree", None, f"{pattern}: no match"))
    directories("sys.prefix", _prefix_dirs(Path(sys.prefix)))
    system = ctypes.util.find_library("hcimpact")
    if system:
        tried.append(("dynamic loader", Path(system), ""))
    else:
        tried.append(("dynamic loader", None,
                      "ctypes.util.find_library('hcimpact') found nothing "
                      "(LD_LIBRARY_PATH, ldconfig)"))
    directories("/usr/local", _prefix_dirs(Path("/usr/local")))
    return tried


def _declare(lib: ctypes.CDLL) -> None:
    """Argument and result types of the core functions (include/hcimpact.h)."""
    from ._types import Contact, ElasticLaw, Outcome

    d, i, pd, pi = c_double, c_int, POINTER(c_double), POINTER(c_int)
    pc, po = POINTER(Contact), POINTER(Outcome)
    signatures = {
        "hcimpact_status_message": (c_char_p, [i]),
        "hcimpact_version": (c_char_p, []),
        "hcimpact_version_number": (i, []),
        "hcimpact_array_threads": (i, []),
        "hcimpact_damping_for_restitution": (i, [d, d, d, pd]),
        "hcimpact_hertz_constant": (d, [d] * 6),
        "hcimpact_effective_mass": (d, [d, d]),
        "hcimpact_two_body_velocities": (i, [d] * 5 + [pd, pd]),
        "hcimpact_impact": (i, [pc, po]),
        "hcimpact_impact_array": (i, [i, pc, po, pi]),
        "hcimpact_impact_law": (i, [POINTER(ElasticLaw), d, d, d, po]),
        "hcimpact_velocity_at_depth": (i, [pc, d, i, pd]),
        "hcimpact_velocity_at_depth_array": (i, [pc, i, pd, i, pd]),
        "hcimpact_time_law": (i, [pc, i, pd, pd, pd, pd]),
        "hcimpact_time_law_samples": (i, [pc, i, pd, pd, pd, pd]),
    }
    for name in ("lambert_w0", "lambert_wm1", "lambert_w0p1", "lambert_wm1p1", "restitution",
                 "restitution_inverse", "one_minus_restitution", "energy_loss_ratio",
                 "restitution_derivative"):
        signatures[f"hcimpact_{name}"] = (d, [d])
        signatures[f"hcimpact_{name}_array"] = (i, [i, pd, pd])
    signatures["hcimpact_u_minus_log1p"] = (d, [d])
    for name, (restype, argtypes) in signatures.items():
        function = getattr(lib, name)
        function.restype = restype
        function.argtypes = argtypes


def _declare_components(lib: ctypes.CDLL) -> None:
    from ._types import (ChainContact, ChainLaw, ChainMonitor, ChainOptions, ChainOutcome,
                         ChainSamples, ChainWall, Contact, Outcome)

    d, i, pd = c_double, c_int, POINTER(c_double)
    signatures = {
        "hcimpact_chain_simulate": (i, [i, pd, pd, pd, POINTER(ChainLaw), POINTER(ChainWall),
                                        POINTER(ChainWall), d, POINTER(ChainOptions),
                                        POINTER(ChainOutcome), pd, pd, i,
                                        POINTER(ChainContact), POINTER(ChainSamples),
                                        c_char_p, c_size_t]),
        "hcimpact_chain_simulate_monitored": (
            i, [i, pd, pd, pd, POINTER(ChainLaw), POINTER(ChainWall), POINTER(ChainWall), d,
                POINTER(ChainOptions), POINTER(ChainOutcome), pd, pd, i, POINTER(ChainContact),
                POINTER(ChainSamples), POINTER(ChainMonitor), c_char_p, c_size_t]),
        "hcimpact_simulate": (i, [POINTER(Contact), d, POINTER(Outcome)]),
        "hcimpact_simulate_message": (i, [POINTER(Contact), d, POINTER(Outcome), c_char_p,
                                          c_size_t]),
        "hcimpact_fit_damping": (i, [i, pd, pd, pd, i, pd, pd, pd]),
        "hcimpact_fit_damping_linear": (i, [i, pd, pd, pd, i, pd, pd, pd]),
        "hcimpact_fit_static": (i, [i, pd, pd, pd, i, pd, pd, pd]),
        "hcimpact_fit_elastic": (i, [i, d, d, pd, pd, pd, pd, pd, i, pd, pd, pd, pd]),
        "hcimpact_fit_impact": (i, [i, d, pd, pd, pd, pd, pd, pd, pd, i, pd, pd, pd, pd]),
    }
    for name, (restype, argtypes) in signatures.items():
        function = getattr(lib, name, None)
        if function is not None:
            function.restype = restype
            function.argtypes = argtypes


def load() -> ctypes.CDLL:
    """The core library, loaded on first use (thread-safe)."""
    global _core, _core_path
    if _core is not None:
        return _core
    with _lock:
        if _core is not None:
            return _core
        explicit = os.environ.get("HCIMPACT_LIBRARY")
        if explicit:
            tried: list[tuple[str, Path | None, str]] = [
                ("HCIMPACT_LIBRARY", Path(explicit), "")]
        else:
            tried = _candidates()
        errors = []
        for where, path, detail in tried:
            if path is None:
                errors.append(f"  {where}: {detail}")
                continue
            try:
                lib = ctypes.CDLL(str(path))
            except OSError as exc:
                errors.append(f"  {where}: {path}: {exc}")
                continue
            if not hasattr(lib, "hcimpact_version_number"):
                errors.append(f"  {where}: {path}: not libhcimpact (no hcimpact_version_number)")
                continue
            _declare(lib)
            _declare_components(lib)
            _core_path = str(path)
            _core = lib
            return lib
        raise LibraryNotFoundError(
            "cannot load the shared library libhcimpact. `pip install ./python` (from the "
            "repository) builds it into the package; or build it with CMake "
            "(-DBUILD_SHARED_LIBS=ON) and set HCIMPACT_LIBRARY=/path/to/libhcimpact.so or "
            "HCIMPACT_PREFIX=<install prefix> (python/README.md). Tried, in order:\n"
            + "\n".join(errors))


def build_info() -> dict:
    """What the wheel was built with (hcimpact/_build.json), or {} outside a wheel.

    ``{"version": ..., "components": {"cvode": {"built": bool, "status": str}, ...}}``;
    ``status`` is the configuration summary's line, e.g. "OFF (SUNDIALS not found:
    fcvode_mod.mod (libsundials-fortran-dev))".
    """
    path = PACKAGE_DIR / "_build.json"
    if not path.is_file():
        return {}
    with open(path, encoding="utf-8") as stream:
        return json.load(stream)


def library_path() -> str:
    """Path of the core library in use (loads it if needed)."""
    load()
    assert _core_path is not None
    return _core_path


def component(function: str, stem: str) -> ctypes.CDLL | None:
    """The library that exports ``function``: the core itself, or ``lib<stem>`` next to it.

    None when neither has it (the component is not part of this installation).
    """
    core = load()
    if hasattr(core, function):
        return core
    with _lock:
        if stem not in _components:
            lib = None
            directory = Path(library_path()).resolve().parent
            for path in [directory / f"lib{stem}{_SUFFIX}", *_library_files(directory, stem),
                         Path(library_path()).parent / f"lib{stem}{_SUFFIX}"]:
                if not path.is_file():
                    continue
                try:
                    lib = ctypes.CDLL(str(path))
                except OSError:
                    continue
                _declare_components(lib)
                break
            _components[stem] = lib
        lib = _components[stem]
    if lib is not None and hasattr(lib, function):
        return lib
    return None
