#!/usr/bin/env python3
"""Plot ff-track-bench --frontier: the heightmap error against the chatter, per class.

Input: the CSV of `ff-track-bench --frontier --csv FILE` ('#' metadata lines,
then one row per class and fade). One panel per class: every fade of the grid
as a dot (heightmap amplitude error while moving, as a ratio to the thesis
pipeline, against the chatter at rest on a log scale), the Pareto front as a
line, the shipping fade as a star and the region that meets both goals
shaded. Prints, per class, the best heightmap ratio at the chatter goal and
whether any fade reaches the goal region; the Pareto front is recomputed here
from the points (not read from the CSV's column), and a disagreement is an
input error.

Example:
  ff-track-bench --frontier --csv frontier.csv
  plot_frontier.py frontier.csv -o frontier.png
Exit codes: 0 ok, 2 bad usage or input (one line on stderr, never a traceback).
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plot_classes import InputError, number, parse_plot_args, read_csv, save_figure  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import ff_files  # noqa: E402

REQUIRED = ("class", "rest_sigmas", "moving_sigmas", "heightmap_vs_thesis", "rest_rms", "pareto", "shipping",
            "heightmap_goal", "rest_goal")


def read_frontier(path):
    """(metadata, {class: [point dicts]}) with the numbers as floats, classes in file order."""
    metadata, rows = read_csv(path, REQUIRED, "ff-track-bench --frontier --csv")
    classes = {}
    for r in rows:
        point = {k: number(r, k) for k in REQUIRED if k != "class"}
        if any(math.isnan(v) for v in point.values()):
            raise InputError("%s: a row of %s has an empty field" % (path, r["class"]))
        classes.setdefault(r["class"], []).append(point)
    return metadata, classes


def pareto(points):
    """The points no other point beats on both heightmap ratio and chatter, by rising chatter."""
    def beats(a, b):
        return (a["heightmap_vs_thesis"] <= b["heightmap_vs_thesis"] and a["rest_rms"] <= b["rest_rms"] and
                (a["heightmap_vs_thesis"] < b["heightmap_vs_thesis"] or a["rest_rms"] < b["rest_rms"]))
    front = [p for p in points if not any(beats(q, p) for q in points)]
    return sorted(front, key=lambda p: (p["rest_rms"], p["heightmap_vs_thesis"]))


def summary(classes):
    """{class: (best heightmap ratio at the chatter goal or None, its point, goal met?)}."""
    out = {}
    for name, points in classes.items():
        quiet = [p for p in points if p["rest_rms"] <= p["rest_goal"]]
        best = min(quiet, key=lambda p: p["heightmap_vs_thesis"]) if quiet else None
        met = best is not None and best["heightmap_vs_thesis"] <= best["heightmap_goal"]
        out[name] = (best, met)
    return out


def check_pareto_column(path, classes):
    for name, points in classes.items():
        ours = {(p["rest_sigmas"], p["moving_sigmas"]) for p in pareto(points)}
        theirs = {(p["rest_sigmas"], p["moving_sigmas"]) for p in points if p["pareto"] == 1}
        if ours != theirs:
            raise InputError("%s: the pareto column of %s disagrees with its points" % (path, name))


def plot(metadata, classes, output):
    n = len(classes)
    cols = min(4, n)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(3.6 * cols + 1, 3.4 * rows + 0.8), squeeze=False)
    floor = min(p["rest_rms"] for points in classes.values() for p in points if p["rest_rms"] > 0) \
        if any(p["rest_rms"] > 0 for points in classes.values() for p in points) else 1e-4
    floor = max(floor * 0.5, 1e-5)  # a chatter of 0 drawn at the bottom edge of the log axis
    for ax, (name, points) in zip(axes.flat, classes.items()):
        def x(p):
            return max(p["rest_rms"], floor)
        goal_hm, goal_rest = points[0]["heightmap_goal"], points[0]["rest_goal"]
        ax.fill_between([floor * 0.5, goal_rest], 0, goal_hm, color="#27ae60", alpha=0.25, label="both goals")
        ax.plot([x(p) for p in points], [p["heightmap_vs_thesis"] for p in points], "o", color="#b0b7c3",
                markersize=4, label="a fade of the grid")
        front = pareto(points)
        ax.plot([x(p) for p in front], [p["heightmap_vs_thesis"] for p in front], "-o", color="#1f5fa8",
                markersize=4, label="Pareto front")
        for p in points:
            if p["shipping"] == 1:
                ax.plot(x(p), p["heightmap_vs_thesis"], "*", color="#c0392b", markersize=13,
                        label="shipping (%.1f / %.1f σ)" % (p["rest_sigmas"], p["moving_sigmas"]))
        ax.axhline(goal_hm, color="#27ae60", linestyle="--", linewidth=1)
        ax.axvline(goal_rest, color="#27ae60", linestyle="--", linewidth=1)
        ax.set_xscale("log")
        ax.set_xlim(floor * 0.5, max(x(p) for p in points) * 2)
        ax.set_ylim(0, max(1.0, max(p["heightmap_vs_thesis"] for p in points) * 1.05))
        ax.set_title(name, fontsize=10)
        ax.set_xlabel("chatter at rest (RMS of A - 0.5)", fontsize=8)
        ax.set_ylabel("heightmap error / thesis", fontsize=8)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=6.5, loc="upper right")
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    save_figure(fig, output, "plot_frontier.py", metadata, "ff-track-bench --frontier: the fade's trade per class",
                dpi=100, top=0.95)


def main(argv=None):
    args = parse_plot_args(argv, __doc__, "ff-track-bench --frontier --csv", "frontier.png")
    try:
        ff_files.refuse_overwriting_inputs([args.output], [args.csv])
        metadata, classes = read_frontier(args.csv)
        check_pareto_column(args.csv, classes)
        plot(metadata, classes, args.output)
    except (InputError, ff_files.OutputIsInput) as e:
        print("plot_frontier.py: %s" % e, file=sys.stderr)
        return 2
    print("%-18s %-34s %s" % ("class", "best heightmap at the chatter goal", "both goals"))
    results = summary(classes)
    for name, (best, met) in results.items():
        cell = "none that quiet" if best is None else "%.2fx (%.1f / %.1f sigma)" % (
            best["heightmap_vs_thesis"], best["rest_sigmas"], best["moving_sigmas"])
        print("%-18s %-34s %s" % (name, cell, "met" if met else "NOT met"))
    print("classes where some fade meets both goals: %d/%d" % (sum(m for _, m in results.values()), len(results)))
    print("wrote %s" % args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
