#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Draw the figures of an hcimpact results directory (CSV files only).

    hcimpact --figures -o out && python3 python/plot_results.py out

Works from any directory and without the hcimpact shared library: it loads
python/hcimpact/plot.py by its path, so the package's __init__ (which may load the
library) is never imported. Needs NumPy and Matplotlib (without them: one line saying
which is missing and how to install it, exit status 3). --help for the options.
"""
import importlib.util
import os
import sys


def _load_plot_module():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "hcimpact", "plot.py")
    spec = importlib.util.spec_from_file_location("hcimpact_plot", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


if __name__ == "__main__":
    sys.exit(_load_plot_module().main())
