#!/usr/bin/env python3
"""Plot ff-track-bench --classes against issue 14's goals.

Input: the CSV of `ff-track-bench --classes --csv FILE` ('#' metadata lines,
then one row per class and tracker). Four panels, one group of bars per
class: the heightmap and frictionmap amplitude errors as ratios to the
thesis pipeline, the lag, and the chatter at rest; goals as dashed lines
(the heightmap's is 0.35x on white-200hz, 0.45x elsewhere). The heightmap
panel also marks the start floor (direction known after 1 px of motion),
the shipping tracker unfaded, and the best constant-velocity filter with a
perfect motion detector, causal and seeing 30 ms ahead, and the observer told everything but where each
stroke goes (no tracker that assumes nothing about it does better); the chatter panel marks what is left after the
first 100 ms of each rest. A table of which goals each class meets is
printed.

Example:
  ff-track-bench --classes --csv classes.csv
  plot_classes.py classes.csv -o classes.png
Exit codes: 0 ok, 2 bad usage or input (one line on stderr, never a traceback).
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import ff_files  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

GOAL_HEIGHTMAP = 0.45
GOAL_HEIGHTMAP_WHITE = 0.35
GOAL_FRICTIONMAP = 0.8
GOAL_LAG_MS = 1.0
GOAL_CHATTER = 0.01
SHIPPING = "recommended(profile)"
TRACKERS = ("recommended()", SHIPPING)
REQUIRED = ("class", "tracker", "lag_ms", "heightmap_vs_thesis", "frictionmap_vs_thesis", "rest_rms",
            "rest_steady_rms", "floor_1.0px_rms", "unfaded_heightmap_rms", "heightmap_rms", "lookahead_0ms_rms",
            "lookahead_30ms_rms", "anchored_0ms_rms", "heading_bound_rms", "direction_bound_rms")


class InputError(Exception):
    pass


def parse_plot_args(argv, doc, what, default_output):
    """The command line both plot scripts take: the CSV and -o PNG."""
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0],
                                     epilog="Exit codes: 0 ok, 2 bad usage or input.")
    parser.add_argument("csv", help="the CSV of %s" % what)
    parser.add_argument("-o", "--output", default=default_output, help="the PNG to write (default: %(default)s)")
    return parser.parse_args(argv)


def save_figure(fig, output, software, metadata, title, dpi, top):
    """Title the figure with the CSV's traces and tool, lay it out under the title (up to `top` of the
    height), write the PNG with the CSV's metadata in it, and close the figure."""
    fig.suptitle("%s; %s; %s" % (title, metadata.get("traces", "generated traces"), metadata.get("tool", "")),
                 fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, top))
    ff_files.save_figure(fig, output, software, "; ".join("%s: %s" % kv for kv in metadata.items()), dpi=dpi)
    plt.close(fig)


def read_csv(path, required, what):
    """(metadata dict, [row dicts]) of an ff-track-bench CSV: '#' metadata lines, then a header and rows."""
    metadata, lines = {}, []
    try:
        with open(path, newline="") as f:
            for line in f:
                if line.startswith("#"):
                    key, _, value = line[1:].strip().partition(":")
                    metadata[key.strip()] = value.strip()
                elif line.strip():
                    lines.append(line)
    except OSError as e:
        raise InputError("cannot read %s: %s" % (path, e.strerror))
    rows = list(csv.DictReader(lines))
    if not rows:
        raise InputError("%s: no rows (is it the CSV of %s?)" % (path, what))
    missing = [c for c in required if c not in rows[0]]
    if missing:
        raise InputError("%s: not the CSV of %s: no column %s" % (path, what, ", ".join(missing)))
    return metadata, rows


def read_classes(path):
    """(metadata dict, [row dicts]) of a --classes CSV."""
    return read_csv(path, REQUIRED, "ff-track-bench --classes --csv")


def number(row, key):
    value = row.get(key) or ""  # None: the row is short
    try:
        return float(value) if value != "" else float("nan")
    except ValueError:
        where = "/".join(row.get(k, "") for k in ("class", "tracker") if row.get(k))
        raise InputError("%s of %s is not a number: %r" % (key, where, value))


def heightmap_goal(trace_class):
    return GOAL_HEIGHTMAP_WHITE if trace_class == "white-200hz" else GOAL_HEIGHTMAP


def goal_status(rows):
    """{class: {goal: met?}} for the shipping tracker's rows."""
    status = {}
    for r in rows:
        if r["tracker"] != SHIPPING:
            continue
        c = r["class"]
        status[c] = {
            "lag": number(r, "lag_ms") <= GOAL_LAG_MS,
            "heightmap": number(r, "heightmap_vs_thesis") <= heightmap_goal(c),
            "frictionmap": number(r, "frictionmap_vs_thesis") <= GOAL_FRICTIONMAP,
            "chatter": number(r, "rest_rms") <= GOAL_CHATTER,
        }
    return status


def plot(metadata, rows, output):
    classes = []
    for r in rows:
        if r["class"] not in classes:
            classes.append(r["class"])
    by = {(r["class"], r["tracker"]): r for r in rows}
    x = range(len(classes))
    width = 0.38
    fig, axes = plt.subplots(2, 2, figsize=(13, 8.5))
    panels = [
        (axes[0][0], "heightmap_vs_thesis", "heightmap amplitude error / thesis", None),
        (axes[0][1], "frictionmap_vs_thesis", "frictionmap amplitude error / thesis", GOAL_FRICTIONMAP),
        (axes[1][0], "lag_ms", "lag [ms]", GOAL_LAG_MS),
        (axes[1][1], "rest_rms", "chatter at rest: RMS of A - 0.5 (log)", GOAL_CHATTER),
    ]
    colours = {"recommended()": "#9db4d6", SHIPPING: "#1f5fa8"}
    for ax, key, title, goal in panels:
        for k, tracker in enumerate(TRACKERS):
            values = [number(by[(c, tracker)], key) if (c, tracker) in by else float("nan") for c in classes]
            ax.bar([i + (k - 0.5) * width for i in x], values, width, label=tracker, color=colours[tracker])
        if goal is not None:
            ax.axhline(goal, color="#c0392b", linestyle="--", linewidth=1.2, label="goal")
        ax.set_title(title, fontsize=11)
        ax.set_xticks(list(x))
        ax.set_xticklabels(classes, rotation=30, ha="right", fontsize=9)
        ax.grid(axis="y", alpha=0.3)
    hm = axes[0][0]
    goals = [heightmap_goal(c) for c in classes]
    hm.hlines(goals, [i - 0.5 for i in x], [i + 0.5 for i in x], colors="#c0392b", linestyles="--", linewidth=1.2,
              label="goal")
    shipping = [by.get((c, SHIPPING)) for c in classes]
    thesis_hm = [number(by[(c, "thesis")], "heightmap_rms") if (c, "thesis") in by else float("nan") for c in classes]
    floor = [number(s, "floor_1.0px_rms") / t if s else float("nan") for s, t in zip(shipping, thesis_hm)]
    unfaded = [number(s, "unfaded_heightmap_rms") / t if s else float("nan") for s, t in zip(shipping, thesis_hm)]
    hm.plot([i + 0.5 * width for i in x], unfaded, "D", color="#e67e22", label=SHIPPING + ", never faded")
    hm.plot([i + 0.5 * width for i in x], floor, "v", color="#27ae60", label="start floor (direction after 1 px)")
    for key, marker, colour, label in (("lookahead_0ms_rms", "_", "#000000", "best CV filter, perfect motion detector"),
                                       ("lookahead_30ms_rms", "x", "#7f8c8d", "the same, seeing 30 ms ahead"),
                                       ("anchored_0ms_rms", "+", "#8e44ad",
                                        "the same, held at rest, perfect start detector"),
                                       ("heading_bound_rms", "^", "#f1c40f",
                                        "heading model, told every standstill"),
                                       ("direction_bound_rms", "*", "#145a32",
                                        "told all but each stroke's direction (a floor)"),
                                       # Optional: CSVs before round 12 have no such column (NaN: not drawn).
                                       ("predicted_ends_rms", "p", "#d35400",
                                        "heading model, min-jerk ends predicted")):
        bound = [number(s, key) / t if s else float("nan") for s, t in zip(shipping, thesis_hm)]
        hm.plot([i + 0.5 * width for i in x], bound, marker, color=colour, markersize=14 if marker == "_" else 8,
                markeredgewidth=2, label=label)
    chatter = axes[1][1]
    chatter.set_yscale("log")
    steady = [number(s, "rest_steady_rms") if s else float("nan") for s in shipping]
    chatter.plot([i + 0.5 * width for i in x], steady, "o", color="#e67e22",
                 label=SHIPPING + ", after the first 100 ms of each rest")
    predicted_rest = [number(s, "predicted_ends_rest_rms") if s else float("nan") for s in shipping]
    chatter.plot([i + 0.5 * width for i in x], predicted_rest, "p", color="#d35400",
                 label="heading model, ends predicted (not a tracker)")
    for ax in (hm, axes[0][1], axes[1][0], chatter):  # room above the bars for the legend
        low, high = ax.get_ylim()
        ax.set_ylim(low, high * 8.0 if ax is chatter else high * 1.5)
        handles, labels = ax.get_legend_handles_labels()
        unique = dict(zip(labels, handles))
        ax.legend(unique.values(), unique.keys(), fontsize=8, loc="upper left", ncol=2)
    save_figure(fig, output, "plot_classes.py", metadata, "ff-track-bench --classes against issue 14's goals",
                dpi=110, top=0.96)


def main(argv=None):
    args = parse_plot_args(argv, __doc__, "ff-track-bench --classes --csv", "classes.png")
    try:
        ff_files.refuse_overwriting_inputs([args.output], [args.csv])
        metadata, rows = read_classes(args.csv)
        status = goal_status(rows)
        if not status:
            raise InputError("%s: no %s rows" % (args.csv, SHIPPING))
        plot(metadata, rows, args.output)
    except (InputError, ff_files.OutputIsInput) as e:
        print("plot_classes.py: %s" % e, file=sys.stderr)
        return 2
    names = ("lag", "heightmap", "frictionmap", "chatter")
    print("%-18s %s" % ("class", " ".join("%-11s" % n for n in names)))
    for c, met in status.items():
        print("%-18s %s" % (c, " ".join("%-11s" % ("met" if met[n] else "NOT met") for n in names)))
    totals = ", ".join("%s %d/%d" % (n, sum(m[n] for m in status.values()), len(status)) for n in names)
    print("goals met (%s): %s" % (SHIPPING, totals))
    print("wrote %s" % args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
