#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The default scene's console table against MODEL.md, to the digits printed.

    python3 check_default_table.py path/to/hcimpact

Runs `hcimpact --no-files` (the built-in default scene: the seed's steel ball) and
checks every printed value of k, x_max, F_max, t_contact and t_compression against
MODEL.md's table (values to 16-17 digits, computed independently at 50 digits): the
printed decimal must be MODEL.md's value rounded to the printed digits, i.e. differ by
at most half a unit of the last printed digit. Then runs it again with -o and checks
summary.csv (17 digits) to within 4 ulps.
"""
import csv
import math
import os
import subprocess
import sys
import tempfile
from decimal import Decimal

# MODEL.md: V, k, x_max (m), F_max (N), t_contact (s), t_compression (s)
MODEL = [
    ("0.5", "0.9677385785309325", "1.9893579643308693e-5", "1521.9160892838993",
     "1.1904584326151915e-4", "5.8859751374268991e-5"),
    ("1", "0.93747557994990506", "3.4204625278143626e-5", "3441.1122331638547",
     "1.0399469349496538e-4", "5.0856853135224197e-5"),
    ("2", "0.88218998624730638", "5.8156728355576902e-5", "7709.8673680931372",
     "9.1181013535146273e-5", "4.3649774771233254e-5"),
    ("3", "0.83286979226560167", "7.8679668816420547e-5", "12322.929545918441",
     "8.4701327451018694e-5", "3.9721750506275539e-5"),
    ("4", "0.78853912590706515", "9.7008052543829528e-5", "17199.324205797322",
     "8.0573545729318647e-5", "3.7040161639485758e-5"),
    ("5", "0.74843493159743416", "1.1372585556115339e-4", "22315.267380743067",
     "7.7655384043269703e-5", "3.5014163526885175e-5"),
]


def last_digit_unit(text):
    """Value of one unit in the last printed digit of a decimal number."""
    mantissa, _, exponent = text.upper().partition("E")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return Decimal(1).scaleb(-decimals + (int(exponent) if exponent else 0))


def check(name, printed, reference, failures):
    unit = last_digit_unit(printed)
    diff = abs(Decimal(printed) - Decimal(reference))
    ok = diff <= unit / 2
    digits = len(printed.upper().split("E")[0].replace("-", "").replace(".", "").lstrip("0"))
    print(f"  {name:14s} printed {printed:>20s}  MODEL.md {reference:>24s}  "
          f"{'ok' if ok else 'DIFFERS'} ({digits} digits)")
    if not ok:
        failures.append(f"{name}: printed {printed}, MODEL.md {reference}")


def table_rows(text, header_word):
    """The rows (lists of fields) of the console table whose header holds header_word."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.split()[:1] == ["V"] and header_word in line:
            rows = []
            for row in lines[i + 1:]:
                fields = row.split()
                if not fields:
                    break
                rows.append(fields)
            return rows
    raise SystemExit(f"no table with '{header_word}' in the output:\n{text}")


def main():
    program = sys.argv[1]
    run = subprocess.run([program, "--no-files"], capture_output=True, text=True)
    print(run.stdout)
    if run.returncode != 0:
        print(run.stderr, file=sys.stderr)
        raise SystemExit(f"hcimpact exited with {run.returncode}")
    outcome = table_rows(run.stdout, "k")
    contact = table_rows(run.stdout, "x_max")
    if len(outcome) != len(MODEL) or len(contact) != len(MODEL):
        raise SystemExit(f"expected {len(MODEL)} rows in each table")
    failures = []
    for ref, row1, row2 in zip(MODEL, outcome, contact):
        v, k, xmax, fmax, tc, tcomp = ref
        if Decimal(row1[0]) != Decimal(v) or Decimal(row2[0]) != Decimal(v):
            failures.append(f"speed {row1[0]} / {row2[0]} where MODEL.md has {v}")
            continue
        print(f"V = {v} m/s")
        check("k", row1[1], k, failures)
        check("x_max", row2[1], xmax, failures)
        check("F_max", row2[2], fmax, failures)
        check("t_compression", row2[4], tcomp, failures)
        check("t_contact", row2[5], tc, failures)

    # the CSV keeps 17 digits: within 4 ulps of MODEL.md
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "results")
        run = subprocess.run([program, "-q", "-o", out], capture_output=True, text=True)
        if run.returncode != 0:
            raise SystemExit(f"hcimpact -o exited with {run.returncode}: {run.stderr}")
        with open(os.path.join(out, "summary.csv"), newline="") as handle:
            rows = list(csv.DictReader(handle))
    worst = 0.0
    columns = ("restitution [-]", "max_compression [m]", "peak_force [N]",
               "contact_time [s]", "compression_time [s]")
    for ref, row in zip(MODEL, rows):
        for column, value in zip(columns, ref[1:2] + ref[2:4] + ref[4:6]):
            actual = float(row[column])
            expected = float(value)
            ulps = abs(actual - expected) / math.ulp(expected)
            worst = max(worst, ulps)
            if ulps > 4:
                failures.append(f"summary.csv {column} at V = {ref[0]}: {actual!r} is "
                                f"{ulps:.1f} ulps from MODEL.md {value}")
    print(f"summary.csv: largest difference from MODEL.md {worst:.2f} ulps")

    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        return 1
    print("PASS: the default scene's table matches MODEL.md to the digits printed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
