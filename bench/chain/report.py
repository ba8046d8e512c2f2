#!/usr/bin/env python3
"""Figures and tables of the chain benchmarks (doc/chains-bench.md).

Reads the CSV files that bench/chain/run.sh writes into DIR (scaling.csv, memory.csv,
work_precision_n<N>.csv and reference_n<N>.csv, dilute_times.csv, dilute_accuracy.csv,
machine.txt), writes the figures, replaces the generated sections of the Markdown file
(between <!-- NAME:begin --> and <!-- NAME:end -->, NAME = machine, goals, scaling,
memory, work-precision, dilute) and prints the goal table.

Ratios are medians of per-round ratios (each round measures both sides one after the
other, so that a slow phase of the shared machine slows both); the range after a median
is the smallest and largest per-round value.

Usage: python3 bench/chain/report.py --dir DIR --doc doc/chains-bench.md
                                     --figures doc/figures
"""
import argparse
import csv
import glob
import math
import os
import re
import statistics

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import NullFormatter  # noqa: E402

LABELS = {
    "hcimpact-bdf": "hcimpact (CVODE BDF)",
    "hcimpact-adams": "hcimpact (CVODE Adams)",
    "scipy-radau": "SciPy Radau (sparse J)",
    "scipy-bdf": "SciPy BDF (sparse J)",
    "scipy-dop853": "SciPy DOP853",
}
STYLE = {
    "hcimpact-bdf": dict(color="tab:blue", marker="o"),
    "hcimpact-adams": dict(color="tab:orange", marker="s"),
    "scipy-radau": dict(color="tab:green", marker="^", linestyle="--"),
    "scipy-bdf": dict(color="tab:purple", marker="v", linestyle="--"),
    "scipy-dop853": dict(color="tab:brown", marker="D", linestyle="--"),
}
OURS = ("hcimpact-bdf", "hcimpact-adams")
THEIRS = ("scipy-radau", "scipy-bdf", "scipy-dop853")
ERROR_LEVELS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7)


def read(path):
    with open(path) as fh:
        return list(csv.DictReader(fh))


def f(row, key):
    return float(row[key])


def median_range(xs):
    return statistics.median(xs), min(xs), max(xs)


def fmt_range(xs, spec="%.3g"):
    m, lo, hi = median_range(xs)
    return (spec + " (" + spec + "–" + spec + ")") % (m, lo, hi)


def slope(xs, ys):
    """Least-squares slope of log(ys) against log(xs)."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return (sum((a - mx) * (b - my) for a, b in zip(lx, ly))
            / sum((a - mx) ** 2 for a in lx))


def log_axes(ax):
    """Log scales with labels on the decades only."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.yaxis.set_minor_formatter(NullFormatter())


def replace_section(text, name, body):
    begin, end = "<!-- %s:begin -->" % name, "<!-- %s:end -->" % name
    pattern = re.compile(re.escape(begin) + ".*?" + re.escape(end), re.S)
    if not pattern.search(text):
        raise SystemExit("report.py: no section %s in the document" % name)
    return pattern.sub(lambda _: begin + "\n" + body.rstrip() + "\n" + end, text)


# ---- per-step cost and memory against N ------------------------------------------------

def scaling(rows):
    """Per N: medians over the rounds; per round: the slopes."""
    rows = [r for r in rows if int(r["status"]) == 0]
    sizes = sorted({int(r["n"]) for r in rows})
    rounds = sorted({int(r["round"]) for r in rows})
    by = {(int(r["round"]), int(r["n"])): r for r in rows}
    per_n = {}
    for n in sizes:
        rs = [by[(k, n)] for k in rounds if (k, n) in by]
        per_step = [f(r, "seconds") / f(r, "steps") for r in rs]
        per_n[n] = dict(
            seconds=[f(r, "seconds") for r in rs],
            per_step=per_step,
            per_bead=[s / n for s in per_step],
            steps=int(rs[0]["steps"]), rhs=int(rs[0]["rhs_evals"]),
            jac=int(rs[0]["jacobian_evals"]), front=int(rs[0]["front"]),
            t_end=f(rs[0], "t_end"), rtol=f(rs[0], "rtol"))
    slopes_step, slopes_call = [], []
    for k in rounds:
        ns = [n for n in sizes if (k, n) in by]
        if len(ns) < 2:
            continue
        slopes_step.append(slope(ns, [f(by[(k, n)], "seconds") / f(by[(k, n)], "steps")
                                      for n in ns]))
        slopes_call.append(slope(ns, [f(by[(k, n)], "seconds") for n in ns]))
    return sizes, per_n, slopes_step, slopes_call, len(rounds)


def memory(rows):
    rows = sorted((r for r in rows if int(r["status"]) == 0), key=lambda r: int(r["n"]))
    out = []
    for r in rows:
        n = int(r["n"])
        base, peak = int(r["baseline_kib"]), int(r["peak_kib"])
        out.append(dict(n=n, base=base, peak=peak, extra=peak - base,
                        per_bead=(peak - base) * 1024.0 / n, steps=int(r["steps"])))
    big = [o for o in out if o["n"] >= 1000 and o["extra"] > 0]
    mem_slope = slope([o["n"] for o in big], [o["extra"] for o in big]) if len(big) >= 2 \
        else float("nan")
    return out, mem_slope


def gapped_section(rows):
    """The chain with method auto: only the bodies the wave has reached are integrated."""
    sizes, per_n, _, slopes_call, nrounds = scaling(rows)
    by_n = {}
    for r in rows:
        by_n.setdefault(int(r["n"]), r)
    first = by_n[sizes[0]]
    if f(first, "gap") > 0:
        what = ("The same chain with a gap of %.0e m between all beads (smaller than the "
                "compressions in the wave, which still forms)" % f(first, "gap"))
        grows = "as the wave reaches bodies"
    else:
        what = "The same touching chain with method auto"
        grows = ("as the wave sets beads moving (a touching bead at rest joins when the one "
                 "before it pushes into it)")
    lines = ["%s, until t = %.3g ms: the region integrated grows %s, by a quarter of "
             "itself at a time (each growth is logged as a switch and starts the integrator "
             "anew), and is the same whatever N; %d rounds." % (what, f(first, "t_end") * 1e3,
                                                             grows, nrounds), "",
             "| N | steps | switches logged | bodies integrated at the end | wave at bead "
             "| s per call |", "|---:|---:|---:|---:|---:|---:|"]
    for n in sizes:
        r = by_n[n]
        lines.append("| %d | %s | %s | %s | %s | %s |" % (
            n, r["steps"], r["switches"], r["region"], r["front"],
            fmt_range(per_n[n]["seconds"])))
    lines.append("")
    lines.append("Slope of log(time per call) against log(N): %s." % fmt_range(slopes_call,
                                                                              "%.3f"))
    return "\n".join(lines)


def scaling_sections(sc, mem):
    sizes, per_n, slopes_step, slopes_call, nrounds = sc
    lines = []
    any_n = per_n[sizes[0]]
    lines.append("Struck chain of N touching Hertz beads, method integrated (the whole chain "
                 "is one integrated region), BDF, rtol = %.0e, until t = %.3g ms; %d rounds, each "
                 "size once per round. Time: CPU time of the thread per call of "
                 "`chain_simulate`, median over the rounds (smallest–largest)."
                 % (any_n["rtol"], any_n["t_end"] * 1e3, nrounds))
    lines.append("")
    lines.append("| N | steps | RHS evals | Jacobians | wave at bead | s per call | µs per step "
                 "| ns per step and bead | ms per bead the wave crosses |")
    lines.append("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n in sizes:
        p = per_n[n]
        lines.append("| %d | %d | %d | %d | %d | %s | %s | %s | %s |" % (
            n, p["steps"], p["rhs"], p["jac"], p["front"], fmt_range(p["seconds"]),
            fmt_range([x * 1e6 for x in p["per_step"]]),
            fmt_range([x * 1e9 for x in p["per_bead"]]),
            fmt_range([x * 1e3 / p["front"] for x in p["seconds"]])))
    lines.append("")
    lines.append("Slope of log(time per step) against log(N), fitted over all sizes in each "
                 "round: **%s** (median, smallest–largest over the rounds); of log(time per "
                 "call): %s." % (fmt_range(slopes_step, "%.3f"), fmt_range(slopes_call, "%.3f")))
    scaling_md = "\n".join(lines)

    out, mem_slope = mem
    lines = ["Peak resident set size (getrusage) of a process that builds the chain and "
             "runs it for a few steps (one process per N), against the same process before "
             "the chain is built (the program, the Fortran runtime, SUNDIALS and hcimpact "
             "loaded).", "",
             "| N | steps | before (MiB) | peak (MiB) | added (MiB) | added per bead (bytes) |",
             "|---:|---:|---:|---:|---:|---:|"]
    for o in out:
        lines.append("| %d | %d | %.1f | %.1f | %.1f | %.0f |" % (
            o["n"], o["steps"], o["base"] / 1024.0, o["peak"] / 1024.0, o["extra"] / 1024.0,
            o["per_bead"]))
    lines.append("")
    lines.append("Slope of log(added memory) against log(N) for N ≥ 1000: **%.3f**." % mem_slope)
    return scaling_md, "\n".join(lines)


def figure_scaling(sc, mem, path):
    sizes, per_n, slopes_step, _, _ = sc
    out, mem_slope = mem
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    ax = axes[0]
    med = [statistics.median(per_n[n]["per_step"]) * 1e6 for n in sizes]
    lo = [min(per_n[n]["per_step"]) * 1e6 for n in sizes]
    hi = [max(per_n[n]["per_step"]) * 1e6 for n in sizes]
    ax.errorbar(sizes, med, yerr=[[m - a for m, a in zip(med, lo)],
                                  [b - m for m, b in zip(med, hi)]],
                marker="o", color="tab:blue", capsize=3,
                label="hcimpact, CPU time per step (median, range)")
    ref = [med[0] * n / sizes[0] for n in sizes]
    ax.plot(sizes, ref, color="gray", linestyle=":", label="slope 1")
    log_axes(ax)
    ax.set_xlabel("beads N")
    ax.set_ylabel("µs per integration step")
    ax.set_title("Struck chain: cost of one step (slope %.3f)" % statistics.median(slopes_step),
                 fontsize=11)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=9)
    ax = axes[1]
    ns = [o["n"] for o in out]
    ax.plot(ns, [o["peak"] / 1024.0 for o in out], marker="o", color="tab:red",
            label="peak RSS")
    ax.plot(ns, [max(o["extra"], 1) / 1024.0 for o in out], marker="s", color="tab:orange",
            label="added by the chain")
    log_axes(ax)
    ax.set_xlabel("beads N")
    ax.set_ylabel("MiB")
    ax.set_title("Memory (slope %.3f for N ≥ 1000)" % mem_slope, fontsize=11)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---- work-precision against SciPy --------------------------------------------------------

def wp_points(rows, solver, round_no=None):
    """(rtol, seconds, error) of one solver, one round or the median over rounds."""
    rs = [r for r in rows if r["solver"] == solver and int(r["status"]) == 0
          and f(r, "err_velocity") >= 0]
    by_rtol = {}
    for r in rs:
        if round_no is not None and int(r["round"]) != round_no:
            continue
        by_rtol.setdefault(f(r, "rtol"), []).append(r)
    pts = []
    for rtol in sorted(by_rtol, reverse=True):
        group = by_rtol[rtol]
        pts.append((rtol, statistics.median(f(r, "seconds") for r in group),
                    f(group[0], "err_velocity")))
    return pts


def cost_at(pts, err):
    """Time to reach the error err: log-log interpolation through the points sorted by
    error, each point's time replaced by the least time of the points at least as
    accurate (a tighter tolerance that costs less counts for the solver). None outside
    the errors reached."""
    pts = sorted(((e, t) for _, t, e in pts if e > 0), key=lambda p: p[0])
    if not pts or err < pts[0][0] or err > pts[-1][0]:
        return None
    best = []
    least = float("inf")
    for e, t in pts:
        least = min(least, t)
        best.append((e, least))
    for (e0, t0), (e1, t1) in zip(best, best[1:]):
        if e0 <= err <= e1:
            if e1 == e0:
                return t0
            w = (math.log(err) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + w * (math.log(t1) - math.log(t0)))
    return best[0][1]


def equal_error_ratios(rows, floor):
    """{(ours, theirs, level): [per-round ratio their time / our time]}"""
    rounds = sorted({int(r["round"]) for r in rows})
    out = {}
    for k in rounds:
        curves = {s: wp_points(rows, s, k) for s in OURS + THEIRS}
        for level in ERROR_LEVELS:
            if level < 10 * floor:
                continue
            for o in OURS:
                t_ours = cost_at(curves[o], level)
                if t_ours is None:
                    continue
                for s in THEIRS:
                    t_theirs = cost_at(curves[s], level)
                    if t_theirs is not None:
                        out.setdefault((o, s, level), []).append(t_theirs / t_ours)
    return out


def wp_section(n, rows, ref_rows):
    floor = max(f(r, "err_velocity") for r in ref_rows)
    ref = ref_rows[0]
    nrounds = len({int(r["round"]) for r in rows})
    lines = ["**N = %d beads**, until t = %.3g ms (the wave is then near bead %s). Reference: "
             "SciPy %s DOP853 at rtol %s (%s steps). Its distance to the other tight "
             "solutions (velocity error, relative to the striker's speed):" % (
                 n, f(ref, "t_end") * 1e3, "%s", ref["scipy"], ref["reference_rtol"],
                 ref["reference_steps"]), ""]
    lines.append("| solution | rtol | CPU s | velocity error | position error (of x_ref) |")
    lines.append("|---|---:|---:|---:|---:|")
    for r in ref_rows:
        lines.append("| %s | %.0e | %.3g | %.2e | %.2e |" % (
            r["against"], f(r, "rtol"), f(r, "seconds"), f(r, "err_velocity"),
            f(r, "err_position")))
    lines.append("")
    lines.append("So errors below about %.0e are not resolved; ratios are formed only at "
                 "errors ≥ 10× that." % floor)
    lines.append("")
    lines.append("Each solver over its tolerances (%d rounds; CPU time per call, median over "
                 "the rounds; errors: largest over the beads, velocity relative to the "
                 "striker's speed, position relative to x_ref = %.3g µm):" % (
                     nrounds, f(ref, "x_ref") * 1e6))
    lines.append("")
    lines.append("| solver | rtol | steps | RHS evals | CPU s | velocity error | position error |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|")
    for s in OURS + THEIRS:
        rs = [r for r in rows if r["solver"] == s and int(r["round"]) == 1]
        for r in sorted(rs, key=lambda r: -f(r, "rtol")):
            secs = [f(x, "seconds") for x in rows
                    if x["solver"] == s and x["rtol"] == r["rtol"] and int(x["status"]) == 0]
            if int(r["status"]) != 0 or not secs:
                lines.append("| %s | %.0e | failed | | | | |" % (LABELS[s], f(r, "rtol")))
                continue
            lines.append("| %s | %.0e | %s | %s | %.3g | %.2e | %.2e |" % (
                LABELS[s], f(r, "rtol"), r["steps"], r["rhs_evals"],
                statistics.median(secs), f(r, "err_velocity"), f(r, "err_position")))
    lines.append("")
    ratios = equal_error_ratios(rows, floor)
    lines.append("SciPy's time over hcimpact's at equal velocity error (interpolated on each "
                 "curve, per round; median over the rounds, smallest–largest). Above 1: "
                 "hcimpact is faster.")
    lines.append("")
    header = "| hcimpact | SciPy | " + " | ".join("error %.0e" % e for e in ERROR_LEVELS) + " |"
    lines.append(header)
    lines.append("|---|---|" + "---:|" * len(ERROR_LEVELS))
    for o in OURS:
        for s in THEIRS:
            cells = []
            for e in ERROR_LEVELS:
                xs = ratios.get((o, s, e))
                cells.append(fmt_range(xs, "%.2g") if xs else "–")
            lines.append("| %s | %s | %s |" % (LABELS[o], LABELS[s], " | ".join(cells)))
    text = "\n".join(lines)
    fronts = sorted({r.get("front", "") for r in rows} - {""})
    return text.replace("bead %s", "bead %s" % (fronts[0] if fronts else "?")), ratios, floor


def figure_wp(data, path):
    fig, axes = plt.subplots(1, len(data), figsize=(6.5 * len(data), 5.2), squeeze=False)
    for ax, (n, rows, floor) in zip(axes[0], data):
        for s in OURS + THEIRS:
            pts = wp_points(rows, s)
            if not pts:
                continue
            ax.plot([p[1] for p in pts], [p[2] for p in pts], label=LABELS[s], markersize=5,
                    **STYLE[s])
        ax.axhline(floor, color="gray", linestyle=":", linewidth=1)
        ax.text(0.01, floor, " reference floor", transform=ax.get_yaxis_transform(),
                fontsize=8, color="gray", va="bottom")
        log_axes(ax)
        ax.set_xlabel("CPU time per run (s)")
        ax.set_ylabel("largest velocity error / striker speed")
        ax.set_title("Struck chain, N = %d (lower left is better)" % n, fontsize=11)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---- the dilute systems ------------------------------------------------------------------

def dilute(times, acc):
    cases = []
    for r in times:
        if r["case"] not in cases:
            cases.append(r["case"])
    by = {}
    for r in times:
        by[(r["case"], int(r["round"]), r["method"])] = f(r, "seconds")
    ratios = {}
    for c in cases:
        rounds = sorted({k[1] for k in by if k[0] == c})
        for num in ("bdf", "adams"):
            for den in ("auto", "exact"):
                ratios[(c, num, den)] = [by[(c, k, num)] / by[(c, k, den)] for k in rounds
                                         if (c, k, num) in by and (c, k, den) in by]
        ratios[(c, "times")] = {m: [by[(c, k, m)] for k in rounds if (c, k, m) in by]
                                for m in ("auto", "exact", "bdf", "adams")}
    return cases, ratios


def dilute_section(cases, ratios, acc):
    main_rtol = None
    lines = ["| system | contacts | auto (ms) | exact (ms) | CVODE BDF (ms) | CVODE Adams (ms) "
             "| BDF / auto | Adams / auto |", "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for c in cases:
        t = ratios[(c, "times")]
        row = next(r for r in acc if r["case"] == c and r["method"] == "auto")
        main_rtol = f(row, "rtol")
        lines.append("| %s | %s | %s | %s | %s | %s | **%s** | **%s** |" % (
            c, row["contacts"], fmt_range([x * 1e3 for x in t["auto"]]),
            fmt_range([x * 1e3 for x in t["exact"]]),
            fmt_range([x * 1e3 for x in t["bdf"]]), fmt_range([x * 1e3 for x in t["adams"]]),
            fmt_range(ratios[(c, "bdf", "auto")], "%.0f"),
            fmt_range(ratios[(c, "adams", "auto")], "%.0f")))
    lines.append("")
    lines.append("Accuracy against the exact answer (method auto: every contact by the closed "
                 "forms); CVODE (method integrated) at rtol = %.0e in bold, and as the "
                 "tolerance tightens. Velocity and position errors: largest over the balls at "
                 "the end (m/s with a striker at 1 m/s, and m); separation: the largest "
                 "relative error of the contacts' separation speeds, contacts compared in the "
                 "order they ended." % main_rtol)
    lines.append("")
    lines.append("| system | method | rtol | contacts | closed forms / integrated | steps | "
                 "energy error | velocity error | position error | separation error | CPU ms |")
    lines.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for c in cases:
        rs = [r for r in acc if r["case"] == c]
        for r in rs:
            bold = r["method"] in ("bdf", "adams") and f(r, "rtol") == main_rtol
            exact = r["method"] in ("auto", "exact")
            b = "**" if bold else ""
            lines.append("| %s | %s | %s | %s | %s / %s | %s | %.1e | %s | %s | %s | %.3g |" % (
                c, r["method"], "–" if exact else "%.0e" % f(r, "rtol"), r["contacts"],
                r["closed_form_contacts"], r["integrated_contacts"], r["steps"],
                f(r, "energy_error"),
                "0 (itself)" if r["method"] == "auto" else b + "%.1e" % f(r, "err_velocity") + b,
                "0 (itself)" if r["method"] == "auto" else "%.1e" % f(r, "err_position"),
                "0 (itself)" if r["method"] == "auto" else "%.1e" % f(r, "err_separation"),
                f(r, "seconds") * 1e3))
    return "\n".join(lines)


def figure_dilute(cases, ratios, acc, path):
    fig, axes = plt.subplots(1, len(cases), figsize=(5.2 * len(cases), 4.6), squeeze=False)
    for ax, c in zip(axes[0], cases):
        for m, style in (("bdf", STYLE["hcimpact-bdf"]), ("adams", STYLE["hcimpact-adams"])):
            rs = sorted((r for r in acc if r["case"] == c and r["method"] == m
                         and int(r["status"]) == 0), key=lambda r: -f(r, "rtol"))
            seen, pts = set(), []
            for r in rs:
                if r["rtol"] in seen:
                    continue
                seen.add(r["rtol"])
                pts.append((f(r, "seconds") * 1e3, max(f(r, "err_velocity"), 1e-17)))
            ax.plot([p[0] for p in pts], [p[1] for p in pts], label="integrated, CVODE "
                    + ("BDF" if m == "bdf" else "Adams"), markersize=5, **style)
        t_auto = statistics.median(ratios[(c, "times")]["auto"]) * 1e3
        ax.plot([t_auto], [1e-16], marker="*", markersize=16, color="crimson", linestyle="none",
                label="exact event-driven (auto): its own answer")
        log_axes(ax)
        ax.set_ylim(3e-17, 3)
        ax.set_xlabel("CPU time per run (ms)")
        ax.set_ylabel("largest velocity error (m/s)")
        ax.set_title(c, fontsize=11)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Dilute systems: closed forms against integrating everything "
                 "(rtol 1e-6 … 1e-12)", fontsize=12)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---- the goals ------------------------------------------------------------------------------

def goals_section(sc, mem, wp, cases, dil_ratios, acc):
    lines = ["| goal (issue 15) | measured | met |", "|---|---|---|"]
    if sc:
        s = statistics.median(sc[2])
        lines.append("| per-step cost linear in N: slope of log(time per step) against log(N) "
                     "≤ 1.1 (N = %d … %d) | %s | %s |" % (
                         sc[0][0], sc[0][-1], fmt_range(sc[2], "%.3f"),
                         "yes" if s <= 1.1 else "no"))
    for n, ratios, floor in wp:
        for o in OURS:
            best = []
            for e in ERROR_LEVELS:
                xs = [(statistics.median(ratios[(o, s, e)]), s) for s in THEIRS
                      if (o, s, e) in ratios]
                if xs:
                    best.append((e, *min(xs)))
            cells = "; ".join("%.2g× (%s) at %.0e" % (x, LABELS[s].split(" (")[0], e)
                              for e, x, s in best)
            met = "yes" if best and all(x >= 20 for _, x, _ in best) else "no"
            lines.append("| ≥ 20× faster than SciPy at equal error: N = %d, %s against the "
                         "fastest SciPy method reaching each error | %s | %s |" % (
                             n, LABELS[o], cells or "–", met))
    for c in cases:
        rb = dil_ratios[(c, "bdf", "auto")]
        ra = dil_ratios[(c, "adams", "auto")]
        row = next(r for r in acc if r["case"] == c and r["method"] == "bdf")
        ok = min(statistics.median(rb), statistics.median(ra)) >= 100
        lines.append("| dilute %s: exact path ≥ 100× faster than CVODE at rtol %.0e, and "
                     "more accurate | BDF %s, Adams %s; CVODE's velocity error %.1e m/s | %s |"
                     % (c, f(row, "rtol"), fmt_range(rb, "%.0f"), fmt_range(ra, "%.0f"),
                        f(row, "err_velocity"), "yes" if ok else "no"))
    if mem:
        lines.append("| memory O(N) | slope %.3f of the added peak RSS for N ≥ 1000; %.0f bytes "
                     "per bead at N = %d | %s |" % (
                         mem[1], mem[0][-1]["per_bead"], mem[0][-1]["n"],
                         "yes" if mem[1] <= 1.1 else "no"))
    return "\n".join(lines)


# ---- the dilute row ----------------------------------------------------------------------

def row_section(rows):
    """Table of the dilute row: per size, the medians over the rounds of method auto's
    time and of the whole row integrated (where run), their per-round ratio, and the
    work of the last round."""
    sizes = sorted({int(r["n"]) for r in rows})
    lines = ["| beads | contacts | clusters | closed forms / integrated contacts | CVODE steps "
             "| auto (s) | per contact (us) | whole row integrated (s) | integrated / auto "
             "| energy error (auto) | velocity difference (m/s) |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for n in sizes:
        auto = [r for r in rows if int(r["n"]) == n and r["method"] == "auto"]
        whole = [r for r in rows if int(r["n"]) == n and r["method"] == "integrated"]
        if not auto:
            continue
        last = auto[-1]
        if last["status"] != "0":
            lines.append("| %d | status %s | | | | | | | | | |" % (n, last["status"]))
            continue
        t_auto = [f(r, "seconds") for r in auto]
        per_contact = [1e6 * f(r, "seconds") / max(int(r["contacts"]), 1) for r in auto]
        cells = ["%d" % n, last["contacts"], last["clusters"],
                 "%s / %s" % (last["closed_form_contacts"], last["integrated_contacts"]),
                 last["steps"], fmt_range(t_auto), fmt_range(per_contact)]
        if whole and all(r["status"] == "0" for r in whole):
            rounds = {int(r["round"]): f(r, "seconds") for r in auto}
            ratio = [f(r, "seconds") / rounds[int(r["round"])] for r in whole
                     if int(r["round"]) in rounds]
            cells += [fmt_range([f(r, "seconds") for r in whole]), fmt_range(ratio)]
            dv = "%.1e" % max(f(r, "dv_from_auto") for r in whole)
        else:
            cells += ["not run", ""]
            dv = ""
        cells += ["%.1e" % f(last, "energy_error"), dv]
        lines.append("| " + " | ".join(cells) + " |")
    t_end, rtol = rows[0]["t_end"], rows[0]["rtol"]
    lines.append("")
    lines.append("To t = %s s at rtol %s; times are medians (range) over %d rounds, ratios "
                 "formed within each round. The velocity difference is the largest between "
                 "the whole row integrated and method auto."
                 % (float(t_end), float(rtol), len({r["round"] for r in rows})))
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", required=True)
    ap.add_argument("--doc", required=True)
    ap.add_argument("--figures", required=True)
    a = ap.parse_args()
    os.makedirs(a.figures, exist_ok=True)
    with open(a.doc) as fh:
        doc = fh.read()

    machine = os.path.join(a.dir, "machine.txt")
    if os.path.exists(machine):
        with open(machine) as fh:
            doc = replace_section(doc, "machine", "```\n" + fh.read().rstrip() + "\n```")

    sc = mem = None
    if os.path.exists(os.path.join(a.dir, "scaling.csv")):
        sc = scaling(read(os.path.join(a.dir, "scaling.csv")))
    if os.path.exists(os.path.join(a.dir, "memory.csv")):
        mem = memory(read(os.path.join(a.dir, "memory.csv")))
    if sc and mem:
        scaling_md, memory_md = scaling_sections(sc, mem)
        touching = os.path.join(a.dir, "scaling_auto.csv")
        if os.path.exists(touching):
            scaling_md += "\n\n" + gapped_section(read(touching))
        gapped = os.path.join(a.dir, "scaling_gap.csv")
        if os.path.exists(gapped):
            scaling_md += "\n\n" + gapped_section(read(gapped))
        doc = replace_section(doc, "scaling", scaling_md)
        doc = replace_section(doc, "memory", memory_md)
        figure_scaling(sc, mem, os.path.join(a.figures, "chain_scaling.png"))

    wp, wp_text, wp_fig = [], [], []
    for path in sorted(glob.glob(os.path.join(a.dir, "work_precision_n*.csv")),
                       key=lambda p: int(re.search(r"_n(\d+)\.csv$", p).group(1))):
        n = int(re.search(r"_n(\d+)\.csv$", path).group(1))
        rows = read(path)
        ref_rows = read(os.path.join(a.dir, "reference_n%d.csv" % n))
        text, ratios, floor = wp_section(n, rows, ref_rows)
        wp.append((n, ratios, floor))
        wp_text.append(text)
        wp_fig.append((n, rows, floor))
    if wp:
        doc = replace_section(doc, "work-precision", "\n\n".join(wp_text))
        figure_wp(wp_fig, os.path.join(a.figures, "chain_work_precision.png"))

    cases, dil_ratios, acc = [], {}, []
    if os.path.exists(os.path.join(a.dir, "dilute_times.csv")):
        acc = read(os.path.join(a.dir, "dilute_accuracy.csv"))
        cases, dil_ratios = dilute(read(os.path.join(a.dir, "dilute_times.csv")), acc)
        doc = replace_section(doc, "dilute", dilute_section(cases, dil_ratios, acc))
        figure_dilute(cases, dil_ratios, acc, os.path.join(a.figures, "chain_dilute.png"))

    if os.path.exists(os.path.join(a.dir, "row.csv")):
        doc = replace_section(doc, "row", row_section(read(os.path.join(a.dir, "row.csv"))))

    goals = goals_section(sc, mem, wp, cases, dil_ratios, acc)
    doc = replace_section(doc, "goals", goals)
    with open(a.doc, "w") as fh:
        fh.write(doc)
    print(goals)


if __name__ == "__main__":
    main()
