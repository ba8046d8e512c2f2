# SPDX-License-Identifier: Apache-2.0
"""Bad and extreme input to hcimpact.chain, each case in its own process under a
60 s timeout (a crash or a hang shows as such). Prints one line per case:
  RAISE <exception>: <message>   a clear refusal
  OK <summary>                   a result (check it is right!)
  CRASH rc / HANG                a defect
Usage: python3 attack_bad.py [substring-of-case-name]
"""
import subprocess
import sys

C = 1e9  # a stiffness, N/m^1.5
W = "{'stiffness': 1e9, 'gap': 0.01}"

CASES = {
    # non-finite anywhere
    "nan-mass": f"chain([1, float('nan')], [1, 0], gaps=[0.01], stiffness={C})",
    "inf-mass": f"chain([1, float('inf')], [1, 0], gaps=[0.01], stiffness={C})",
    "nan-velocity": f"chain([1, 1], [float('nan'), 0], gaps=[0.01], stiffness={C})",
    "inf-velocity": f"chain([1, 1], [float('inf'), 0], gaps=[0.01], stiffness={C})",
    "nan-gap": f"chain([1, 1], [1, 0], gaps=[float('nan')], stiffness={C})",
    "inf-gap": f"chain([1, 1], [1, 0], gaps=[float('inf')], stiffness={C})",
    "inf-gap-tend": f"chain([1, 1], [1, 0], gaps=[float('inf')], stiffness={C}, t_end=1)",
    "nan-stiffness": "chain([1, 1], [1, 0], gaps=[0.01], stiffness=float('nan'))",
    "inf-stiffness": "chain([1, 1], [1, 0], gaps=[0.01], stiffness=float('inf'))",
    "nan-exponent": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, exponent=float('nan'))",
    "nan-damping": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, damping=float('nan'))",
    "inf-damping": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, damping=float('inf'))",
    "nan-gravity": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, gravity=float('nan'))",
    "inf-gravity": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, gravity=float('inf'))",
    "nan-tend": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, t_end=float('nan'))",
    "inf-tend": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, t_end=float('inf'))",
    "nan-rtol": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, rtol=float('nan'))",
    "nan-wall-gap": "chain([1], [-1], wall_left={'stiffness': 1e9, 'gap': float('nan')})",
    "inf-wall-gap": "chain([1], [-1], wall_left={'stiffness': 1e9, 'gap': float('inf')})",
    "inf-wall-gap-tend": "chain([1], [-1], wall_left={'stiffness': 1e9, 'gap': float('inf')}, t_end=1)",
    "nan-wall-stiffness": "chain([1], [-1], wall_left={'stiffness': float('nan'), 'gap': 0.01})",
    "nan-sample": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, sample_times=[0, float('nan')])",
    "inf-sample": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, sample_times=[0, float('inf')])",
    # masses
    "zero-mass": f"chain([1, 0], [1, 0], gaps=[0.01], stiffness={C})",
    "negative-mass": f"chain([1, -1], [1, 0], gaps=[0.01], stiffness={C})",
    "subnormal-mass": f"chain([1, 5e-324], [1, 0], gaps=[0.01], stiffness={C})",
    "subnormal-masses-both": f"chain([5e-324, 5e-324], [1, 0], gaps=[0.01], stiffness={C})",
    "huge-mass": f"chain([1e308, 1], [1, 0], gaps=[0.01], stiffness={C})",
    "huge-masses-both": f"chain([1e308, 1e308], [1, 0], gaps=[0.01], stiffness={C})",
    "huge-masses-touching": f"chain([1e308, 1e308, 1e308], [1, 0, 0], gaps=[0.0, 0.0], stiffness={C})",
    # gaps
    "negative-gap": f"chain([1, 1], [1, 0], gaps=[-1e-9], stiffness={C})",
    "minus-zero-gap": f"chain([1, 1], [1, 0], gaps=[-0.0], stiffness={C})",
    "negative-wall-gap": "chain([1], [-1], wall_left={'stiffness': 1e9, 'gap': -1e-9})",
    "huge-gap": f"chain([1, 1], [1, 0], gaps=[1e300], stiffness={C})",
    "huge-gap-sum-overflow": f"chain([1, 1, 1], [1, 0, -1], gaps=[1.7e308, 1.7e308], stiffness={C})",
    "subnormal-gap": f"chain([1, 1], [1, 0], gaps=[5e-324], stiffness={C})",
    # sizes
    "n0": "chain([], [])",
    "n1-free": "chain([1], [1])",
    "n1-free-tend": "chain([1], [1], t_end=1)",
    "n1-gravity": "chain([1], [1], gravity=-9.81)",
    "n1-wall-ahead": "chain([1], [-1], wall_left={'stiffness': 1e9, 'gap': 0.01})",
    "n1-two-walls-elastic": "chain([1], [1], wall_left={'stiffness': 1e9, 'gap': 0.01}, wall_right={'stiffness': 1e9, 'gap': 0.01})",
    "n1-two-walls-elastic-maxevents": "chain([1], [1], wall_left={'stiffness': 1e9, 'gap': 0.01}, wall_right={'stiffness': 1e9, 'gap': 0.01}, max_events=1000)",
    "n1-two-walls-touching-rest": "chain([1], [0], wall_left={'stiffness': 1e9, 'gap': 0}, wall_right={'stiffness': 1e9, 'gap': 0})",
    "n2-two-walls-touching-rest-gravity": f"chain([1, 1], [0, 0], gaps=[0], stiffness={C}, wall_left={{'stiffness': 1e9, 'gap': 0}}, wall_right={{'stiffness': 1e9, 'gap': 0}}, gravity=-9.81)",
    "huge-n-tiny-tend": "chain(np.ones(10**6), np.r_[1.0, np.zeros(10**6 - 1)], gaps=0.0, stiffness=1e9, t_end=1e-9)",
    "huge-n-none": "chain(np.ones(10**6), np.zeros(10**6), gaps=1e-3, stiffness=1e9)",
    # gravity and walls
    "gravity-no-wall-none": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, gravity=-9.81)",
    "gravity-no-wall-separating": f"chain([1, 1], [0, 1], gaps=[0.01], stiffness={C}, gravity=-9.81)",
    "gravity-away-from-wall": "chain([1], [0], wall_right={'stiffness': 1e9, 'gap': 0.01}, gravity=-9.81)",
    "gravity-up-to-wall-not-reaching": "chain([1], [1], wall_right={'stiffness': 1e9, 'gap': 1.0}, gravity=-9.81)",
    "gravity-up-to-wall-reaching": "chain([1], [1], wall_right={'stiffness': 1e9, 'gap': 0.01}, gravity=-9.81)",
    "bouncing-elastic-forever": "chain([1], [0], wall_left={'stiffness': 1e9, 'gap': 0.01}, gravity=-9.81)",
    "bouncing-elastic-forever-maxsteps": "chain([1], [0], wall_left={'stiffness': 1e9, 'gap': 0.01}, gravity=-9.81, max_steps=100000)",
    "bouncing-damped": "chain([1], [0], wall_left={'stiffness': 1e9, 'gap': 0.01, 'damping': 0.5}, gravity=-9.81)",
    "resting-on-floor-elastic": "chain([1], [0], wall_left={'stiffness': 1e9, 'gap': 0.0}, gravity=-9.81)",
    "gravity-subnormal-floor": "chain([1], [0], wall_left={'stiffness': 1e9, 'gap': 0.01, 'damping': 0.5}, gravity=-5e-324)",
    "gravity-tiny-floor": "chain([1], [0], wall_left={'stiffness': 1e9, 'gap': 0.01, 'damping': 0.5}, gravity=-1e-300)",
    "gravity-huge": "chain([1], [0], wall_left={'stiffness': 1e9, 'gap': 0.01, 'damping': 0.5}, gravity=-1e300)",
    "wall-gap-huge-gravity": "chain([1], [0], wall_left={'stiffness': 1e9, 'gap': 1e300, 'damping': 0.5}, gravity=-9.81)",
    # laws
    "damping-huge": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, damping=1e12)",
    "damping-huge-touching3": f"chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness={C}, damping=1e12)",
    "damping-negative": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, damping=-0.1)",
    "exponent-tiny": f"chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness={C}, exponent=1e-3)",
    "exponent-zero": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, exponent=0.0)",
    "exponent-negative": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, exponent=-1)",
    "exponent-huge": f"chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness={C}, exponent=100)",
    "exponent-huge-2": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, exponent=1000)",
    "stiffness-tiny": "chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness=1e-300)",
    "stiffness-tiny-2": "chain([1, 1], [1, 0], gaps=[0.01], stiffness=1e-300)",
    "stiffness-huge": "chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness=1e300)",
    "stiffness-huge-2": "chain([1, 1], [1, 0], gaps=[0.01], stiffness=1e300)",
    "stiffness-zero": "chain([1, 1], [1, 0], gaps=[0.01], stiffness=0.0)",
    # velocities
    "velocities-zero": f"chain([1, 1, 1], [0, 0, 0], gaps=[0, 0.01], stiffness={C})",
    "velocities-zero-walls": f"chain([1, 1], [0, 0], gaps=[0], stiffness={C}, wall_left={{'stiffness': 1e9}}, wall_right={{'stiffness': 1e9}})",
    "velocities-subnormal": f"chain([1, 1, 1], [5e-324, 0, 0], gaps=[0, 0], stiffness={C})",
    "velocities-subnormal-gap": f"chain([1, 1], [5e-324, 0], gaps=[1e-300], stiffness={C})",
    "velocities-huge": f"chain([1, 1], [1e200, 0], gaps=[0.01], stiffness={C})",
    "velocities-huge-touching": f"chain([1, 1, 1], [1e200, 0, 0], gaps=[0, 0], stiffness={C})",
    "velocities-1e154": f"chain([1, 1, 1], [1e154, 0, 0], gaps=[0, 0], stiffness={C})",
    # tolerances and options
    "rtol-0": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, rtol=0)",
    "rtol-1": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, rtol=1)",
    "rtol-negative": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, rtol=-1e-10)",
    "rtol-tiny": f"chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness={C}, rtol=1e-20)",
    "rtol-subnormal": f"chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness={C}, rtol=5e-324)",
    "rtol-large": f"chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness={C}, rtol=0.9)",
    "tend-subnormal": f"chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness={C}, t_end=5e-324)",
    "tend-huge": f"chain([1, 1], [1, 0], gaps=[0.01], stiffness={C}, t_end=1e300)",
    "tend-huge-gravity-floor": "chain([1], [0], wall_left={'stiffness': 1e9, 'gap': 0.01, 'damping': 0.5}, gravity=-9.81, t_end=1e300)",
    "max-contacts-0": f"chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness={C}, max_contacts=0)",
    "exact-cluster": f"chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness={C}, method='exact')",
    "wall-no-stiffness": "chain([1], [-1], wall_left={'gap': 0.01})",
    "wall-unknown-key": "chain([1], [-1], wall_left={'stiffness': 1e9, 'gapp': 0.01})",
    "walls-both-n1-squeezed-gravity": "chain([1], [0], wall_left={'stiffness': 1e9, 'gap': 0}, wall_right={'stiffness': 1e9, 'gap': 0}, gravity=-9.81)",
    "stiffness-per-pair-wrong-size": "chain([1, 1, 1], [1, 0, 0], gaps=[0, 0], stiffness=[1e9, 1e9, 1e9])",
    "masses-2d": "chain([[1, 1]], [1, 0], gaps=[0], stiffness=1e9)",
    "masses-strings": "chain(['1', '1'], [1, 0], gaps=[0], stiffness=1e9)",
    "masses-bool": "chain([True, True], [1, 0], gaps=[0], stiffness=1e9)",
    "gravity-array": "chain([1, 1], [1, 0], gaps=[0], stiffness=1e9, gravity=[1.0, 2.0])",
}

PRELUDE = ("import numpy as np, math\nfrom hcimpact import chain\nimport hcimpact\n"
           "try:\n    r = {expr}\n"
           "except hcimpact.HcimpactError as e:\n"
           "    print('RAISE', type(e).__name__ + ':', e)\n"
           "except Exception as e:\n"
           "    print('RAISE-OTHER', type(e).__name__ + ':', e)\n"
           "else:\n"
           "    print('OK', r, 'v', r.velocities[:4], 'x', r.positions[:4], 'rested', r.rested,"
           " 'dissipated', r.dissipated, 'E0', r.initial_energy, 'steps', r.counters['steps'], 'msg', r.message)\n")


def main():
    sel = sys.argv[1] if len(sys.argv) > 1 else ""
    for name, expr in CASES.items():
        if sel not in name:
            continue
        try:
            p = subprocess.run([sys.executable, "-c", PRELUDE.format(expr=expr)],
                               capture_output=True, text=True, timeout=60)
            out = (p.stdout.strip() or p.stderr.strip()[-300:])
            if p.returncode != 0:
                out = f"CRASH rc={p.returncode} " + p.stderr.strip()[-300:]
        except subprocess.TimeoutExpired:
            out = "HANG (60 s)"
        print(f"{name:38s} {out}", flush=True)


if __name__ == "__main__":
    main()
