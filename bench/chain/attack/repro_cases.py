# SPDX-License-Identifier: Apache-2.0
"""The runner of the reproducer scripts (repro_second_attack.py, repro_frame_attack.py).

A script makes `case = Cases()`, marks each case's function with `@case("name")` (its
docstring is the Python source of the case) and ends with `case.main()`. Each case
runs in its own process with a timeout (60 s unless said); `--list` names the cases,
and names on the command line choose some.
"""
import subprocess
import sys
import textwrap


class Cases:
    def __init__(self):
        self.cases = {}

    def __call__(self, name, timeout=60):
        def wrap(src):
            self.cases[name] = (textwrap.dedent(src.__doc__), timeout)
            return src
        return wrap

    def main(self):
        names = sys.argv[1:] or list(self.cases)
        if names == ["--list"]:
            print("\n".join(self.cases))
            return
        for name in names:
            src, timeout = self.cases[name]
            print(f"== {name}", flush=True)
            try:
                out = subprocess.run([sys.executable, "-c", src], capture_output=True,
                                     text=True, timeout=timeout)
                print(out.stdout + out.stderr[-2000:], end="", flush=True)
            except subprocess.TimeoutExpired:
                print(f"TIMEOUT after {timeout} s", flush=True)
