# SPDX-License-Identifier: Apache-2.0
"""A sweep of every bead's mass at once (&system_sweep mass_body = 0) obeys the
scaling of Hertz's law: with c, n = 3/2 and the striker's speed V kept, the only time
scale is T = (m / (c sqrt(V)))^(2/5), so the run's end time goes as m^(2/5) and every
final velocity is the same for all masses.

    python3 check_mass_scaling.py HCIMPACT SCENE OUT_DIR

SCENE is example/scenes/struck_chain_masses.nml (elastic touching beads, rtol 1e-10).
The bounds are those of the integration, not of the law (which is exact): end times
within 1e-5 of the ratio, final velocities within 1e-8 m/s of the first run's. A sweep
that gave the mass to body 1 alone breaks both by far more.
"""
import csv
import os
import subprocess
import sys


def main():
    program, scene, out = sys.argv[1], sys.argv[2], sys.argv[3]
    proc = subprocess.run([program, scene, "-o", out, "-q"], capture_output=True, text=True)
    if proc.returncode != 0:
        print(f"the scene failed ({proc.returncode}):\n{proc.stdout}{proc.stderr}")
        return 1
    with open(os.path.join(out, "system_sweep.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    n = sum(1 for key in rows[0] if key.startswith("velocity_"))
    if len(rows) < 2 or n < 3 or "mass_all [kg]" not in rows[0]:
        print(f"expected a sweep of every body's mass over 3 bodies or more: {len(rows)} "
              f"rows, columns {list(rows[0])}")
        return 1
    first = rows[0]
    m1, t1 = float(first["mass_all [kg]"]), float(first["time [s]"])
    v1 = [float(first[f"velocity_{i} [m/s]"]) for i in range(1, n + 1)]
    failures = 0
    worst_time = worst_velocity = 0.0
    for row in rows:
        m, t = float(row["mass_all [kg]"]), float(row["time [s]"])
        ratio = (m / m1) ** 0.4
        time_error = abs(t / t1 / ratio - 1.0)
        v = [float(row[f"velocity_{i} [m/s]"]) for i in range(1, n + 1)]
        velocity_error = max(abs(a - b) for a, b in zip(v, v1))
        worst_time = max(worst_time, time_error)
        worst_velocity = max(worst_velocity, velocity_error)
        ok = int(float(row["status [-]"])) == 0 and time_error <= 1e-5 \
            and velocity_error <= 1e-8
        if not ok:
            failures += 1
            print(f"mass {m}: status {row['status [-]']}, end time {t} s is {t / t1:.9f} of "
                  f"the first, expected {ratio:.9f}; velocities differ by up to "
                  f"{velocity_error:.3g} m/s")
    print(f"{len(rows)} masses: end times within {worst_time:.2g} of (m/m1)^(2/5), final "
          f"velocities within {worst_velocity:.2g} m/s")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
