# SPDX-License-Identifier: Apache-2.0
"""Figures from a results directory of the ``hcimpact`` scene runner.

Reads only the CSV files the runner wrote (never the shared library), so it works on
any machine with NumPy and Matplotlib::

    hcimpact --figures -o out              # the seed's steel ball, every figure's data
    python3 python/plot_results.py out     # writes out/fig1_phase.png ... fig8_lambertw.png

or, with ``python/`` on the module path, ``python3 -m hcimpact.plot out``.

Each figure is drawn when its CSV files are present and skipped otherwise:

======  ============================================  ==================================
figure  what (the seed's caption)                     from
======  ============================================  ==================================
1       phase trajectories V(x)                       phase.csv
2       V against z on both branches of W             velocity_z.csv, motion_z.csv
3       k and energy loss against beta = b V          restitution.csv (+ summary.csv)
4       x(t) and F(t)                                 histories.csv
5       x_max, F_max and contact time against V       sweep.csv and/or summary.csv
6       force against deformation (hysteresis)        loops.csv
7       energy lost against V                         sweep.csv and/or summary.csv
8       the two real branches of Lambert W            lambertw.csv
9       work-precision: CVODE against closed form     cvode.csv
10      damping rules of multibody codes              legacy.csv
11      a system of bodies: velocities against time   motion.csv
12      a struck chain: the force in space and time   forces.csv (3 pairs or more)
13      a bouncing ball: rebound heights per bounce   contacts.csv (wall contacts and
                                                      gravity, from parameters.csv)
======  ============================================  ==================================
"""

import argparse
import csv
import math
import os
import sys

# NumPy and Matplotlib are imported on first use (`_load`): importing this module
# costs nothing and needs neither.
np = None
matplotlib = None

__all__ = ["read_csv", "plot_results", "main"]

FIGURES = {
    1: "fig1_phase",
    2: "fig2_velocity_z",
    3: "fig3_restitution",
    4: "fig4_histories",
    5: "fig5_peaks",
    6: "fig6_loops",
    7: "fig7_energy",
    8: "fig8_lambertw",
    9: "fig9_work_precision",
    10: "fig10_legacy",
    11: "fig11_velocities",
    12: "fig12_force_spacetime",
    13: "fig13_rebounds",
}


class NotApplicable(Exception):
    """A figure whose files are there but whose data it does not fit (a chain of two
    bodies has no wave to draw): skipped with the reason."""


class MissingPackage(ImportError):
    """NumPy or Matplotlib cannot be imported: the message says which and how to
    install it (one line)."""


def _load():
    """Import NumPy and Matplotlib (the Agg backend: files only, no display); a
    MissingPackage error naming the one that cannot be imported."""
    global np, matplotlib
    if np is None:
        try:
            import numpy
        except ImportError as exc:
            raise _missing("NumPy", "numpy", exc) from exc
        np = numpy
    if matplotlib is None:
        try:
            import matplotlib as mpl
            mpl.use("Agg")
            import matplotlib.pyplot  # noqa: F401 (the figures' module, imported here)
            import matplotlib.ticker  # noqa: F401 (used as matplotlib.ticker)
        except ImportError as exc:
            raise _missing("Matplotlib", "matplotlib", exc) from exc
        matplotlib = mpl


def _missing(package, name, exc):
    """The MissingPackage error of `package` (pip's name `name`), from the ImportError."""
    why = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return MissingPackage(f"the figures need {package}, which this Python cannot import "
                          f"({why}): pip install {name} (for this Python: "
                          f"{sys.executable} -m pip install {name})", name=name)


# ----------------------------------------------------------------------------------
# Reading
# ----------------------------------------------------------------------------------

def read_csv(path):
    """Columns of a runner CSV file as a dict: name -> NumPy array (float) or list
    (text). Header cells are ``name [unit]``; the unit is dropped from the key and
    kept in ``result["_units"][name]``."""
    _load()
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    if not rows:
        raise ValueError(f"{path}: empty file")
    names, units = [], {}
    for cell in rows[0]:
        cell = cell.strip()
        if cell.endswith("]") and "[" in cell:
            name, unit = cell[:-1].split("[", 1)
            name = name.strip()
            units[name] = unit.strip()
        else:
            name = cell
        names.append(name)
    columns = {name: [] for name in names}
    for number, row in enumerate(rows[1:], start=2):
        if not row:
            continue
        if len(row) != len(names):
            raise ValueError(f"{path}:{number}: {len(row)} fields, the header has {len(names)}")
        for name, cell in zip(names, row):
            columns[name].append(cell)
    result = {"_units": units}
    for name, cells in columns.items():
        try:
            result[name] = np.array([float(cell) for cell in cells])
        except ValueError:
            result[name] = cells
    return result


def read_parameters(directory):
    """parameters.csv as a dict name -> float (or text); {} if absent."""
    path = os.path.join(directory, "parameters.csv")
    values = {}
    if not os.path.exists(path):
        return values
    with open(path, newline="") as handle:
        for row in list(csv.reader(handle))[1:]:
            if len(row) < 2:
                continue
            try:
                values[row[0]] = float(row[1])
            except ValueError:
                values[row[0]] = row[1]
    return values


# ----------------------------------------------------------------------------------
# Helpers
# ----------------------------------------------------------------------------------

_PREFIXES = [(1e-9, "n"), (1e-6, "µ"), (1e-3, "m"), (1.0, ""), (1e3, "k"), (1e6, "M"),
             (1e9, "G")]


def scale(values, unit):
    """A factor and a unit with an SI prefix that bring the largest |value| into
    [1, 1000): returns (factor to multiply by, unit text)."""
    _load()
    finite = np.abs(np.asarray(values, dtype=float))
    finite = finite[np.isfinite(finite) & (finite > 0)]
    if finite.size == 0:
        return 1.0, unit
    top = finite.max()
    chosen = _PREFIXES[0]
    for factor, prefix in _PREFIXES:
        if top >= factor * 0.9999:
            chosen = (factor, prefix)
    return 1.0 / chosen[0], chosen[1] + unit


def speed_colors(speeds):
    """One colour per speed, from a sequential colour map (slow: light, fast: dark)."""
    _load()
    cmap = matplotlib.colormaps["viridis"]
    n = len(speeds)
    return {v: cmap(0.85 * (1.0 - i / max(n - 1, 1))) for i, v in enumerate(speeds)}


def speed_label(v):
    return f"V = {v:g} m/s"


def unique(values):
    seen, out = set(), []
    for v in values:
        if v not in seen:
            seen.add(v)
            out.append(v)
    return out


def title_of(params, default="hcimpact"):
    title = params.get("title", default)
    return title if isinstance(title, str) else default


def caption(fig, text):
    fig.text(0.5, 0.005, text, ha="center", va="bottom", fontsize=8.5, color="0.3",
             wrap=True)


# ----------------------------------------------------------------------------------
# The figures
# ----------------------------------------------------------------------------------

def fig_phase(d, params, plt):
    data = read_csv(os.path.join(d, "phase.csv"))
    speeds = unique(list(data["speed"]))
    colors = speed_colors(speeds)
    kx, ux = scale(data["compression"], "m")
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    phase = data["phase"]
    for v in speeds:
        for name, style in (("compression", "-"), ("restitution", "-")):
            mask = [(s == v and p == name) for s, p in zip(data["speed"], phase)]
            x = data["compression"][mask] * kx
            y = data["velocity"][mask]
            ax.plot(x, y, style, color=colors[v], lw=1.6,
                    label=speed_label(v) if name == "compression" else None)
        # direction of motion: along the compression branch, back along restitution
        mask = [(s == v and p == "compression") for s, p in zip(data["speed"], phase)]
        x = data["compression"][mask] * kx
        y = data["velocity"][mask]
        i = len(x) // 3
        ax.annotate("", xy=(x[i + 1], y[i + 1]), xytext=(x[i], y[i]),
                    arrowprops=dict(arrowstyle="->", color=colors[v], lw=1.4))
    b = params.get("damping")
    if isinstance(b, float) and b > 0:
        ax.axhline(-1.0 / b, color="k", ls="--", lw=1.0,
                   label=f"V = −1/b = −{1.0 / b:g} m/s (never reached)")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel(f"deformation x ({ux})")
    ax.set_ylabel("velocity V = dx/dt (m/s)")
    ax.set_xlim(left=0)
    title = "Fig. 1  Phase trajectories V(x)"
    if isinstance(b, float):
        title += f", b = {b:g} s/m"
    ax.set_title(title + "\n" + title_of(params), fontsize=11)
    ax.legend(fontsize=8, loc="lower left", bbox_to_anchor=(0.0, 0.1), ncol=2)
    ax.grid(alpha=0.3)
    ax.text(0.98, 0.97, "compression: V > 0\nrestitution: V < 0", transform=ax.transAxes,
            ha="right", va="top", fontsize=8.5, color="0.3")
    return fig


def fig_velocity_z(d, params, plt):
    curve = read_csv(os.path.join(d, "velocity_z.csv"))
    motion_path = os.path.join(d, "motion_z.csv")
    motion = read_csv(motion_path) if os.path.exists(motion_path) else None
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    phase = curve["phase"]
    for name, style, label in (("compression", "--", "compression: W₋₁ branch"),
                               ("restitution", "-", "restitution: W₀ branch")):
        mask = [p == name for p in phase]
        ax.plot(curve["z"][mask], curve["velocity"][mask], style, color="k", lw=1.2,
                label=label)
    b = params.get("damping")
    if isinstance(b, float) and b > 0:
        ax.axhline(-1.0 / b, color="0.5", ls=":", lw=1.0, label=f"V = −1/b = −{1.0 / b:g} m/s")
    ax.axvline(-1.0 / math.e, color="0.6", lw=0.6)
    ax.axhline(0.0, color="0.6", lw=0.6)
    vmax = None
    if motion is not None:
        speeds = unique(list(motion["speed"]))
        colors = speed_colors(speeds)
        vmax = max(speeds)
        # the faster impacts run through the slower ones' arcs: draw them first
        for v in reversed(speeds):
            mask = [s == v for s in motion["speed"]]
            ax.plot(motion["z"][mask], motion["velocity"][mask], color=colors[v], lw=3.5,
                    solid_capstyle="round", label=f"impact at {speed_label(v)}")
    top = 2.5 * vmax if vmax else np.nanmax(curve["velocity"])
    if isinstance(b, float) and b > 0:
        ax.set_ylim(-1.15 / b, max(top, 0.3 / b))
    ax.set_xlim(-1.0 / math.e - 0.01, 0.0)
    ax.set_xlabel("z = −exp(g(x))  (seed eq. 14)")
    ax.set_ylabel("velocity V = −(1 + W(z))/b (m/s)")
    ax.set_title("Fig. 2  Velocity against z on both real branches of W\n" + title_of(params),
                 fontsize=11)
    handles, labels = ax.get_legend_handles_labels()
    order = list(range(3)) + list(range(len(handles) - 1, 2, -1))
    ax.legend([handles[i] for i in order if i < len(handles)],
              [labels[i] for i in order if i < len(handles)], fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    if motion is not None:
        # the impacts run through a small neighbourhood of the branch point: zoom in
        zmax = float(np.nanmax(motion["z"]))
        width = zmax + 1.0 / math.e
        inset = ax.inset_axes([0.56, 0.5, 0.41, 0.44])
        for name, style in (("compression", "--"), ("restitution", "-")):
            mask = [p == name for p in phase]
            inset.plot(curve["z"][mask], curve["velocity"][mask], style, color="k", lw=1.0)
        for v in reversed(speeds):
            mask = [s == v for s in motion["speed"]]
            inset.plot(motion["z"][mask], motion["velocity"][mask], color=colors[v], lw=3)
        inset.set_xlim(-1.0 / math.e - 0.05 * width, zmax + 0.1 * width)
        vel = motion["velocity"]
        inset.set_ylim(1.1 * np.nanmin(vel), 1.1 * np.nanmax(vel))
        inset.axhline(0.0, color="0.6", lw=0.6)
        inset.tick_params(labelsize=7)
        inset.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(4))
        inset.set_title("near z = −1/e: the impacts", fontsize=8)
        inset.grid(alpha=0.3)
    return fig


def fig_restitution(d, params, plt):
    data = read_csv(os.path.join(d, "restitution.csv"))
    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    ax.plot(data["beta"], data["restitution"], "-", color="C0", lw=1.8,
            label="restitution k")
    ax.plot(data["beta"], data["energy_loss_ratio"], "--", color="C3", lw=1.8,
            label="energy lost ΔT/T⁻ = 1 − k²")
    ax.plot(data["beta"], 1.0 - 2.0 * data["beta"] / 3.0, ":", color="C0", lw=1.0,
            label="k ≈ 1 − 2β/3 (small β, seed eq. 24)")
    summary_path = os.path.join(d, "summary.csv")
    if os.path.exists(summary_path):
        s = read_csv(summary_path)
        ax.plot(s["beta"], s["restitution"], "o", color="C0", ms=5,
                label="this scene's speeds")
        ax.plot(s["beta"], s["energy_loss_ratio"], "s", color="C3", ms=4.5,
                label="(the same speeds)")
    ax.set_ylim(0, 1.05)
    ax.set_xlim(0, float(np.nanmax(data["beta"])))
    ax.set_xlabel("β = b V⁻ (dimensionless)")
    ax.set_ylabel("k,  ΔT/T⁻ (dimensionless)")
    ax.set_title("Fig. 3  Restitution and energy loss against β = b V⁻\n"
                 "(the same for every elastic law and mass)", fontsize=11)
    ax.legend(fontsize=8.5, loc="center right")
    ax.grid(alpha=0.3)
    return fig


def fig_histories(d, params, plt):
    data = read_csv(os.path.join(d, "histories.csv"))
    speeds = unique(list(data["speed"]))
    colors = speed_colors(speeds)
    kt, ut = scale(data["time"], "s")
    kx, ux = scale(data["compression"], "m")
    kf, uf = scale(data["force"], "N")
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7.5, 7.0), sharex=True)
    for v in speeds:
        mask = data["speed"] == v
        ax1.plot(data["time"][mask] * kt, data["compression"][mask] * kx, color=colors[v],
                 lw=1.6, label=speed_label(v))
        ax2.plot(data["time"][mask] * kt, data["force"][mask] * kf, color=colors[v], lw=1.6)
    ax1.set_ylabel(f"deformation x ({ux})")
    ax2.set_ylabel(f"contact force F ({uf})")
    ax2.set_xlabel(f"time t ({ut})")
    ax1.set_title("Fig. 4  Deformation and contact force against time\n" + title_of(params),
                  fontsize=11)
    ax1.legend(fontsize=8, loc="upper right")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
        ax.set_ylim(bottom=0)
        ax.set_xlim(left=0)
    fig.tight_layout()
    return fig


def _speed_series(d):
    """(line data, marker data) for figures 5 and 7: sweep.csv and summary.csv."""
    sweep_path = os.path.join(d, "sweep.csv")
    summary_path = os.path.join(d, "summary.csv")
    line = read_csv(sweep_path) if os.path.exists(sweep_path) else None
    points = read_csv(summary_path) if os.path.exists(summary_path) else None
    return line, points


def fig_peaks(d, params, plt):
    line, points = _speed_series(d)
    fig, axes = plt.subplots(3, 1, figsize=(7.0, 8.2), sharex=True)
    specs = (("max_compression", "m", "maximum deformation x_max"),
             ("peak_force", "N", "maximum contact force F_max"),
             ("contact_time", "s", "contact time"))
    for ax, (key, unit, label) in zip(axes, specs):
        ref = line if line is not None else points
        k, u = scale(ref[key], unit)
        if line is not None:
            ax.plot(line["speed"], line[key] * k, "-", color="C0", lw=1.8)
        if points is not None:
            ax.plot(points["speed"], points[key] * k, "o", color="C1", ms=5,
                    label="the scene's speeds")
        ax.set_ylabel(f"{label}\n({u})", fontsize=9.5)
        ax.grid(alpha=0.3)
        ax.set_ylim(bottom=0)
    axes[-1].set_xlabel("approach speed V⁻ (m/s)")
    axes[-1].set_xlim(left=0)
    if points is not None:
        axes[0].legend(fontsize=8, loc="lower right")
    axes[0].set_title("Fig. 5  Maximum deformation, peak force and contact time against V⁻\n"
                      + title_of(params), fontsize=11)
    fig.tight_layout()
    return fig


def fig_loops(d, params, plt):
    data = read_csv(os.path.join(d, "loops.csv"))
    speeds = unique(list(data["speed"]))
    colors = speed_colors(speeds)
    kx, ux = scale(data["compression"], "m")
    kf, uf = scale(data["force"], "N")
    fig, ax = plt.subplots(figsize=(7.5, 5.4))
    for v in reversed(speeds):
        mask = data["speed"] == v
        x = data["compression"][mask] * kx
        f = data["force"][mask] * kf
        ax.fill(x, f, color=colors[v], alpha=0.18, lw=0)
        ax.plot(x, f, color=colors[v], lw=1.5, label=speed_label(v))
        phase = [p for p, m in zip(data["phase"], mask) if m]
        i = phase.index("restitution") + len(phase) // 6
        ax.annotate("", xy=(x[i + 1], f[i + 1]), xytext=(x[i], f[i]),
                    arrowprops=dict(arrowstyle="->", color=colors[v], lw=1.3))
    ax.set_xlabel(f"deformation x ({ux})")
    ax.set_ylabel(f"contact force F ({uf})")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.set_title("Fig. 6  Contact force against deformation: the hysteresis loops\n"
                 "(upper branch: compression; the shaded area is the energy lost)",
                 fontsize=11)
    handles, labels = ax.get_legend_handles_labels()
    ax.legend(handles[::-1], labels[::-1], fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    return fig


def fig_energy(d, params, plt):
    line, points = _speed_series(d)
    ref = line if line is not None else points
    k, u = scale(ref["energy_lost"], "J")
    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    if line is not None:
        ax.plot(line["speed"], line["energy_lost"] * k, "-", color="C3", lw=1.8,
                label="energy lost ΔT")
    if points is not None:
        ax.plot(points["speed"], points["energy_lost"] * k, "o", color="C3", ms=5,
                label="the scene's speeds")
    ax.set_xlabel("approach speed V⁻ (m/s)")
    ax.set_ylabel(f"kinetic energy lost ΔT ({u})")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax2 = ax.twinx()
    ax2.plot(ref["speed"], ref["energy_loss_ratio"], "--", color="0.4", lw=1.2,
             label="share lost ΔT/T⁻ (right axis)")
    ax2.set_ylabel("share of the kinetic energy lost ΔT/T⁻", color="0.3")
    ax2.set_ylim(bottom=0)
    lines = ax.get_legend_handles_labels()
    lines2 = ax2.get_legend_handles_labels()
    ax.legend(lines[0] + lines2[0], lines[1] + lines2[1], fontsize=8.5, loc="upper left")
    ax.set_title("Fig. 7  Kinetic energy lost in the impact against V⁻\n" + title_of(params),
                 fontsize=11)
    return fig


def fig_lambertw(d, params, plt):
    data = read_csv(os.path.join(d, "lambertw.csv"))
    fig, ax = plt.subplots(figsize=(7.0, 5.2))
    branch = data["branch"]
    for name, style, label in ((0.0, "-", "principal branch W₀(z)"),
                               (-1.0, "--", "lower branch W₋₁(z)")):
        mask = branch == name
        ax.plot(data["z"][mask], data["w"][mask], style, color="k", lw=1.6, label=label)
    ax.plot([-1.0 / math.e], [-1.0], "o", color="C3", ms=5, label="branch point (−1/e, −1)")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.axvline(0.0, color="0.6", lw=0.6)
    ax.set_ylim(-5.0, 1.5)
    ax.set_xlim(-0.5, float(np.nanmax(data["z"])))
    ax.set_xlabel("z")
    ax.set_ylabel("W(z),  W e^W = z")
    ax.set_title("Fig. 8  The two real branches of the Lambert W function", fontsize=11)
    ax.legend(fontsize=9, loc="lower right")
    ax.grid(alpha=0.3)
    return fig


def fig_work_precision(d, params, plt):
    data = read_csv(os.path.join(d, "cvode.csv"))
    speeds = unique(list(data["speed"]))
    colors = speed_colors(speeds)
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    floor = 1e-17
    for v in speeds:
        mask = data["speed"] == v
        err = np.maximum(data["max_error"][mask], floor)
        ax.loglog(data["seconds"][mask], err, "o-", color=colors[v], lw=1.4, ms=4,
                  label=f"CVODE, {speed_label(v)}")
        for t, e, r in zip(data["seconds"][mask], err, data["rtol"][mask]):
            if v == speeds[-1]:
                ax.annotate(f"rtol {r:.0e}", (t, e), textcoords="offset points",
                            xytext=(5, 3), fontsize=7, color="0.3")
    exact = data["closed_form_seconds"]
    ax.loglog(exact, np.full_like(exact, 2.2e-16), "*", color="C3", ms=10,
              label="closed forms (the reference, ~1 ulp)")
    ax.set_xlabel("time per impact (s)")
    ax.set_ylabel("largest relative error\n(k, x_max, F_max, contact and compression time)")
    ax.xaxis.set_minor_locator(matplotlib.ticker.LogLocator(subs=(2.0, 5.0)))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.LogFormatterSciNotation(
        labelOnlyBase=False, minor_thresholds=(10, 10)))
    ax.set_title("Work-precision: CVODE at several tolerances against the closed forms\n"
                 + title_of(params), fontsize=11)
    ax.legend(fontsize=7.5, loc="upper right")
    ax.grid(alpha=0.3, which="both")
    return fig


def fig_legacy(d, params, plt):
    data = read_csv(os.path.join(d, "legacy.csv"))
    rules = unique(list(data["rule"]))
    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    markers = "osD^v<>p"
    for i, rule in enumerate(rules):
        mask = [r == rule for r in data["rule"]]
        ax.plot(data["restitution"][mask], 100.0 * data["k_relative_error"][mask],
                marker=markers[i % len(markers)], lw=1.2, ms=4, label=rule)
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlabel("restitution e asked for (the exact k at each of the scene's speeds)")
    ax.set_ylabel("error of the restitution obtained, (k(χ) − e)/e (%)")
    ax.set_title("Damping rules of multibody codes in the exact model\n" + title_of(params),
                 fontsize=11)
    ax.legend(fontsize=7.5, ncol=2)
    ax.grid(alpha=0.3)
    return fig


def _long_table(data, key, value):
    """A long table (time, key, value) as (times, keys, matrix[time, key])."""
    times = np.array(unique(list(data["time"])))
    keys = np.array(unique(list(data[key])))
    matrix = np.full((times.size, keys.size), np.nan)
    row = {t: i for i, t in enumerate(times)}
    col = {k: j for j, k in enumerate(keys)}
    for t, k, v in zip(data["time"], data[key], data[value]):
        matrix[row[t], col[k]] = v
    return times, keys, matrix


def _active_window(times, matrix, margin=0.08):
    """The time window where the matrix changes by more than a thousandth of its
    largest value (with a margin at both ends), as a mask."""
    size = np.nanmax(np.abs(matrix)) if matrix.size else 0.0
    step = np.abs(np.diff(matrix, axis=0))
    changing = np.flatnonzero(np.any(step > 1e-3 * size, axis=1))
    if changing.size == 0:
        return np.ones(times.size, dtype=bool)
    first, last = times[changing[0]], times[min(changing[-1] + 1, times.size - 1)]
    pad = margin * (last - first)
    return (times >= first - pad) & (times <= last + pad)


def fig_velocities(d, params, plt):
    data = read_csv(os.path.join(d, "motion.csv"))
    times, bodies, v = _long_table(data, "body", "velocity")
    window = _active_window(times, v)
    kt, ut = scale(times[window], "s")
    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    cmap = matplotlib.colormaps["viridis"]
    shown = bodies if bodies.size <= 12 else bodies[np.linspace(0, bodies.size - 1,
                                                                12).astype(int)]
    for j, body in enumerate(bodies):
        if body not in shown:
            continue
        color = cmap(0.9 * j / max(bodies.size - 1, 1))
        ax.plot(times[window] * kt, v[window, j], lw=1.6, color=color,
                label=f"body {int(body)}")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel(f"time ({ut})")
    ax.set_ylabel("velocity (m/s, positive to the right)")
    ax.set_title("Velocities of the bodies against time\n" + title_of(params), fontsize=11)
    ax.legend(fontsize=8, ncol=2 if len(shown) > 6 else 1)
    ax.grid(alpha=0.3)
    fig.subplots_adjust(bottom=0.14)
    caption(fig, "Bodies numbered from the left; the time axis shows where the velocities "
                 "change.")
    return fig


def fig_force_spacetime(d, params, plt):
    data = read_csv(os.path.join(d, "forces.csv"))
    times, pairs, force = _long_table(data, "pair", "force")
    n = int(params.get("bodies", pairs.max() + 1))
    inner = (pairs >= 1) & (pairs <= n - 1)
    if np.count_nonzero(inner) < 3:
        raise NotApplicable("fewer than 3 pairs of neighbours: no wave to draw")
    pairs, force = pairs[inner], force[:, inner]
    window = _active_window(times, force, margin=0.02)
    kt, ut = scale(times[window], "s")
    kf, uf = scale(force[window], "N")
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    mesh = ax.pcolormesh(times[window] * kt, pairs, (force[window] * kf).T,
                         shading="nearest", cmap="magma_r")
    bar = fig.colorbar(mesh, ax=ax)
    bar.set_label(f"contact force ({uf})")
    ax.set_xlabel(f"time ({ut})")
    ax.set_ylabel("pair (bodies p and p + 1)")
    ax.set_title("The force along the chain in space and time\n" + title_of(params),
                 fontsize=11)
    fig.subplots_adjust(bottom=0.14)
    caption(fig, "Each pair of neighbours is a row; a solitary wave is a band of constant "
                 "width and slope (its speed).")
    return fig


def fig_rebounds(d, params, plt):
    data = read_csv(os.path.join(d, "contacts.csv"))
    g = params.get("gravity", 0.0)
    if not isinstance(g, float) or g == 0.0:
        raise NotApplicable("no gravity: no rebound heights")
    wall = 0 if g < 0 else int(params.get("bodies", 1))
    mask = np.asarray(data["pair"]) == wall
    if np.count_nonzero(mask) < 2:
        raise NotApplicable("fewer than two contacts with the wall below")
    v_in = data["approach_speed"][mask]
    v_out = data["separation_speed"][mask]
    k = data["closed_form_restitution"][mask]
    bounce = np.arange(1, v_out.size + 1)
    height = v_out**2 / (2.0 * abs(g))
    predicted = (k * v_in)**2 / (2.0 * abs(g))
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.5, 7.0), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 2]})
    top.semilogy(bounce, height, "o", ms=3.5, label="rebound height V_out²/(2g)")
    top.semilogy(bounce, predicted, "-", lw=1.0, color="C1",
                 label="closed forms: (k(b V_in) V_in)²/(2g)")
    top.set_ylabel("rebound height (m)")
    top.set_title("Rebound heights of a bouncing ball\n" + title_of(params), fontsize=11)
    top.legend(fontsize=8)
    top.grid(alpha=0.3, which="both")
    bottom.plot(bounce, v_out / v_in, "o", ms=3.5, label="e = V_out/V_in")
    bottom.plot(bounce, k, "-", lw=1.0, color="C1", label="k(b V_in), no gravity in contact")
    bottom.set_xlabel("bounce number")
    bottom.set_ylabel("restitution")
    bottom.legend(fontsize=8)
    bottom.grid(alpha=0.3)
    fig.subplots_adjust(bottom=0.11)
    caption(fig, "The gap between e and k(b V) is gravity acting during the contact; it "
                 "grows as the bounces get slower, until the ball rests.")
    return fig


PLOTTERS = [
    (1, ("phase.csv",), fig_phase),
    (2, ("velocity_z.csv",), fig_velocity_z),
    (3, ("restitution.csv",), fig_restitution),
    (4, ("histories.csv",), fig_histories),
    (5, ("sweep.csv|summary.csv",), fig_peaks),
    (6, ("loops.csv",), fig_loops),
    (7, ("sweep.csv|summary.csv",), fig_energy),
    (8, ("lambertw.csv",), fig_lambertw),
    (9, ("cvode.csv",), fig_work_precision),
    (10, ("legacy.csv",), fig_legacy),
    (11, ("motion.csv",), fig_velocities),
    (12, ("forces.csv",), fig_force_spacetime),
    (13, ("contacts.csv",), fig_rebounds),
]


# ----------------------------------------------------------------------------------
# Figures from Python objects: a fit's data against its model, an impact result
# ----------------------------------------------------------------------------------

#: how each series of a fit is drawn: label, unit, the ImpactResult field of the model
_SERIES = {"contact_time": ("contact time", "s", "contact_time"),
           "peak_force": ("peak force", "N", "peak_force"),
           "restitution": ("restitution k", "", "restitution")}


def _save(fig, path):
    if path:
        partial = f"{path}.partial{os.path.splitext(path)[1]}"
        fig.savefig(partial, bbox_inches="tight")
        os.replace(partial, path)


def plot_fit(fit, path=None):
    """The data of a calibration fit (a ``hcimpact.FitResult``) against the fitted model.

    One panel per measured series: restitution against the speed for ``fit_damping``
    (and the linear law for ``fit_damping_linear``), force against deflection (log-log)
    for ``fit_static``, contact time, peak force and restitution against the speed for
    ``fit_elastic`` and ``fit_impact``, the model from the closed forms at the fitted
    parameters. Returns the Matplotlib figure; with ``path`` it is also written there.
    Needs the library (the model is computed) and Matplotlib.
    """
    _load()
    import matplotlib.pyplot as plt
    import hcimpact

    data, p = fit.data, fit.parameters
    if not data:
        raise ValueError("this FitResult carries no data to plot")
    if fit.kind == "static":
        fig, ax = plt.subplots(figsize=(5.5, 4.0))
        x = data["deflection"]
        grid = np.geomspace(x.min(), x.max(), 200)
        ax.loglog(x, data["force"], "o", label="data")
        ax.loglog(grid, p["stiffness"] * grid**p["exponent"], "-",
                  label=f"c x^n, c = {p['stiffness']:.4g}, n = {p['exponent']:.4g}")
        ax.set_xlabel("deflection x (m)")
        ax.set_ylabel("force F (N)")
        ax.legend()
        _save(fig, path)
        return fig
    v = data["velocity"]
    grid = np.linspace(v.min(), v.max(), 200) if v.max() > v.min() else v[:1]
    names = [n for n in _SERIES if n in data]
    if fit.kind in ("damping", "damping_linear"):
        names = ["restitution"]
    fig, axes = plt.subplots(len(names), 1, figsize=(5.5, 3.2 * len(names)), squeeze=False,
                             sharex=True)
    if fit.kind == "damping":
        model = {"restitution": hcimpact.restitution(p["damping"] * grid)}
        label = f"k(b V), b = {p['damping']:.4g} s/m"
    elif fit.kind == "damping_linear":
        model = {"restitution": 1.0 - (2.0 / 3.0) * p["damping"] * grid}
        label = f"1 - 2 b V/3, b = {p['damping']:.4g} s/m"
    else:
        damping = p.get("damping", fit.fixed.get("damping", 0.0))
        result = hcimpact.impact(mass=fit.fixed["mass"], stiffness=p["stiffness"],
                                 exponent=p["exponent"], damping=damping, velocity=grid)
        model = {n: getattr(result, _SERIES[n][2]) for n in names}
        label = (f"model: c = {p['stiffness']:.4g}, n = {p['exponent']:.4g}, "
                 f"b = {damping:.4g}")
    for ax, name in zip(axes[:, 0], names):
        title, unit, _ = _SERIES[name]
        ax.plot(v, data[name], "o", label="data")
        ax.plot(grid, model[name], "-", label=label)
        ax.set_ylabel(f"{title} ({unit})" if unit else title)
        ax.legend(fontsize=8)
    axes[-1, 0].set_xlabel("approach speed V (m/s)")
    _save(fig, path)
    return fig


def plot_result(result, x=None, xlabel="approach speed V (m/s)", path=None):
    """The outputs of an impact (a ``hcimpact.ImpactResult`` of arrays, from ``impact``
    or ``simulate`` over a 1-D array of contacts) against ``x`` (default: the element
    index): restitution, maximum compression, peak force, contact and compression time.
    Returns the Matplotlib figure; with ``path`` it is also written there.
    """
    _load()
    import matplotlib.pyplot as plt

    k = np.atleast_1d(np.asarray(result.restitution))
    if k.ndim != 1:
        raise ValueError(f"plot_result draws a 1-D result, not one of shape {k.shape}")
    x = np.arange(k.size) if x is None else np.asarray(x, dtype=float)
    if x.shape != k.shape:
        raise ValueError(f"x has shape {x.shape}, the result {k.shape}")
    panels = [("restitution", "restitution k", ""), ("max_compression", "x_max", "m"),
              ("peak_force", "peak force", "N"), ("contact_time", "contact time", "s")]
    fig, axes = plt.subplots(len(panels), 1, figsize=(5.5, 9.0), sharex=True)
    for ax, (name, label, unit) in zip(axes, panels):
        ax.plot(x, np.atleast_1d(getattr(result, name)), "o-", ms=3)
        ax.set_ylabel(f"{label} ({unit})" if unit else label)
    axes[-1].plot(x, np.atleast_1d(result.compression_time), "--",
                  label="compression time")
    axes[-1].legend(fontsize=8)
    axes[-1].set_xlabel(xlabel if x is not None else "element")
    _save(fig, path)
    return fig


def _have(directory, requirement):
    return any(os.path.exists(os.path.join(directory, name)) for name in requirement.split("|"))


def plot_results(directory, out_dir=None, figures=None, dpi=150, fmt="png", log=print):
    """Draw every figure whose CSV files are in ``directory``; returns the paths written.

    out_dir: where the images go (default: ``directory``); figures: numbers to draw
    (default: all); fmt: any format Matplotlib writes (png, pdf, svg)."""
    _load()
    import matplotlib.pyplot as plt

    if not os.path.isdir(directory):
        raise FileNotFoundError(f"{directory}: no such results directory")
    out_dir = out_dir or directory
    os.makedirs(out_dir, exist_ok=True)
    params = read_parameters(directory)
    system = params.get("kind") == "system"
    written = []
    plt.rcParams.update({"figure.dpi": dpi, "savefig.dpi": dpi, "font.size": 10})
    for number, requirements, function in PLOTTERS:
        if figures and number not in figures:
            continue
        missing = [r for r in requirements if not _have(directory, r)]
        name = FIGURES[number]
        if missing:
            # the seed's figures 1-8 are expected of one impact, 11 of a system; the
            # others only when asked for
            if (number <= 8 and not system) or (number == 11 and system) or figures:
                log(f"  skipped {name}: no "
                    f"{', '.join(m.replace('|', ' or ') for m in missing)}")
            continue
        try:
            fig = function(directory, params, plt)
        except NotApplicable as why:
            log(f"  skipped {name}: {why}")
            continue
        path = os.path.join(out_dir, f"{name}.{fmt}")
        partial = path + ".partial." + fmt
        fig.savefig(partial, bbox_inches="tight")
        os.replace(partial, path)
        plt.close(fig)
        written.append(path)
        log(f"  wrote {path}")
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="plot_results",
        description="Draw the figures of an hcimpact results directory (the seed's "
                    "figures 1-8, the CVODE and legacy figures when their data are "
                    "there, and those of a system of bodies: 11-13). Reads the CSV "
                    "files only.")
    parser.add_argument("results", help="results directory written by hcimpact -o DIR")
    parser.add_argument("-o", "--output", help="directory for the images (default: RESULTS)")
    parser.add_argument("--figures", help="comma-separated figure numbers (default: all)")
    parser.add_argument("--format", default="png", help="image format (png, pdf, svg)")
    parser.add_argument("--dpi", type=int, default=150, help="resolution (default 150)")
    args = parser.parse_args(argv)
    figures = None
    if args.figures:
        figures = {int(x) for x in args.figures.split(",") if x.strip()}
    try:
        _load()
        written = plot_results(args.results, args.output, figures, args.dpi, args.format)
    except MissingPackage as exc:
        print(f"plot_results: error: {exc}", file=sys.stderr)
        return 3
    except (FileNotFoundError, ValueError, KeyError) as exc:
        print(f"plot_results: error: {exc}", file=sys.stderr)
        return 2
    if not written:
        print("plot_results: no figure drawn: the directory has none of the CSV files "
              "(run hcimpact --figures -o DIR first)", file=sys.stderr)
        return 1
    print(f"{len(written)} figures written to {args.output or args.results}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
