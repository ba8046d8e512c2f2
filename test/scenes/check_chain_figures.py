#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The figures of systems of bodies (doc/scenes.md): each example scene through the
runner, then plot_results.py, which must draw the figure the scene is there for.

    python3 check_chain_figures.py path/to/hcimpact python/plot_results.py OUTPUT_DIR [--core]

With --core (a runner built without CVODE, as fpm builds it) only the scene whose
contacts are all isolated runs (the cradle with gaps: figures 11 and 12). Prints
"skipped: no matplotlib" (and passes) when Matplotlib is not installed.
"""
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# scene -> the figures it must give
WITH_CVODE = {
    "newton_cradle": ["fig11_velocities", "fig12_force_spacetime"],
    "struck_chain": ["fig11_velocities", "fig12_force_spacetime"],
    "bouncing_ball": ["fig11_velocities", "fig13_rebounds"],
}
CORE = {"newton_cradle_gaps": ["fig11_velocities", "fig12_force_spacetime"]}


def main():
    program, script, out = sys.argv[1:4]
    core = "--core" in sys.argv[4:]
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
    except ImportError:
        print("skipped: no matplotlib (or numpy) in this Python")
        return 0
    shutil.rmtree(out, ignore_errors=True)
    for scene, figures in (CORE if core else WITH_CVODE).items():
        directory = os.path.join(out, scene)
        path = os.path.join(ROOT, "example", "scenes", scene + ".nml")
        run = subprocess.run([program, path, "-q", "-o", directory])
        if run.returncode != 0:
            return f"{scene}: hcimpact exited with {run.returncode}"
        run = subprocess.run([sys.executable, script, directory])
        if run.returncode != 0:
            return f"{scene}: plot_results.py exited with {run.returncode}"
        missing = [name for name in figures
                   if not os.path.exists(os.path.join(directory, name + ".png"))
                   or os.path.getsize(os.path.join(directory, name + ".png")) < 10000]
        if missing:
            return f"{scene}: figures missing or empty: {missing}"
    print(f"PASS: the figures of {len(CORE if core else WITH_CVODE)} scenes in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
