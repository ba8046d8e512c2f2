#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Compare the outcomes of hcimpact_impact of two shared libraries bit for bit.

A change meant to make one impact cheaper should give the same answers: this calls
hcimpact_impact of both libraries (ctypes, the C API) on every row of the impact
reference tables (test/reference/impact*.csv, the exact double inputs) and on random
contacts (the distribution of bench_one_impact: m, c, V log-uniform over three decades,
n log-uniform in [0.5, 3] with a quarter exactly 1.5, beta = b V log-uniform in the
range asked for), counts the outputs whose bits differ, and for the reference rows
prints the largest error of each library against the mpmath references, in ulps.

The same set-up serves the time law and the velocity at a depth: for the first
`--time-law K` random contacts (default 2,000) it also compares, bit for bit,
hcimpact_time_law_samples on 17 times and hcimpact_velocity_at_depth at 0.1, 0.5 and
0.9 x_max on both branches.

Usage: compare_outcomes.py [--count N] [--time-law K] [--seed S] [--beta LO HI]
                           OLD_LIB NEW_LIB
Exit status 0 whether or not outcomes differ (it reports; it does not judge).
"""
import argparse
import ctypes
import math
import os
import random
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TABLES = ["impact.csv", "impact_whole.csv", "impact_extremes.csv"]
# hcimpact_outcome's fields, in the order of include/hcimpact.h
FIELDS = ["restitution", "energy_loss_ratio", "rebound_velocity", "max_compression",
          "peak_force", "compression_at_peak_force", "time_at_peak_force",
          "compression_time", "contact_time"]
# the reference columns (hi, lo) of the tables and the outcome field of each
REFERENCE = [("x_max", "max_compression"), ("peak_force", "peak_force"),
             ("compression_at_peak", "compression_at_peak_force"),
             ("time_at_peak", "time_at_peak_force"),
             ("compression_time", "compression_time"), ("contact_time", "contact_time"),
             ("restitution", "restitution")]


class Contact(ctypes.Structure):
    _fields_ = [("mass", ctypes.c_double), ("stiffness", ctypes.c_double),
                ("exponent", ctypes.c_double), ("damping", ctypes.c_double),
                ("velocity", ctypes.c_double)]


class Outcome(ctypes.Structure):
    _fields_ = [(name, ctypes.c_double) for name in FIELDS]


def load(path):
    lib = ctypes.CDLL(os.path.abspath(path), mode=ctypes.RTLD_LOCAL)
    lib.hcimpact_impact.argtypes = [ctypes.POINTER(Contact), ctypes.POINTER(Outcome)]
    lib.hcimpact_impact.restype = ctypes.c_int
    arrays = [ctypes.POINTER(ctypes.c_double)] * 4
    lib.hcimpact_time_law_samples.argtypes = [ctypes.POINTER(Contact), ctypes.c_int] + arrays
    lib.hcimpact_time_law_samples.restype = ctypes.c_int
    lib.hcimpact_velocity_at_depth.argtypes = [ctypes.POINTER(Contact), ctypes.c_double,
                                               ctypes.c_int, ctypes.POINTER(ctypes.c_double)]
    lib.hcimpact_velocity_at_depth.restype = ctypes.c_int
    return lib


SAMPLES = 17


def motion(lib, m, c, n, b, v, x_max):
    """The time law on SAMPLES times and the velocity at three depths on both branches:
    the statuses and every value, in one list"""
    contact = Contact(m, c, n, b, v)
    buffers = [(ctypes.c_double * SAMPLES)() for _ in range(4)]
    values = [lib.hcimpact_time_law_samples(ctypes.byref(contact), SAMPLES, *buffers)]
    for buf in buffers:
        values.extend(buf)
    speed = ctypes.c_double()
    for share in (0.1, 0.5, 0.9):
        for branch in (1, 2):
            values.append(lib.hcimpact_velocity_at_depth(ctypes.byref(contact),
                                                         share * x_max, branch,
                                                         ctypes.byref(speed)))
            values.append(speed.value)
    return values


def impact(lib, m, c, n, b, v):
    contact = Contact(m, c, n, b, v)
    out = Outcome()
    stat = lib.hcimpact_impact(ctypes.byref(contact), ctypes.byref(out))
    return stat, [getattr(out, name) for name in FIELDS]


def bits(x):
    return ctypes.c_uint64.from_buffer(ctypes.c_double(x)).value


def ulp_error(x, hi, lo):
    """|x - (hi + lo)| in ulps of the reference (the spacing of doubles at hi)"""
    if math.isnan(x):
        return math.inf
    return abs((x - hi) - lo) / math.ulp(hi) if hi != 0.0 else abs(x)


def read_table(name):
    rows = []
    with open(os.path.join(ROOT, "test", "reference", name)) as f:
        header = None
        for line in f:
            if line.startswith("#"):
                continue
            cells = line.strip().split(",")
            if header is None:
                header = cells
                continue
            rows.append(dict(zip(header, (float(x) for x in cells))))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--count", type=int, default=100000)
    parser.add_argument("--time-law", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=20261126)
    parser.add_argument("--beta", type=float, nargs=2, default=[1e-3, 100.0])
    parser.add_argument("old")
    parser.add_argument("new")
    args = parser.parse_args()
    libs = [load(args.old), load(args.new)]

    print("| reference table | rows | outcomes differing | "
          + " | ".join(f"{f} max ulp (old, new)" for _, f in REFERENCE) + " |")
    print("|---|---:|---:|" + "---|" * len(REFERENCE))
    for name in TABLES:
        rows = read_table(name)
        differing = 0
        worst = [[0.0, 0.0] for _ in REFERENCE]
        for r in rows:
            results = [impact(lib, r["m"], r["c"], r["n"], r["b"], r["V"]) for lib in libs]
            if results[0][0] != results[1][0] or any(
                    bits(x) != bits(y) for x, y in zip(results[0][1], results[1][1])):
                differing += 1
            for side, (stat, values) in enumerate(results):
                if stat != 0:
                    continue
                for j, (column, field) in enumerate(REFERENCE):
                    e = ulp_error(values[FIELDS.index(field)], r[column + "_hi"],
                                  r[column + "_lo"])
                    worst[j][side] = max(worst[j][side], e)
        print(f"| {name} | {len(rows)} | {differing} | "
              + " | ".join(f"{a:.3f}, {b:.3f}" for a, b in worst) + " |")

    rng = random.Random(args.seed)

    def log_uniform(lo, hi):
        return lo * (hi / lo) ** rng.random()

    differing = 0
    motions_differing = 0
    fields = [0] * len(FIELDS)
    lo, hi = args.beta
    for i in range(args.count):
        m = log_uniform(1e-3, 1.0)
        c = log_uniform(1e8, 1e11)
        n = 1.5 if i % 4 == 0 else log_uniform(0.5, 3.0)
        v = log_uniform(0.1, 100.0)
        b = log_uniform(lo, hi) / v
        results = [impact(lib, m, c, n, b, v) for lib in libs]
        diff = [bits(x) != bits(y) for x, y in zip(results[0][1], results[1][1])]
        if results[0][0] != results[1][0] or any(diff):
            differing += 1
            for j, d in enumerate(diff):
                fields[j] += d
        if i < args.time_law and results[0][0] == 0:
            x_max = results[0][1][FIELDS.index("max_compression")]
            old, new = (motion(lib, m, c, n, b, v, x_max) for lib in libs)
            if any(bits(float(x)) != bits(float(y)) for x, y in zip(old, new)):
                motions_differing += 1
    print()
    print(f"random contacts (seed {args.seed}, beta log-uniform in [{lo:g}, {hi:g}]): "
          f"{args.count}, outcomes differing: {differing}")
    if differing:
        print("differing per output: " + ", ".join(
            f"{name} {k}" for name, k in zip(FIELDS, fields) if k))
    print(f"time law ({SAMPLES} samples) and velocity at 3 depths on both branches, the "
          f"first {min(args.time_law, args.count)} contacts: {motions_differing} differing")
    return 0


if __name__ == "__main__":
    sys.exit(main())
