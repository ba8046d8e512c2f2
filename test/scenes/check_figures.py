#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The README's main job: `hcimpact --figures -o DIR`, then `plot_results.py DIR` draws
the seed's figures 1-8.

    python3 check_figures.py path/to/hcimpact python/plot_results.py OUTPUT_DIR

Prints "skipped: no matplotlib" (and passes) when Matplotlib is not installed.
"""
import os
import shutil
import subprocess
import sys

EXPECTED = ["fig1_phase", "fig2_velocity_z", "fig3_restitution", "fig4_histories",
            "fig5_peaks", "fig6_loops", "fig7_energy", "fig8_lambertw"]


def main():
    program, script, out = sys.argv[1:4]
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
    except ImportError:
        print("skipped: no matplotlib (or numpy) in this Python")
        return 0
    shutil.rmtree(out, ignore_errors=True)
    run = subprocess.run([program, "--figures", "-q", "-o", out])
    if run.returncode != 0:
        return f"hcimpact --figures exited with {run.returncode}"
    run = subprocess.run([sys.executable, script, out])
    if run.returncode != 0:
        return f"plot_results.py exited with {run.returncode}"
    missing = [name for name in EXPECTED
               if not os.path.exists(os.path.join(out, name + ".png"))
               or os.path.getsize(os.path.join(out, name + ".png")) < 10000]
    if missing:
        return f"figures missing or empty: {missing}"
    leftovers = [name for name in os.listdir(out) if ".partial" in name]
    if leftovers:
        return f"partial files left: {leftovers}"
    print(f"PASS: {len(EXPECTED)} figures in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
