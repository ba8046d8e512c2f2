# SPDX-License-Identifier: Apache-2.0
"""Fixtures of the hcimpact Python tests: the reference data and the library.

The library is found as the package finds it (HCIMPACT_LIBRARY, HCIMPACT_PREFIX, a build
tree; python/README.md). When HCIMPACT_LIBRARY is set and cannot be loaded the tests
fail; when nothing is set and no library is found they are skipped with the reason.
"""

from __future__ import annotations

import csv
import os
import sys
from pathlib import Path

import numpy as np
import pytest

# the package from this source tree when it is not installed (or on PYTHONPATH)
try:
    import hcimpact
except ImportError:
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    import hcimpact


def pytest_configure(config):
    config.addinivalue_line("markers", "cvode: needs the CVODE component")
    config.addinivalue_line("markers", "lapack: needs the LAPACK component")


@pytest.fixture(scope="session", autouse=True)
def library():
    try:
        path = hcimpact.library_path()
    except hcimpact.LibraryNotFoundError as exc:
        if os.environ.get("HCIMPACT_LIBRARY"):
            raise
        pytest.skip(f"no shared libhcimpact found: {exc}", allow_module_level=True)
    return path


def reference_dir() -> Path:
    env = os.environ.get("HCIMPACT_REFERENCE_DIR")
    if env:
        return Path(env)
    return Path(__file__).resolve().parents[2] / "test" / "reference"


def read_reference(name: str, fieldnames: list[str] | None = None) -> list[dict[str, str]]:
    """Rows of test/reference/<name> (comment lines skipped) as dictionaries; the column
    names are the first line unless given."""
    path = reference_dir() / name
    if not path.is_file():
        pytest.skip(f"reference data {path} not found")
    with open(path, newline="") as fh:
        lines = [line for line in fh if not line.startswith("#")]
    return list(csv.DictReader(lines, fieldnames=fieldnames))


def ulp_error(actual, hi, lo=0.0):
    """|(actual - hi) - lo| / ulp(exact), the convention of test/reference/README.md.

    NaN against NaN and equal infinities count 0; NaN against a number +inf.
    """
    actual, hi, lo = (np.asarray(a, dtype=np.float64) for a in (actual, hi, lo))
    with np.errstate(invalid="ignore", over="ignore"):
        ulp = np.spacing(np.abs(hi))
        # a power of two with the rest pointing to zero: the ulp below it is half
        half = (np.frexp(np.abs(hi))[0] == 0.5) & (lo * np.sign(hi) < 0)
        ulp = np.where(half, ulp / 2, ulp)
        ulp = np.where(ulp == 0, 5e-324, ulp)
        err = np.abs((actual - hi) - lo) / ulp
        same_special = (np.isnan(actual) & np.isnan(hi)) | (np.isinf(hi) & (actual == hi))
        err = np.where(same_special, 0.0, err)
        err = np.where(np.isnan(err), np.inf, err)
    return err
