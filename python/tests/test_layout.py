# SPDX-License-Identifier: Apache-2.0
"""Python's view of the C structures against include/hcimpact.h and hcimpact_cvode.h.

ctypes cannot read a header: the package mirrors ``hcimpact_contact``,
``hcimpact_outcome``, ``hcimpact_elastic_law``, the chain structures of
hcimpact_cvode.h (``hcimpact_chain_law``, ``_wall``, ``_options``, ``_result``,
``_contact``, ``_samples``, ``_monitor``; hcimpact/_types.py) and ``hcimpact_force``
(hcimpact/_force.py) by hand. These
tests parse the header's declarations and compare them with the mirrors field by field
(name, order, C type), and the callback types with the header's typedefs, so that a field
added, removed, reordered or retyped in the header fails here instead of silently
shifting every value that Python reads. They also check that ``ImpactResult`` has the
outcome's fields. The headers are taken from the source tree (or the directory of
HCIMPACT_HEADER).
"""

from __future__ import annotations

import ctypes
import dataclasses
import os
import re
from pathlib import Path

import pytest

from hcimpact import _force, _types


def header_text(name: str = "hcimpact.h") -> str:
    main = Path(os.environ.get("HCIMPACT_HEADER")
                or Path(__file__).resolve().parents[2] / "include" / "hcimpact.h")
    path = main.parent / name
    if not path.is_file():
        pytest.skip(f"{path} not found (set HCIMPACT_HEADER)")
    text = path.read_text(encoding="utf-8")
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)    # comments
    return re.sub(r"//[^\n]*", " ", text)


def struct_fields(text: str, name: str) -> list[tuple[str, str]]:
    """(C type, field name) of ``typedef struct {...} name;``, in order."""
    match = re.search(r"typedef\s+struct\s*\w*\s*\{([^}]*)\}\s*" + name + r"\s*;", text)
    assert match, f"typedef struct ... {name}; not found in the header"
    fields = []
    for declaration in match.group(1).split(";"):
        declaration = " ".join(declaration.split())
        if not declaration:
            continue
        for part in declaration.split(","):   # "double a, b" declares two fields
            part = part.strip()
            decl = re.fullmatch(r"(.*?)([A-Za-z_]\w*)", part)
            assert decl, f"cannot read the field declaration {part!r} of {name}"
            ctype = decl.group(1).strip() or fields[-1][0]
            fields.append((ctype.replace(" *", "*").replace("* ", "*"), decl.group(2)))
    return fields


# the C types the structures use, and their ctypes counterparts
C_TYPES = {"double": ctypes.c_double, "void*": ctypes.c_void_p, "int": ctypes.c_int,
           "int64_t": ctypes.c_int64, "const double*": ctypes.POINTER(ctypes.c_double),
           "double*": ctypes.POINTER(ctypes.c_double), "hcimpact_law_fn": _types.LawFunction,
           "hcimpact_chain_poll": _types.ChainPoll}


def python_fields(structure: type[ctypes.Structure]) -> list[tuple[str, object]]:
    return [(name, ctype) for name, ctype in structure._fields_]


@pytest.mark.parametrize("header, c_name, structure", [
    ("hcimpact.h", "hcimpact_contact", _types.Contact),
    ("hcimpact.h", "hcimpact_outcome", _types.Outcome),
    ("hcimpact.h", "hcimpact_elastic_law", _types.ElasticLaw),
    ("hcimpact.h", "hcimpact_force", _force.Force),
    ("hcimpact_cvode.h", "hcimpact_chain_law", _types.ChainLaw),
    ("hcimpact_cvode.h", "hcimpact_chain_wall", _types.ChainWall),
    ("hcimpact_cvode.h", "hcimpact_chain_options", _types.ChainOptions),
    ("hcimpact_cvode.h", "hcimpact_chain_result", _types.ChainOutcome),
    ("hcimpact_cvode.h", "hcimpact_chain_contact", _types.ChainContact),
    ("hcimpact_cvode.h", "hcimpact_chain_samples", _types.ChainSamples),
    ("hcimpact_cvode.h", "hcimpact_chain_monitor", _types.ChainMonitor),
])
def test_structure_matches_header(header, c_name, structure):
    declared = struct_fields(header_text(header), c_name)
    for ctype, name in declared:
        assert ctype in C_TYPES, f"{c_name}.{name}: C type {ctype!r} has no ctypes mapping here"
    expected = [(name, C_TYPES[ctype]) for ctype, name in declared]
    assert python_fields(structure) == expected, (
        f"{structure.__name__} does not mirror {c_name}: header {declared}, "
        f"Python {structure._fields_}")


@pytest.mark.parametrize("header, c_name, callback", [
    ("hcimpact.h", "hcimpact_law_fn", _types.LawFunction),
    ("hcimpact_cvode.h", "hcimpact_chain_poll", _types.ChainPoll),
])
def test_callbacks_match_header(header, c_name, callback):
    text = header_text(header)
    match = re.search(r"typedef\s+(\w+)\s*\(\s*\*\s*" + c_name + r"\s*\)\s*\(([^)]*)\)\s*;",
                      text)
    assert match, f"typedef ... (*{c_name})(...); not found in the header"
    result = match.group(1)
    arguments = []
    for argument in match.group(2).split(","):
        named = re.fullmatch(r"\s*(.*[\s*])\s*[A-Za-z_]\w*\s*", argument)  # drop the name
        ctype = named.group(1) if named else argument
        arguments.append(re.sub(r"\s*\*\s*", "*", ctype.strip()))
    assert C_TYPES[result] is callback._restype_
    assert [C_TYPES[a] for a in arguments] == list(callback._argtypes_)


def test_result_fields_follow_the_outcome():
    assert tuple(f.name for f in dataclasses.fields(_types.ImpactResult)) == _types.OUTCOME_FIELDS
    assert tuple(name for name, _ in _types.Outcome._fields_) == _types.OUTCOME_FIELDS
    assert tuple(name for name, _ in _types.Contact._fields_) == _types.CONTACT_FIELDS


def test_contact_records_follow_the_header():
    """The structured array of hcimpact.chain has the C record's layout: NumPy's view of
    the mirrored structure (offsets and size included) is what the library writes."""
    from hcimpact import _chain
    dtype = _chain.CONTACT_DTYPE
    declared = struct_fields(header_text("hcimpact_cvode.h"), "hcimpact_chain_contact")
    assert list(dtype.names) == [name for _, name in declared]
    assert dtype.itemsize == ctypes.sizeof(_types.ChainContact)
    for name, _ in _types.ChainContact._fields_:
        assert dtype.fields[name][1] == getattr(_types.ChainContact, name).offset
    outcome = [name for name, _ in _types.ChainOutcome._fields_]
    assert outcome[8:17] == list(_types.CHAIN_COUNTS)


def test_the_parser_sees_a_changed_header():
    """The check itself: each kind of change to the outcome is a difference."""
    text = header_text()
    base = struct_fields(text, "hcimpact_outcome")
    block = re.search(r"typedef\s+struct\s*\{([^}]*)\}\s*hcimpact_outcome\s*;", text)
    body = block.group(1)
    changes = {
        "added": body + " double extra_field;",
        "removed": body.replace("double contact_time;", ""),
        "retyped": body.replace("double contact_time;", "float contact_time;"),
        "reordered": body.replace("double restitution;", "").replace(
            "double contact_time;", "double contact_time; double restitution;"),
    }
    for kind, changed in changes.items():
        altered = text.replace(body, changed)
        assert struct_fields(altered, "hcimpact_outcome") != base, kind
