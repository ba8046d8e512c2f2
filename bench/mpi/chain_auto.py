# SPDX-License-Identifier: Apache-2.0
"""The chain of example/scenes/mpi_chain.nml with method auto, for doc/mpi.md ("When the
MPI chain pays").

    python3 bench/mpi/chain_auto.py --n N --t-end T [--state STATE.csv] [--rtol R]

The beads of the example (4.084e-3 kg, Hertz constant 7.69e9 N/m^1.5, damping 0.05
s/m, touching, the first struck at 1 m/s) with `hcimpact.chain`, method auto: the
closed forms where contacts are isolated and CVODE only on the beads a contact has set
moving. Prints the CPU time of the call (one call: the time of a whole run, not a
benchmark's median) with what the library reports. With --state, a file of
`hcimpact_mpi_chain` (`bead,position,velocity`, with or without --serial) of the same
chain: the largest differences of the final positions and velocities from it.

Needs the Python package on a shared build (`. bench/chain/attack/env.sh`).
"""
import argparse
import csv
import sys
import time

import numpy as np

import hcimpact

MASS, STIFFNESS, DAMPING, STRIKER = 4.084e-3, 7.69e9, 0.05, 1.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, required=True)
    parser.add_argument("--t-end", type=float, required=True)
    parser.add_argument("--rtol", type=float, default=1e-8)
    parser.add_argument("--state")
    args = parser.parse_args()
    if args.n < 2:
        sys.exit("chain_auto.py: --n must be at least 2")

    velocities = np.zeros(args.n)
    velocities[0] = STRIKER
    start = time.process_time()
    result = hcimpact.chain(np.full(args.n, MASS), velocities, gaps=np.zeros(args.n - 1),
                            stiffness=STIFFNESS, exponent=1.5, damping=DAMPING,
                            t_end=args.t_end, rtol=args.rtol, method="auto")
    seconds = time.process_time() - start
    print(f"beads {args.n}, t_end {args.t_end:g} s, rtol {args.rtol:g}: {seconds:.3f} s CPU, "
          f"method used {result.method_used}, {len(result.contacts)} contacts, "
          f"energy error {result.energy_error:.2e}")
    if args.state:
        with open(args.state, newline="") as handle:
            rows = list(csv.DictReader(handle))
        if len(rows) != args.n:
            sys.exit(f"chain_auto.py: {args.state} has {len(rows)} beads, not {args.n}")
        positions = np.array([float(row["position"]) for row in rows])
        state_velocities = np.array([float(row["velocity"]) for row in rows])
        print(f"against {args.state}: positions within "
              f"{np.max(np.abs(positions - result.positions)):.2e} m, velocities within "
              f"{np.max(np.abs(state_velocities - result.velocities)):.2e} m/s")


if __name__ == "__main__":
    main()
