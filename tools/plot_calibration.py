#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Draw the figures of doc/calibration.md from the CSV files of calibration_study.

    cmake --build build/release --target calibration_study
    mkdir -p build/calibration
    build/release/test/lapack/calibration_study 200 build/calibration > build/calibration/tables.md
    python3 tools/plot_calibration.py build/calibration doc/figures

writes doc/figures/calibration-linear-law.svg (the linear restitution law against the
exact one) and doc/figures/calibration-coverage.svg (errors of the noisy fits in units
of their reported standard errors). Needs numpy and matplotlib. The SVG files carry no
date, so that the same data give the same files.
"""
import argparse
import csv
import math
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

SVG_OPTIONS = {"format": "svg", "metadata": {"Date": None}}


def read_rows(path):
    with open(path, newline="") as handle:
        lines = [line for line in handle if not line.startswith("#")]
    return list(csv.reader(lines))


def linear_law(directory, output):
    rows = read_rows(directory / "linear_law.csv")[1:]
    beta = np.array([float(r[0]) for r in rows])
    ratio = np.array([float(r[1]) for r in rows])
    seed = read_rows(directory / "seed_example.csv")
    curves = {}
    for kind, v, e in seed:
        curves.setdefault(kind, ([], []))
        curves[kind][0].append(float(v))
        curves[kind][1].append(float(e))

    fig, (left, right) = plt.subplots(1, 2, figsize=(9.5, 3.8))
    left.semilogx(beta, ratio, color="C3")
    left.axhline(1.0, color="0.6", linewidth=0.8)
    left.plot([0.5], [np.interp(0.5, beta, ratio)], "o", color="C3")
    left.annotate("the seed's steel ball:\nb = 0.1 s/m, V = 0.5...5 m/s",
                  (0.5, np.interp(0.5, beta, ratio)), xytext=(0.012, 0.35),
                  arrowprops={"arrowstyle": "->", "color": "0.4"}, fontsize=8)
    left.set_xlabel(r"$\beta_{max} = b\,V_{max}$ (speeds over $[\beta_{max}/10, \beta_{max}]/b$)")
    left.set_ylabel(r"$b_{linear}\,/\,b$")
    left.set_ylim(0, 1.05)
    left.set_title("Linear law on exact-law data (noise free)", fontsize=10)

    v, e = curves["data"]
    right.plot(v, e, "o", color="k", markersize=4, label="data: k(0.1 V) + noise 0.01")
    for kind, style, label in (("true", dict(color="0.6", linestyle=":"), "true law, b = 0.1 s/m"),
                               ("exact", dict(color="C0"), "fit, exact law k(b V)"),
                               ("linear", dict(color="C3", linestyle="--"),
                                "fit, linear law 1 - (2b/3) V")):
        right.plot(*curves[kind], label=label, **style)
    right.set_xlabel("approach speed V (m/s)")
    right.set_ylabel("restitution e")
    right.set_xlim(0, 5.5)
    right.legend(fontsize=8, loc="lower left")
    right.set_title("Seed example with noise (seed 1)", fontsize=10)
    fig.tight_layout()
    fig.savefig(output / "calibration-linear-law.svg", **SVG_OPTIONS)
    plt.close(fig)


def coverage(directory, output):
    rows = read_rows(directory / "recovery.csv")[1:]
    groups = {}
    for fit, parameter, _seed, true, estimate, error in rows:
        z = (float(estimate) - float(true)) / float(error)
        groups.setdefault((fit, parameter), []).append(z)
    titles = {
        "fit_damping": "fit_damping: e(V)",
        "fit_damping_linear": "fit_damping_linear: e(V)",
        "fit_static": "fit_static: F(x)",
        "fit_elastic_t": "fit_elastic: t_c(V)",
        "fit_elastic_tf": "fit_elastic: t_c, F_max",
        "fit_impact": "fit_impact: t_c, F_max, e",
        "fit_impact_absolute": "fit_impact, true sigmas",
    }
    keys = [key for key in groups if key[0] != "fit_damping_linear"]
    columns = 5
    nrows = math.ceil(len(keys) / columns)
    fig, axes = plt.subplots(nrows, columns, figsize=(12, 2.5 * nrows), squeeze=False)
    grid = np.linspace(-4, 4, 200)
    normal = np.exp(-grid**2 / 2) / math.sqrt(2 * math.pi)
    for axis, key in zip(axes.flat, keys):
        z = np.array(groups[key])
        axis.hist(np.clip(z, -4, 4), bins=np.linspace(-4, 4, 33), density=True, color="C0",
                  alpha=0.6)
        axis.plot(grid, normal, color="k", linewidth=1)
        inside = np.mean(np.abs(z) <= 2)
        axis.set_title(f"{titles.get(key[0], key[0])}\n{key[1]}: {100 * inside:.0f} % within 2 SE",
                       fontsize=8)
        axis.tick_params(labelsize=7)
        axis.set_xlim(-4, 4)
    for index, axis in enumerate(axes.flat):
        if index >= len(keys):
            axis.set_visible(False)
        elif index + columns >= len(keys):
            axis.set_xlabel("(estimate - true) / SE", fontsize=8)
    fig.suptitle(f"Noisy data, {len(next(iter(groups.values())))} seeds: errors in units of "
                 "the reported standard error (curve: standard normal)", fontsize=10)
    fig.tight_layout()
    fig.savefig(output / "calibration-coverage.svg", **SVG_OPTIONS)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("directory", type=pathlib.Path, help="output of calibration_study")
    parser.add_argument("output", type=pathlib.Path, nargs="?", default=pathlib.Path("doc/figures"))
    args = parser.parse_args()
    args.output.mkdir(parents=True, exist_ok=True)
    plt.rcParams["svg.hashsalt"] = "hcimpact"
    plt.rcParams["svg.fonttype"] = "none"     # text as text: smaller files
    linear_law(args.directory, args.output)
    coverage(args.directory, args.output)


if __name__ == "__main__":
    main()
