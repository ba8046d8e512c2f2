#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""plot_results.py in a Python without Matplotlib, and one without NumPy: one line on
standard error naming what is missing and how to install it (pip install ...), exit
status 3, no traceback, nothing written.

    python3 check_plot_missing.py python/plot_results.py OUTPUT_DIR

The package is made to fail its import in the child (a finder at the front of
sys.meta_path, which refuses it and its submodules as an absent package would), so the
test runs whether or not Matplotlib and NumPy are installed.
"""
import os
import shutil
import subprocess
import sys

# the child: refuse the imports of sys.argv[1] (and its submodules), then run the
# script as `python3 plot_results.py ARGS...`
CHILD = """
import importlib.abc, runpy, sys
blocked = sys.argv[1]

class Absent(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name == blocked or name.startswith(blocked + "."):
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None

sys.meta_path.insert(0, Absent())
for name in [m for m in sys.modules if m == blocked or m.startswith(blocked + ".")]:
    del sys.modules[name]
sys.argv = sys.argv[2:]
runpy.run_path(sys.argv[0], run_name="__main__")
"""


def check(script, out, blocked):
    """None when the run without `blocked` behaves, else what is wrong."""
    run = subprocess.run([sys.executable, "-c", CHILD, blocked, script, out],
                         capture_output=True, text=True, timeout=120)
    lines = run.stderr.splitlines()
    wrong = []
    if run.returncode != 3:
        wrong.append(f"exit status {run.returncode}, expected 3")
    if len(lines) != 1:
        wrong.append(f"{len(lines)} lines on standard error, expected 1")
    text = run.stderr
    for part in ("plot_results: error: ", f"No module named '{blocked}'",
                 f"pip install {blocked}"):
        if part not in text:
            wrong.append(f"standard error lacks {part!r}")
    if "Traceback" in text:
        wrong.append("a traceback")
    made = [name for name in os.listdir(out) if name != "summary.csv"]
    if made:
        wrong.append(f"files written: {made}")
    if wrong:
        return f"without {blocked}: " + "; ".join(wrong) + f"\n--- stderr:\n{run.stderr}"
    print(f"without {blocked}: {lines[0]}")
    return None


def main():
    script, out = sys.argv[1:3]
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    # a results directory with one file of a run, which a plot would read
    with open(os.path.join(out, "summary.csv"), "w") as handle:
        handle.write("speed [m/s],restitution []\n1,0.9\n")
    failures = [text for text in (check(script, out, name) for name in ("matplotlib", "numpy"))
                if text]
    if failures:
        return "FAIL " + "\nFAIL ".join(failures)
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
