#!/usr/bin/env python3
"""Figure and tables of the CVODE benchmark (doc/cvode.md).

Reads the CSV files written by bench_cvode_work_precision, scipy_work_precision.py and
bench_cvode_stability; writes the work-precision figure and replaces the generated
sections of the Markdown file (between the markers <!-- NAME:begin --> and
<!-- NAME:end -->, NAME = work-precision, goals, stability), and prints the headline
numbers.

Usage: python3 bench/cvode/report.py --dir DIR --doc doc/cvode.md
                                     --figure doc/figures/work_precision.png
   DIR holds work_precision.csv, scipy_work_precision.csv, stability.csv and, from
   bench_cvode_goal_ratio, goal_ratio.csv and goal_ratio_machine.txt (run.sh).
"""
import argparse
import csv
import math
import os
import re
import statistics

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OUTPUTS = ("contact", "restitution", "x_max", "peak_force")
LABELS = {
    "closed": "closed forms (hcimpact)",
    "bdf": "CVODE BDF",
    "adams": "CVODE Adams",
    "scipy-radau": "SciPy Radau",
    "scipy-lsoda": "SciPy LSODA",
    "scipy-dop853": "SciPy DOP853",
}
STYLE = {
    "bdf": dict(color="tab:blue", marker="o"),
    "adams": dict(color="tab:orange", marker="s"),
    "scipy-radau": dict(color="tab:green", marker="^", linestyle="--"),
    "scipy-lsoda": dict(color="tab:purple", marker="v", linestyle="--"),
    "scipy-dop853": dict(color="tab:brown", marker="D", linestyle="--"),
}
STEEL = 2          # the steel ball at V = 1 m/s
STIFF = 16         # n = 1.5, beta = 1e4


def read(path):
    with open(path) as fh:
        return list(csv.DictReader(fh))


def num(row, key):
    return float(row[key])


def max_err(row):
    return max(num(row, "err_" + k) for k in OUTPUTS)


def ok(row):
    return int(row["status"]) == 0


def geomean(xs):
    return math.exp(sum(math.log(x) for x in xs) / len(xs))


def by_method(rows):
    out = {}
    for r in rows:
        out.setdefault(r["method"], []).append(r)
    return out


def curves(rows, case=None):
    """method -> sorted list of (rtol, seconds, error) over one case or all cases."""
    res = {}
    for method, rs in by_method(rows).items():
        if method == "closed":
            continue
        pts = {}
        for r in rs:
            if case is not None and int(r["case"]) != case:
                continue
            pts.setdefault(float(r["rtol"]), []).append(r)
        line = []
        for rtol in sorted(pts, reverse=True):
            group = pts[rtol]
            if not all(ok(r) for r in group):
                continue
            t = geomean([num(r, "seconds") for r in group])
            e = max(max_err(r) for r in group)
            line.append((rtol, t, e))
        res[method] = line
    return res


def closed_points(rows, case=None):
    rs = [r for r in rows if r["method"] == "closed" and (case is None or int(r["case"]) == case)]
    t = geomean([num(r, "seconds") for r in rs])
    e = max(max_err(r) for r in rs)
    u = max(max(num(r, "ulps_" + k) for k in OUTPUTS) for r in rs)
    return t, e, u


def figure(rows, path):
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.4), sharey=True)
    panels = [(STEEL, "Steel ball, V = 1 m/s (n = 1.5, \u03b2 = 0.1)"),
              (STIFF, "Stiff: n = 1.5, \u03b2 = 1e4"),
              (None, "All 21 contacts (geometric-mean time, worst error)")]
    for ax, (case, title) in zip(axes, panels):
        for method, line in curves(rows, case).items():
            if not line:
                continue
            ax.plot([p[1] * 1e6 for p in line], [max(p[2], 1e-17) for p in line],
                    label=LABELS[method], markersize=5, **STYLE[method])
            for rtol, t, e in line:
                if method == "bdf" and rtol in (1e-4, 1e-8, 1e-12):
                    ax.annotate("rtol %.0e" % rtol, (t * 1e6, max(e, 1e-17)),
                                textcoords="offset points", xytext=(6, -10), fontsize=7,
                                color=STYLE["bdf"]["color"])
        t, e, u = closed_points(rows, case)
        ax.plot([t * 1e6], [max(e, 1e-17)], marker="*", markersize=16, color="crimson",
                linestyle="none", label=LABELS["closed"] + ", ≤ %.1f ulp" % closed_points(rows)[2])
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(title, fontsize=11)
        ax.set_xlabel("CPU time per impact (\u00b5s)")
        ax.grid(True, which="major", alpha=0.4)
        ax.grid(True, which="minor", alpha=0.1)
    axes[0].set_ylabel("largest relative error of contact time, k, x_max, F_max")
    axes[0].set_ylim(3e-18, 3e-1)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=6, fontsize=9, frameon=False)
    fig.suptitle("Error against run time: closed forms, CVODE and SciPy on the same impacts "
                 "(lower left is better)", fontsize=13)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def fmt_e(x):
    if x < 0:
        return "fail"
    if x == 0:
        return "0"
    return "%.1e" % x


def fmt_us(s):
    us = s * 1e6
    return "%.0f" % us if us >= 10 else "%.1f" % us


def work_precision_table(rows):
    lines = ["| method | rtol | CPU time (µs), median over contacts | worst contact-time error "
             "| worst error of the 4 outputs | steps (median) | RHS evals (median) |",
             "|---|---|---|---|---|---|---|"]
    t, e, u = closed_points(rows)
    closed = [r for r in rows if r["method"] == "closed"]
    lines.append("| closed forms | — | %s | %s (%.1f ulp) | %s (%.1f ulp) | — | — |" % (
        fmt_us(statistics.median(num(r, "seconds") for r in closed)),
        fmt_e(max(num(r, "err_contact") for r in closed)),
        max(num(r, "ulps_contact") for r in closed), fmt_e(e), u))
    for method in ("bdf", "adams", "scipy-radau", "scipy-lsoda", "scipy-dop853"):
        for rtol in (1e-4, 1e-6, 1e-8, 1e-10, 1e-12):
            rs = [r for r in rows if r["method"] == method and abs(float(r["rtol"]) / rtol - 1) < 1e-6]
            if not rs:
                continue
            good = [r for r in rs if ok(r)]
            fails = len(rs) - len(good)
            steps = statistics.median(float(r["steps"]) for r in good) if "steps" in good[0] and good[0].get("steps") else None
            lines.append("| %s | %.0e | %s | %s | %s%s | %s | %s |" % (
                LABELS[method], rtol,
                fmt_us(statistics.median(num(r, "seconds") for r in good)),
                fmt_e(max(num(r, "err_contact") for r in good)),
                fmt_e(max(max_err(r) for r in good)),
                " (%d failed)" % fails if fails else "",
                "%.0f" % steps if steps is not None else "—",
                "%.0f" % statistics.median(float(r["rhs_evals"]) for r in good)))
    return "\n".join(lines)


def goals(rows, ratio_rows=None, machine=None):
    out = []
    # 1. contact time within 100 rtol for rtol 1e-4 ... 1e-11, every contact
    worst = {}
    bad = []
    for r in rows:
        if r["method"] not in ("bdf", "adams"):
            continue
        rtol = float(r["rtol"])
        if rtol > 1.0001e-4 or rtol < 0.9999e-11:
            continue
        ratio = num(r, "err_contact") / rtol if ok(r) else math.inf
        key = r["method"]
        if ratio > worst.get(key, (0,))[0]:
            worst[key] = (ratio, r)
        if ratio > 100:
            bad.append(r)
    n_runs = sum(1 for r in rows if r["method"] in ("bdf", "adams")
                 and 0.9999e-11 <= float(r["rtol"]) <= 1.0001e-4)
    out.append(("contact time within 100 rtol, rtol = 1e-4 ... 1e-11, every contact "
                "(BDF and Adams: %d runs)" % n_runs,
                "met" if not bad else "missed in %d runs" % len(bad),
                "; ".join("worst %s: %.1f rtol (contact %s, n = %s, \u03b2 = %s, rtol %s)"
                          % (LABELS[m], w[0], w[1]["case"], float(w[1]["n"]),
                             "%g" % float(w[1]["beta"]), "%.0e" % float(w[1]["rtol"]))
                          for m, w in sorted(worst.items()))))
    # 2. closed forms >= 100x faster than CVODE at rtol = 1e-10; 3. >= 1e4x more accurate
    closed = {int(r["case"]): r for r in rows if r["method"] == "closed"}
    speed = {}
    acc = {}
    for r in rows:
        if r["method"] in ("bdf", "adams") and abs(float(r["rtol"]) / 1e-10 - 1) < 1e-6 and ok(r):
            c = closed[int(r["case"])]
            speed.setdefault(r["method"], []).append(num(r, "seconds") / num(c, "seconds"))
            ce = max(max_err(c), 2.0 ** -53)
            acc.setdefault(r["method"], []).append(max_err(r) / ce)
    how = "the times of the work-precision runs (each contact repeated)"
    if ratio_rows:
        # issue 17's protocol (goal_ratio.f90): per contact the median of per-round ratios
        speed = {"adams": [float(r["ratio_adams"]) for r in ratio_rows],
                 "bdf": [float(r["ratio_bdf"]) for r in ratio_rows]}
        how = ("per contact the median of per-round ratios, shared libraries, contacts in "
               "a fresh random order every pass (goal_ratio.csv)")
    sp = "; ".join("%s: %.1f\u00d7 (median over the contacts), %.1f\u00d7 to %.1f\u00d7" % (
        LABELS[m], statistics.median(v), min(v), max(v)) for m, v in sorted(speed.items()))
    sp += "; " + how
    below = sorted(set(i for v in speed.values() for i, x in enumerate(v) if x < 100))
    smed = min(statistics.median(v) for v in speed.values())
    smin = min(min(v) for v in speed.values())
    if smin >= 100:
        verdict = "met (every contact)"
    elif smed >= 100:
        verdict = ("met in the median; %d of %d contacts below (%.0f\u00d7 at worst)"
                   % (len(below), len(list(speed.values())[0]), smin))
    else:
        verdict = "missed (median %.0f\u00d7)" % smed
    out.append(("closed forms at least 100\u00d7 faster than CVODE at rtol = 1e-10",
                verdict, sp))
    ac = "; ".join("%s: %.1e\u00d7 (median), at least %.1e\u00d7" % (
        LABELS[m], statistics.median(v), min(v)) for m, v in sorted(acc.items()))
    amin = min(min(v) for v in acc.values())
    out.append(("closed forms at least 1e4\u00d7 more accurate than CVODE at rtol = 1e-10",
                "met" if amin >= 1e4 else "missed", ac +
                " (closed-form error floored at 2^-53 where it rounds to 0)"))
    lines = ["| goal | result | numbers |", "|---|---|---|"]
    for g, res, nums in out:
        lines.append("| %s | **%s** | %s |" % (g, res, nums))
    if ratio_rows:
        lines += goal_ratio_table(ratio_rows, machine)
    # equal-error comparison: the cheapest CVODE run whose error reaches 1e-12
    lines.append("")
    lines.append("Equal error. No CVODE or SciPy run reaches the closed forms' accuracy; "
                 "the closest each comes, on the steel ball at V = 1 m/s:")
    lines.append("")
    lines.append("| method | best error reached | at rtol | CPU time (µs) | closed forms faster by |")
    lines.append("|---|---|---|---|---|")
    c = closed[STEEL]
    for method in ("bdf", "adams", "scipy-radau", "scipy-lsoda", "scipy-dop853"):
        rs = [r for r in rows if r["method"] == method and int(r["case"]) == STEEL and ok(r)]
        if not rs:
            continue
        best = min(rs, key=max_err)
        lines.append("| %s | %s | %s | %s | %.0f\u00d7 |" % (
            LABELS[method], fmt_e(max_err(best)), "%.0e" % float(best["rtol"]),
            fmt_us(num(best, "seconds")),
            num(best, "seconds") / num(c, "seconds")))
    lines.append("| %s | %s (%.1f ulp) | — | %s | 1 |" % (
        LABELS["closed"], fmt_e(max_err(c)),
        max(num(c, "ulps_" + k) for k in OUTPUTS), fmt_us(num(c, "seconds"))))
    return "\n".join(lines), out


def goal_ratio_table(ratio_rows, machine):
    """The speed ratio per contact under issue 17's protocol (goal_ratio.f90)."""
    lines = [""]
    if machine:
        lines.append("Run: " + "; ".join(machine) + ".")
        lines.append("")
    lines.append("Speed per contact at rtol = 1e-10 (issue 17's protocol: the shared libraries "
                 "through their Fortran API; every call timed alone in thread CPU time, the "
                 "clock's cost of %.2f \u00b5s subtracted; the closed forms in passes over all "
                 "21 contacts in a fresh random order, CVODE's 42 solves likewise, interleaved "
                 "in each round; times the medians over the rounds, ratios the medians of the "
                 "per-round ratios with the smallest and largest round in brackets. \"Old "
                 "protocol\": in the same rounds, each contact repeated in a batch, 64 calls of "
                 "the closed forms, 4 solves of CVODE, the clock read once a batch; the last "
                 "column is the closed forms' batch time over their time in random order):"
                 % (1e6 * float(ratio_rows[0]["clock_seconds"])))
    lines.append("")
    lines.append("| contact | n | \u03b2 | V | closed forms (\u00b5s) | CVODE Adams (\u00b5s) "
                 "| CVODE BDF (\u00b5s) | Adams / closed | BDF / closed "
                 "| old protocol: Adams, BDF / closed | closed forms: batch / random order |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|")

    def spread(r, key, fmt):
        return ("%s (%s\u2013%s)" % (fmt % float(r[key]), fmt % float(r[key + "_min"]),
                                        fmt % float(r[key + "_max"])))
    for r in ratio_rows:
        lines.append("| %s | %g | %g | %g | %.2f | %.0f | %.0f | %s | %s | %.0f\u00d7, %.0f\u00d7 "
                     "| %s |" % (
                         r["case"], float(r["n"]), float(r["beta"]), float(r["V"]),
                         1e6 * float(r["closed_seconds"]), 1e6 * float(r["adams_seconds"]),
                         1e6 * float(r["bdf_seconds"]),
                         spread(r, "ratio_adams", "%.0f\u00d7"),
                         spread(r, "ratio_bdf", "%.0f\u00d7"),
                         float(r["old_ratio_adams"]), float(r["old_ratio_bdf"]),
                         spread(r, "ratio_batch", "%.2f")))
    med = {k: statistics.median(float(r[k]) for r in ratio_rows)
           for k in ("closed_seconds", "adams_seconds", "bdf_seconds", "ratio_adams",
                     "ratio_bdf", "old_ratio_adams", "old_ratio_bdf", "ratio_batch")}
    low = {k: min(float(r[k]) for r in ratio_rows) for k in ("ratio_adams", "ratio_bdf")}
    lines.append("| median over the contacts | | | | %.2f | %.0f | %.0f | %.0f\u00d7 (smallest "
                 "contact %.0f\u00d7) | %.0f\u00d7 (smallest contact %.0f\u00d7) "
                 "| %.0f\u00d7, %.0f\u00d7 | %.2f |" % (
                     1e6 * med["closed_seconds"], 1e6 * med["adams_seconds"],
                     1e6 * med["bdf_seconds"], med["ratio_adams"], low["ratio_adams"],
                     med["ratio_bdf"], low["ratio_bdf"], med["old_ratio_adams"],
                     med["old_ratio_bdf"], med["ratio_batch"]))
    return lines


def stability_tables(rows):
    # per (n, beta): worst over the sizes
    keys = []
    for r in rows:
        k = (float(r["n"]), float(r["beta"]))
        if k not in keys:
            keys.append(k)
    lines = ["| n | \u03b2 | contacts run (skipped) | closed forms | stiffness ratio "
             "max\u2006|\u03bb|\u00b7t_c | BDF 1e-8: status, steps, RHS, µs | "
             "Adams 1e-8: status, steps, RHS, µs | worst difference / rtol (BDF, Adams; 1e-4 and 1e-8) |",
             "|---|---|---|---|---|---|---|---|"]
    summary = {"runs": 0, "ok": 0, "status": 0, "nan": 0, "closed_nan": 0,
               "closed_status": 0, "worst_ratio": (0.0, None), "messages": {}}
    for n, beta in keys:
        rs = [r for r in rows if float(r["n"]) == n and float(r["beta"]) == beta]
        run = [r for r in rs if r["method"] != "skipped"]
        skipped = len(set((r["m"], r["c"], r["V"]) for r in rs if r["method"] == "skipped"))
        sizes = len(set((r["m"], r["c"], r["V"]) for r in run))
        closed_status = sorted(set(int(r["closed_status"]) for r in run))
        closed_finite = all(int(r["closed_finite"]) == 1 for r in run if int(r["closed_status"]) == 0)
        if not closed_finite:
            summary["closed_nan"] += 1
        summary["closed_status"] += sum(1 for r in run if int(r["closed_status"]) != 0) // 4
        cs = "ok" if closed_status == [0] else "status " + "/".join(str(s) for s in closed_status)

        def cell(method):
            group = [r for r in run if r["method"] == method and float(r["rtol"]) == 1e-8]
            if not group:
                return "—"
            st = sorted(set(int(r["status"]) for r in group))
            steps = max(int(r["steps"]) for r in group)
            rhs = max(int(r["rhs_evals"]) for r in group)
            us = max(float(r["seconds"]) for r in group) * 1e6
            s = "ok" if st == [0] else "status " + "/".join(str(x) for x in st)
            return "%s, %d, %d, %.0f" % (s, steps, rhs, us)

        stiff = [float(r["stiffness_ratio"]) for r in run if ok(r) and r["method"] == "bdf"]
        ratios = []
        for method in ("bdf", "adams"):
            rr = []
            for r in run:
                if r["method"] != method:
                    continue
                summary["runs"] += 1
                if ok(r):
                    if int(r["finite"]) != 1:
                        summary["nan"] += 1
                    summary["ok"] += 1
                    d = max(float(r["diff_" + k]) for k in OUTPUTS)
                    if d >= 0:
                        q = d / float(r["rtol"])
                        rr.append(q)
                        if q > summary["worst_ratio"][0]:
                            summary["worst_ratio"] = (q, r)
                else:
                    summary["status"] += 1
                    msg = re.sub(r"t = [-+.0-9Ee]+ s", "t = ...", r["message"])
                    summary["messages"][msg] = summary["messages"].get(msg, 0) + 1
            ratios.append("%.0f" % max(rr) if rr else "—")
        lines.append("| %g | %g | %d (%d) | %s | %s | %s | %s | %s |" % (
            n, beta, sizes, skipped, cs,
            "%.1e" % max(stiff) if stiff else "—", cell("bdf"), cell("adams"),
            ", ".join(ratios)))
    return "\n".join(lines), summary


def replace_section(text, name, body):
    begin = "<!-- %s:begin -->" % name
    end = "<!-- %s:end -->" % name
    pattern = re.compile(re.escape(begin) + ".*?" + re.escape(end), re.S)
    if not pattern.search(text):
        raise SystemExit("report.py: markers for %s not found" % name)
    return pattern.sub(lambda m: begin + "\n" + body + "\n" + end, text)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", required=True)
    ap.add_argument("--doc")
    ap.add_argument("--figure")
    args = ap.parse_args()
    wp = read(os.path.join(args.dir, "work_precision.csv"))
    sp_path = os.path.join(args.dir, "scipy_work_precision.csv")
    if os.path.exists(sp_path):
        wp += read(sp_path)
    st_path = os.path.join(args.dir, "stability.csv")
    if args.figure:
        figure(wp, args.figure)
        print("figure: %s" % args.figure)
    table = work_precision_table(wp)
    ratio_path = os.path.join(args.dir, "goal_ratio.csv")
    ratio_rows = read(ratio_path) if os.path.exists(ratio_path) else None
    machine_path = os.path.join(args.dir, "goal_ratio_machine.txt")
    machine = None
    if os.path.exists(machine_path):
        with open(machine_path) as fh:
            machine = [" ".join(line.split()) for line in fh if line.strip()]
    goal_md, goal_list = goals(wp, ratio_rows, machine)
    print(table)
    print()
    print(goal_md)
    st_md = None
    if os.path.exists(st_path):
        st_md, summary = stability_tables(read(st_path))
        worst = summary["worst_ratio"]
        extra = ""
        if worst[1] is not None:
            w = worst[1]
            extra = " (%s, n = %g, \u03b2 = %g, m = %g, c = %g, V = %g, rtol %g)" % (
                LABELS[w["method"]], float(w["n"]), float(w["beta"]), float(w["m"]),
                float(w["c"]), float(w["V"]), float(w["rtol"]))
        st_md += ("\n\nCVODE runs: %d; finished: %d (NaN or Inf in a finished outcome: %d); "
                  "ended with a status: %d. Largest difference from the closed forms: "
                  "%.0f rtol%s.\n" % (summary["runs"], summary["ok"], summary["nan"],
                                       summary["status"], worst[0], extra))
        if summary["messages"]:
            st_md += "\nStatuses returned (count, message):\n\n"
            for msg, count in sorted(summary["messages"].items(), key=lambda kv: -kv[1]):
                st_md += "- %d \u00d7 %s\n" % (count, msg)
        print(st_md)
    if args.doc:
        with open(args.doc) as fh:
            text = fh.read()
        text = replace_section(text, "work-precision", table)
        text = replace_section(text, "goals", goal_md)
        if st_md is not None:
            text = replace_section(text, "stability", st_md.rstrip())
        with open(args.doc, "w") as fh:
            fh.write(text)
        print("updated %s" % args.doc)


if __name__ == "__main__":
    main()
