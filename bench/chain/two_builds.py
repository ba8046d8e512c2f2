# SPDX-License-Identifier: Apache-2.0
"""Two builds of the library side by side on the struck chain (a change's effect).

    python3 bench/chain/two_builds.py OLD_BENCH NEW_BENCH [--rounds R] [--rtol R]
        [--cases N:T,N:T,...] [--integrators adams,bdf] [--min-seconds S]

OLD_BENCH and NEW_BENCH are two `bench_chain` programs (each linked to its own build's
shared libraries, as `bench/chain/run.sh` builds them). In every round each case runs
once with each program, in an order that alternates from round to round, so that
what the machine does meanwhile falls on both alike; `bench_chain struck` reports the
CPU time of its thread per call (calls repeated until --min-seconds). Printed per case:
the steps of each build, and the median over the rounds of the old build's time over
the new one's (> 1: the new build is faster) with the smallest and largest ratio.
"""
import argparse
import csv
import io
import statistics
import subprocess
import sys


def run(bench, n, t_end, rtol, integrator, min_seconds):
    out = subprocess.run([bench, "struck", "--n", str(n), "--t-end", repr(t_end), "--rtols",
                          repr(rtol), "--integrator", integrator, "--min-seconds",
                          repr(min_seconds)], capture_output=True, text=True, check=True)
    rows = list(csv.DictReader(io.StringIO(out.stdout)))
    if len(rows) != 1 or int(rows[0]["status"]) != 0:
        sys.exit(f"two_builds.py: {bench} failed on n = {n}: {out.stdout}{out.stderr}")
    return float(rows[0]["seconds"]), int(rows[0]["steps"]), float(rows[0]["energy_error"])


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--rtol", type=float, default=1e-8)
    ap.add_argument("--cases", default="100:1e-3,1000:1e-3,10000:1e-2")
    ap.add_argument("--integrators", default="adams,bdf")
    ap.add_argument("--min-seconds", type=float, default=0.3)
    a = ap.parse_args()
    cases = [(int(c.split(":")[0]), float(c.split(":")[1])) for c in a.cases.split(",")]
    integrators = a.integrators.split(",")
    ratios = {}
    info = {}
    for r in range(a.rounds):
        for n, t_end in cases:
            for integ in integrators:
                key = (n, t_end, integ)
                order = [("old", a.old), ("new", a.new)]
                if r % 2:
                    order.reverse()
                got = {}
                for name, bench in order:
                    got[name] = run(bench, n, t_end, a.rtol, integ, a.min_seconds)
                ratios.setdefault(key, []).append(got["old"][0] / got["new"][0])
                info[key] = (got["old"][1], got["new"][1], got["old"][2], got["new"][2])
    print(f"rtol {a.rtol:g}, {a.rounds} rounds; ratio = old time / new time")
    print("n,t_end,integrator,steps_old,steps_new,energy_error_old,energy_error_new,"
          "ratio_median,ratio_min,ratio_max")
    for key, rs in ratios.items():
        n, t_end, integ = key
        so, sn, eo, en = info[key]
        print(f"{n},{t_end:g},{integ},{so},{sn},{eo:.2e},{en:.2e},{statistics.median(rs):.3f},"
              f"{min(rs):.3f},{max(rs):.3f}")


if __name__ == "__main__":
    main()
