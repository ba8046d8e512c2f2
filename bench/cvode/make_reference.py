#!/usr/bin/env python3
"""Reference values (mpmath, 50 digits) for the contacts of the CVODE benchmark.

Writes bench/cvode/reference.csv in the format of test/reference/impact.csv (see
test/reference/IMPACT.md): one row per contact, every output as a hi,lo pair of
doubles. The values come from test/reference/make_impact.py's compute_case, which
computes each case by two independent methods and aborts when they disagree beyond
1e-25.

Contacts (doc/cvode.md):
  the seed's steel ball, m = 0.1 kg, c = 1.7135e10 N/m^1.5, n = 1.5, b = 0.1 s/m,
  at V = 0.5, 1, 2, 3, 4, 5 m/s; then n = 1, 1.5, 2 x beta = 1e-6, 1e-2, 1, 100,
  1e4 with the same m and c, V = 1 m/s and b = beta (s/m).

Usage: python3 bench/cvode/make_reference.py   (about a minute on 2 processes)
"""
import multiprocessing
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "test", "reference"))
import make_impact  # noqa: E402  (the project's reference generator)


def bench_cases():
    cases = []
    for v in (0.5, 1.0, 2.0, 3.0, 4.0, 5.0):
        cases.append({"m": 0.1, "c": 1.7135e10, "n": 1.5, "V": v, "b": 0.1})
    for n in (1.0, 1.5, 2.0):
        for beta in (1e-6, 1e-2, 1.0, 100.0, 1e4):
            cases.append({"m": 0.1, "c": 1.7135e10, "n": n, "V": 1.0, "b": beta})
    return cases


def main():
    cases = bench_cases()
    jobs = [(i, case, False) for i, case in enumerate(cases)]
    with multiprocessing.Pool(2) as pool:
        results = sorted(pool.map(make_impact.compute_case, jobs, chunksize=1),
                         key=lambda out: out["idx"])
    header = ["m", "c", "n", "V", "b"]
    for key in make_impact.OUT_NAMES:
        header += [key + "_hi", key + "_lo"]
    path = os.path.join(HERE, "reference.csv")
    with open(path, "w") as fh:
        fh.write("# hcimpact CVODE benchmark: reference outcomes (test/reference/make_impact.py,"
                 " mpmath %s, %d digits); format of test/reference/impact.csv\n"
                 % (make_impact.M.__version__, make_impact.DPS_A))
        fh.write(",".join(header) + "\n")
        for out in results:
            fh.write(out["row"] + "\n")
    worst = max(out["worst"] for out in results)
    print("%s: %d contacts, methods A and B agree to %.2g" % (path, len(results), worst))


if __name__ == "__main__":
    main()
