# SPDX-License-Identifier: Apache-2.0
"""Every row of a sweep of systems (the output system_sweep) is the run of the system
with that row's values put into &bodies by hand.

    python3 check_system_sweep.py HCIMPACT OUT_DIR

For each sweep below the script writes a scene with a &system_sweep group, runs it,
and checks system_sweep.csv: its rows come in the order of the lists' product (the
first list varying slowest) or side by side (combine = "list"), every parameter column
holds the row's value (nan where the sweep does not vary it), and every row's final
velocities and status are, to the last bit, those of a scene of its own in which the
row's values stand in &bodies (some bodies' velocities, some bodies' masses, every pair's gap,
stiffness, exponent and b, or the restitution at its speed, gravity, the end time)
and the walls' groups (their gaps, b, c and n), run for the output `final`. The varied
scene goes through the sweep's code (the lists, the substitution, the restitution's
damping); the scene of its own through the reader of &bodies alone.
"""
import csv
import itertools
import math
import os
import subprocess
import sys

NAMES = ["striker_speed", "mass", "gap", "stiffness", "exponent", "b", "restitution",
         "gravity", "left_gap", "right_gap", "left_b", "right_b", "left_stiffness",
         "right_stiffness", "left_exponent", "right_exponent", "t_end"]
UNITS = ["m/s", "kg", "m", "N/m^n", "-", "s/m", "-", "m/s^2", "m", "m", "s/m", "s/m",
         "N/m^n", "N/m^n", "-", "-", "s"]

# three balls falling onto a wall (the left one nearest), a cluster and isolated
# contacts alike
BASE = {"mass": [0.2, 0.1, 0.05], "velocity": [-1.0, -1.5, -2.0], "gap": 1e-3,
        "stiffness": 1e8, "exponent": 1.5, "b": 0.05, "gravity": -9.81,
        "t_end": 0.01, "left_gap": 2e-3, "left_b": 0.1, "right_b": 0.1,
        "left_stiffness": 1e9, "right_stiffness": 1e9, "left_exponent": 1.5,
        "right_exponent": 1.5}

SWEEPS = [
    # name, lists (in NAMES' order), combine, the bodies the sweep names (mass_body,
    # striker_body), what &bodies has besides BASE
    ("product", {"striker_speed": [-0.5, -3.0], "mass": [0.3, 0.02], "gap": [0.0, 5e-4],
                 "stiffness": [1e7, 3e8], "exponent": [1.5, 1.25], "b": [0.0, 0.3],
                 "gravity": [-9.81, -1.62]}, "product", {"mass_body": 3}, {}),
    ("restitution", {"striker_speed": [-0.5, -1.0, -2.0], "restitution": [0.95, 0.6, 0.3]},
     "list", {}, {}),
    ("mass-first", {"mass": [0.5, 1e-3], "gravity": [0.0, -30.0]}, "product", {}, {}),
    # &bodies' own restitution: its speed is the sweep's at_speed, not given there
    ("restitution-default-speed", {"restitution": [0.9, 0.4], "gap": [0.0, 1e-4]}, "product",
     {}, {"restitution": 0.7}),
    # the walls' gaps: the drop height onto the left wall, and a right wall the bodies
    # reach after their bounce or not
    ("walls", {"left_gap": [0.0, 1e-3, 2e-2], "right_gap": [0.0, 4e-3]}, "product", {},
     {"right_gap": 1e-2, "velocity": [-1.0, -1.5, 1.0]}),
    # the middle body's speed, the walls' damping (elastic or not) and the end time
    # (before, between and after the contacts with the walls)
    ("walls-damping-time", {"striker_speed": [-0.5, 2.0], "left_b": [0.0, 0.4],
                            "right_b": [0.0, 0.2], "t_end": [2e-3, 6e-3, 0.03]},
     "product", {"striker_body": 2}, {"right_gap": 1e-2, "velocity": [-1.0, -1.5, 1.0]}),
    # the walls' contact constants and exponents, side by side
    ("walls-laws", {"left_stiffness": [1e8, 3e9, 1e10], "right_stiffness": [5e8, 2e9, 4e9],
                    "left_exponent": [1.5, 1.25, 1.4], "right_exponent": [1.1, 1.5, 1.3]},
     "list", {}, {"right_gap": 1e-2, "velocity": [-1.0, -1.5, 1.0]}),
    # every body's mass (0: all of them) and two bodies' speeds, each the row's value
    ("several-bodies", {"striker_speed": [-0.5, 1.5], "mass": [0.3, 0.02, 0.1]}, "product",
     {"mass_body": 0, "striker_body": [3, 2]}, {}),
    # a run of bodies (column mass_1-2) and the striker's speed to bodies 3 and 1
    ("bodies-run", {"striker_speed": [-0.5], "mass": [0.3, 0.02]}, "product",
     {"mass_body": [1, 2], "striker_body": [3, 1]}, {}),
]
AT_SPEED = 0.7


def fmt(x):
    return repr(float(x))


def scene_text(title, bodies, sweep=None, combine=None, chosen=None, outputs="final"):
    text = f'&scene title = "{title}", outputs = "{outputs}" /\n&bodies\n'
    text += "  mass = " + ", ".join(fmt(m) for m in bodies["mass"]) + "\n"
    text += "  velocity = " + ", ".join(fmt(v) for v in bodies["velocity"]) + "\n"
    text += f"  gap = {fmt(bodies['gap'])}, stiffness = {fmt(bodies['stiffness'])}\n"
    text += f"  exponent = {fmt(bodies['exponent'])}\n"
    if "restitution" in bodies:
        text += f"  restitution = {fmt(bodies['restitution'])}, at_speed = {fmt(AT_SPEED)}\n"
    else:
        text += f"  b = {fmt(bodies['b'])}\n"
    text += f"  gravity = {fmt(bodies['gravity'])}, t_end = {fmt(bodies['t_end'])}\n/\n"
    text += (f"&left_wall stiffness = {fmt(bodies['left_stiffness'])}, "
             f"exponent = {fmt(bodies['left_exponent'])}, b = {fmt(bodies['left_b'])}, "
             f"gap = {fmt(bodies['left_gap'])} /\n")
    if "right_gap" in bodies:
        text += (f"&right_wall stiffness = {fmt(bodies['right_stiffness'])}, "
                 f"exponent = {fmt(bodies['right_exponent'])}, b = {fmt(bodies['right_b'])}, "
                 f"gap = {fmt(bodies['right_gap'])} /\n")
    if sweep:
        text += "&system_sweep\n"
        for name, values in sweep.items():
            text += f"  {name} = " + ", ".join(fmt(v) for v in values) + "\n"
        if "restitution" in sweep and "restitution" not in bodies:
            text += f"  at_speed = {fmt(AT_SPEED)}\n"
        for which, body in (chosen or {}).items():
            text += f"  {which} = " + ", ".join(str(b) for b in bodies_list(body)) + "\n"
        text += f'  combine = "{combine}"\n/\n'
    return text


def bodies_list(body):
    """mass_body or striker_body as the scene gives it: an index or a list of them"""
    return body if isinstance(body, list) else [body]


def chosen_bodies(body, n):
    """The bodies (from 1) a list goes to: 0 alone is every one of n"""
    bodies = bodies_list(body)
    return list(range(1, n + 1)) if bodies == [0] else bodies


def column_label(bodies, n):
    """How the sweep's column names the bodies: "all", or their indices in their order
    joined by _, a run of consecutive ones as first-last, or "<count>_bodies" where that
    is longer than 24 characters"""
    if n > 1 and len(bodies) == n:
        return "all"
    runs = []
    for b in bodies:
        if runs and b == runs[-1][1] + 1:
            runs[-1][1] = b
        else:
            runs.append([b, b])
    label = "_".join(str(a) if a == b else f"{a}-{b}" for a, b in runs)
    return label if len(label) <= 24 else f"{len(bodies)}_bodies"


def run(program, path, out):
    proc = subprocess.run([program, path, "-o", out, "-q"], capture_output=True, text=True)
    return proc.returncode, proc.stdout + proc.stderr


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def expected_rows(sweep, combine):
    names = [n for n in NAMES if n in sweep]
    if combine == "product":
        combos = itertools.product(*(sweep[n] for n in names))
    else:
        combos = zip(*(sweep[n] for n in names))
    return [dict(zip(names, c)) for c in combos]


def same_number(text, value):
    if value is None:
        return text == "nan"
    return float(text) == value


def main():
    program, out_dir = sys.argv[1], sys.argv[2]
    os.makedirs(out_dir, exist_ok=True)
    failures = 0
    rows_checked = 0
    for name, sweep, combine, chosen, extra in SWEEPS:
        base = dict(BASE, **extra)
        n_bodies = len(base["mass"])
        mass_bodies = chosen_bodies(chosen.get("mass_body", 1), n_bodies)
        striker_bodies = chosen_bodies(chosen.get("striker_body", 1), n_bodies)
        path = os.path.join(out_dir, f"{name}.nml")
        with open(path, "w") as f:
            f.write(scene_text(name, base, sweep, combine, chosen, "system_sweep"))
        rc, log = run(program, path, os.path.join(out_dir, name))
        if rc != 0:
            print(f"{name}: the sweep failed ({rc}):\n{log}")
            return 1
        rows = read_csv(os.path.join(out_dir, name, "system_sweep.csv"))
        wanted = expected_rows(sweep, combine)
        if len(rows) != len(wanted):
            print(f"{name}: {len(rows)} rows, expected {len(wanted)}")
            return 1
        for k, (row, values) in enumerate(zip(rows, wanted), start=1):
            problems = []
            if int(float(row["variation [-]"])) != k:
                problems.append(f"variation {row['variation [-]']}")
            for n, unit in zip(NAMES, UNITS):
                column = n
                if n == "mass":
                    column = f"mass_{column_label(mass_bodies, n_bodies)}"
                elif n == "striker_speed" and striker_bodies != [1]:
                    column = f"striker_speed_{column_label(striker_bodies, n_bodies)}"
                if not same_number(row[f"{column} [{unit}]"], values.get(n)):
                    problems.append(f"{n} = {row[f'{column} [{unit}]']}, expected {values.get(n)}")
            bodies = dict(base, mass=list(base["mass"]), velocity=list(base["velocity"]))
            for n, v in values.items():
                if n == "striker_speed":
                    for i in striker_bodies:
                        bodies["velocity"][i - 1] = v
                elif n == "mass":
                    for i in mass_bodies:
                        bodies["mass"][i - 1] = v
                else:
                    bodies[n] = v
            one = os.path.join(out_dir, f"{name}-{k}")
            with open(one + ".nml", "w") as f:
                f.write(scene_text(f"{name} {k}", bodies))
            rc, log = run(program, one + ".nml", one)
            status = int(float(row["status [-]"]))
            if rc != 0 or status != 0:
                problems.append(f"status {status} in the sweep, exit {rc} alone: {log}")
            else:
                final = read_csv(os.path.join(one, "final.csv"))
                for i, body in enumerate(final, start=1):
                    got = row[f"velocity_{i} [m/s]"]
                    if got != body["velocity [m/s]"]:
                        problems.append(f"velocity_{i} = {got}, alone {body['velocity [m/s]']}")
            rows_checked += 1
            if problems:
                failures += 1
                print(f"{name} row {k} {values}: " + "; ".join(problems))
    print(f"{rows_checked} rows checked, {failures} wrong")
    return 1 if failures or rows_checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
