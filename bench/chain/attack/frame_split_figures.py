# SPDX-License-Identifier: Apache-2.0
"""The figures of doc/chains.md on settling at a far end time and on a ball bouncing on a
stack (26 November, the region's own frame and the region split).

Run from this directory after `. ./env.sh`:  python3 frame_split_figures.py
Prints, for each system settled to t_end = 1e300, the steps, the CPU time and the rest
position; and for a ball of 10 g dropped 0.1 mm onto a stack of three on a floor
(elastic, to 0.3 s) at rtol 1e-8, 1e-10 and 1e-12, the energy error, the regions begun
(`clusters`), the steps and the CPU time.
"""
import time

import hcimpact

SETTLE = [
    ("two balls of 0.1 kg dropped 1 mm", dict(
        masses=[0.1, 0.1], velocities=[0.0, 0.0], gaps=[0.0], stiffness=1e9, damping=1.0,
        gravity=-9.81, wall_left=dict(stiffness=1e9, damping=1.0, gap=1e-3)), 1e-10),
    ("one ball dropped 10 m", dict(
        masses=[0.1], velocities=[0.0], gravity=-9.81,
        wall_left=dict(stiffness=1e9, damping=1.0, gap=10.0)), 1e-10),
    ("one ball dropped 1 m", dict(
        masses=[0.1], velocities=[0.0], gravity=-9.81,
        wall_left=dict(stiffness=1e9, damping=1.0, gap=1.0)), 1e-12),
]


def main():
    for name, kw, rtol in SETTLE:
        t0 = time.process_time()
        r = hcimpact.chain(**kw, rtol=rtol, t_end=1e300)
        print(f"{name}, rtol {rtol:g}, t_end 1e300: {r.counters['steps']} steps, "
              f"{time.process_time() - t0:.2f} s, positions {r.positions}")
    for rtol in (1e-8, 1e-10, 1e-12):
        t0 = time.process_time()
        r = hcimpact.chain([0.1, 0.1, 0.1, 0.01], [0.0] * 4, gaps=[0.0, 0.0, 1e-4],
                           stiffness=1e9, damping=0.0, gravity=-9.81,
                           wall_left=dict(stiffness=1e9, damping=0.0, gap=0.0), t_end=0.3,
                           rtol=rtol)
        print(f"ball on a stack, rtol {rtol:g}: energy error {r.energy_error:.2e}, "
              f"{r.counters['clusters']} regions, {r.counters['steps']} steps, "
              f"{time.process_time() - t0:.2f} s")


if __name__ == "__main__":
    main()
