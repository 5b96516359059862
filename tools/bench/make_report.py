#!/usr/bin/env python3
"""Merges ff-bench (host: errors, memory, host ns) and ff-m4bench (Cortex-M4F
instructions under qemu) into docs/benchmarks.md, a CSV and a PNG plot, and
checks the goals of issue 5. Run by scripts/run-benchmarks."""
import argparse
import csv
import datetime
import math
import os
import platform
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import ff_files  # noqa: E402

BUDGET_CYCLES = 90_000      # one 500 us tick at 180 MHz
CLOCK_HZ = 180e6            # Teensy 3.6
PREPARE_GOAL_INSTR = 360_000  # 2 ms at 180 MHz, 1 instruction ~ 1 cycle
TICK_GOAL_INSTR = 1_000
ERROR_GOAL_LSB = 1.0

# The columns the report reads from each of ff-bench's, the cycle model's and ff-m4accuracy's CSVs.
HOST_CASE_COLUMNS = ("id", "scene", "strategy", "builtin", "default", "table_bytes", "plan_bytes", "fits_teensy",
                     "gradient_evaluations", "max_g_core", "max_g_ref", "max_lsb", "rms_lsb", "p99_lsb",
                     "max_interior_lsb", "worst_x", "worst_y", "worst_direction_deg", "eval_checksum", "host_eval_ns",
                     "host_prepare_us", "host_tick_ns")
HOST_CASE_WHOLE_NUMBERS = ("table_bytes", "plan_bytes", "fits_teensy", "gradient_evaluations", "eval_checksum")
CYCLE_NUMBERS = ("cycles_best_mean", "cycles_worst_mean", "cycles_best_p99.9", "cycles_worst_p99.9", "cycles_best_max",
                 "cycles_worst_max", "prepare_ms_best", "prepare_ms_worst")  # added up or given to %.2f
CYCLE_COLUMNS = ("scene", "instructions_mean", "instructions_p99.9", "instructions_max", "worst_tick_kind",
                 "prepare_instructions", "isr_best", "isr_worst") + CYCLE_NUMBERS
ACCURACY_COLUMNS = ("scene", "points", "raw_max_lsb", "scaled_max_lsb", "scaled_rms_lsb", "code_max_lsb", "codes_off")

# ff-m4bench's lines (tools/m4bench/main.cpp; its '#' lines name the fields): every field after the kind is a
# whole number but a mode, an id or a name. A tracker line from before its setup costs were timed ends at max_instr.
M4_FIELDS = {
    "m4bench": ("mode",),
    "calibration": ("instructions_per_count",),
    "case": ("id", "default", "prepare_instr", "gradient_evaluations", "table_bytes", "plan_bytes", "eval_instr",
             "evaluations", "eval_checksum", "tick_instr", "ticks", "tick_max_instr", "tick_dac_sum",
             "pipeline_prepare_instr"),
    "tracker": ("name", "instr", "ticks", "max_instr", "configure_instr", "fade_noise_instr"),
    "component": ("name", "instr", "count"),
    "stopwatch_overhead_milli": ("overhead_milli",),
    "done": ("failures",),
}
M4_TEXT_FIELDS = ("mode", "id", "name")
M4_OPTIONAL_FIELDS = ("configure_instr", "fade_noise_instr")
M4_DIVISORS = {"case": "evaluations", "tracker": "ticks", "component": "count"}  # what a total is divided by


class BadInput(Exception):
    """An input file that is malformed or incomplete: one line, exit 2 (docs/tools.md)."""


def parse_args():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--host", required=True, help="folder with host_cases.csv and host_trackers.csv")
    p.add_argument("--m4", help="ff-m4bench output (optional: host-only report without it)")
    p.add_argument("--md", required=True)
    p.add_argument("--csv", required=True)
    p.add_argument("--png", required=True)
    p.add_argument("--png-link", help="how the markdown refers to the PNG (default: relative path)")
    p.add_argument("--environment", default="", help="one line describing how the numbers were made")
    p.add_argument("--cycles", help="cycles.csv of tools/cyclemodel (exact instructions, modelled MK66 cycles)")
    p.add_argument("--m4-accuracy", help="CSV of ff-m4accuracy (the M4 build's amplitudes against the reference)")
    return p.parse_args()


def fnum(text):
    try:
        v = float(text)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def text_lines(path):
    """The lines of an input; one that is not UTF-8 text is refused with its name (a UnicodeDecodeError has none)."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as f:
            return f.readlines()
    except UnicodeDecodeError as e:
        raise BadInput("%s: not UTF-8 text (%s)" % (path, e)) from None


def read_host(folder):
    cases = read_plain_csv(os.path.join(folder, "host_cases.csv"), HOST_CASE_COLUMNS, HOST_CASE_WHOLE_NUMBERS)
    trackers = {}
    path = os.path.join(folder, "host_trackers.csv")
    if os.path.exists(path):
        for row in read_plain_csv(path, ("config", "host_update_ns")):
            trackers[row["config"]] = fnum(row["host_update_ns"])
    return cases, trackers


def error_grid_text(host_folder):
    """The error grid ff-bench says it used ('# run: ..., error grid every S px, ...' in
    host_cases.csv), its points counted as ReferenceGrid makes them (tools/bench/accuracy.cpp)."""
    step = None
    with open(os.path.join(host_folder, "host_cases.csv")) as f:
        for line in f:
            if line.startswith("# run:") and " error grid every " in line:
                step = fnum(line.split(" error grid every ", 1)[1].split(" px", 1)[0])
    if not step or step <= 0:
        return "ff-bench's grid (its step not recorded in host_cases.csv"
    xs, ys = [], []
    x = 0.5
    while x <= 799.0:
        xs.append(x)
        x += step
    y = 0.5
    while y <= 479.0:
        ys.append(y)
        y += step
    return "the grid x = 0.5, %g, … %g, y = 0.5 … %g (%s points" % (
        0.5 + step, xs[-1], ys[-1], "{:,}".format(len(xs) * len(ys)))


def read_m4(path):
    m4 = {"cases": {}, "trackers": {}, "components": {}, "calibration": None, "done": None, "errors": [],
          "mode": None}
    if not path:
        return None
    for number, line in enumerate(text_lines(path), start=1):
        fields = line.strip().split(",")
        kind = fields[0]
        if kind in M4_FIELDS:
            check_m4_line(path, number, fields)
        if kind == "m4bench":
            m4["mode"] = fields[1]
        elif kind == "calibration":
            m4["calibration"] = int(fields[1])
        elif kind == "case":
            (_, cid, default, prepare, grad_evals, table_bytes, plan_bytes, eval_instr, evaluations,
             checksum, tick_instr, ticks, tick_max, tick_dac_sum, pipeline_prepare) = fields
            m4["cases"][cid] = {
                "prepare": int(prepare), "gradient_evaluations": int(grad_evals),
                "table_bytes": int(table_bytes), "plan_bytes": int(plan_bytes),
                "eval": int(eval_instr) / int(evaluations), "checksum": int(checksum),
                "tick": int(tick_instr) / int(ticks) if int(ticks) > 0 else None,
                "tick_max": int(tick_max) if int(ticks) > 0 else None,
                "pipeline_prepare": int(pipeline_prepare) if int(pipeline_prepare) >= 0 else None,
            }
        elif kind == "tracker":
            m4["trackers"][fields[1]] = {"mean": int(fields[2]) / int(fields[3]), "max": int(fields[4]),
                                         "configure": int(fields[5]) if len(fields) > 5 else None,
                                         "fade_noise": int(fields[6]) if len(fields) > 6 else None}
        elif kind == "component":
            m4["components"][fields[1]] = int(fields[2]) / int(fields[3])
        elif kind == "stopwatch_overhead_milli":
            m4["stopwatch"] = int(fields[1]) / 1000
        elif kind == "error":
            m4["errors"].append(",".join(fields[1:]))
        elif kind == "done":
            m4["done"] = int(fields[1])
    return m4


def check_m4_line(path, number, fields):
    """A line of a kind the report reads, cut short, too long or with a count that is no whole number (or 0 where
    it divides), is refused with its line: a half-written or edited file, never figures made up from it."""
    kind = fields[0]
    names = M4_FIELDS[kind]
    fewest, most = 1 + len([n for n in names if n not in M4_OPTIONAL_FIELDS]), 1 + len(names)
    if not fewest <= len(fields) <= most:
        wanted = "%d" % most if fewest == most else "%d to %d" % (fewest, most)
        raise BadInput("%s:%d: a %s line of %d fields, ff-m4bench writes %s" % (
            path, number, kind, len(fields), wanted))
    for name, value in zip(names, fields[1:]):
        if name in M4_TEXT_FIELDS:
            continue
        try:
            count = int(value)
        except ValueError:
            raise BadInput("%s:%d: %s %s '%s' is not a whole number" % (path, number, kind, name, value)) from None
        if name == M4_DIVISORS.get(kind) and count < 1:
            raise BadInput("%s:%d: %s %s is %d: nothing was measured" % (path, number, kind, name, count))


def check_m4_complete(m4, path):
    """ff-m4bench writes its calibration first and 'done' last."""
    if m4["done"] is None:
        raise BadInput("%s is incomplete (no done line): did the harness crash?" % path)
    if m4["calibration"] is None:
        raise BadInput("%s is incomplete (no calibration line)" % path)


def check_m4_measured_every_closed_form(m4, path, host_cases, host_cases_path):
    """ff-m4bench measures every closed form, a smoke run too: the rows the M4 goals are worked out from. One that
    ff-bench measured and the harness did not is a line lost, or a harness of another build."""
    missing = [h["id"] for h in host_cases if h["strategy"] == "closed-form" and h["id"] not in m4["cases"]]
    if missing:
        raise BadInput("%s is incomplete (no case line for %s, which %s has)" % (
            path, ", ".join(missing), host_cases_path))


# Singular spots of the built-in fields, to say where an error sits.
CONE_APEX = {"heightmap-top": (700, 40), "heightmap-middle": (700, 240), "heightmap-bottom": (700, 440),
             "general-3": (700, 40), "general-6": (700, 40)}
TUNNEL_ENDS = {"tunnel-pilot-a": (100, 500), "tunnel-pilot-b": (100, 500), "general-6": (100, 500)}


def where(row):
    x, y = fnum(row["worst_x"]), fnum(row["worst_y"])
    if x is None or fnum(row["max_lsb"]) is None or fnum(row["max_lsb"]) < 1.0:
        return ""
    spacing = 1.0
    if row["strategy"].startswith("table-"):
        spacing = float(row["strategy"].split("-")[1].rstrip("px"))
    apex = CONE_APEX.get(row["scene"])
    if apex and math.hypot(x - apex[0], y - apex[1]) <= 3 * spacing + 1:
        return "cone apex"
    ends = TUNNEL_ENDS.get(row["scene"])
    if ends and min(abs(x - e) for e in ends) <= spacing + 1:
        return "tunnel end (x = %g)" % min(ends, key=lambda e: abs(x - e))
    if min(x, y, 799 - x, 479 - y) <= spacing + 1:
        return "screen edge"
    return "valley floor or curvature (x %g, y %g)" % (x, y)


def merge(host_cases, m4):
    rows = []
    for h in host_cases:
        r = dict(h)
        r["memory_bytes"] = int(h["table_bytes"] or 0) + int(h["plan_bytes"] or 0)
        r["fits_teensy"] = int(h["fits_teensy"])
        r["where"] = where(h)
        mg, mr = fnum(h["max_g_core"]), fnum(h["max_g_ref"])
        r["max_g_rel_error"] = abs(mg / mr - 1.0) if mg is not None and mr else None
        m = m4["cases"].get(h["id"]) if m4 else None
        r["m4"] = m
        r["m4_eval"] = m["eval"] if m else None
        r["m4_prepare"] = m["prepare"] if m else None
        r["m4_tick"] = m["tick"] if m else None
        r["m4_tick_max"] = m["tick_max"] if m else None
        r["m4_tick_estimated"] = False
        r["checksum_match"] = (m["checksum"] == int(h["eval_checksum"])) if m else None
        rows.append(r)
    # A table too big for the pipeline's slot has no measured whole tick: estimate it from the
    # scene's closed-form tick, swapping the closed form's evaluation for this strategy's.
    by_id = {r["id"]: r for r in rows}
    for r in rows:
        if r["m4"] and r["m4_tick"] is None:
            base = by_id.get(r["scene"] + "/closed-form")
            if base and base["m4_tick"] is not None:
                r["m4_tick"] = base["m4_tick"] - base["m4_eval"] + r["m4_eval"]
                r["m4_tick_estimated"] = True
    return rows


def fmt(v, digits=3):
    if v is None:
        return "–"
    if abs(v) >= 1000:
        return "{:,.0f}".format(v)
    if abs(v) >= 100:
        return "%.0f" % v
    return ("%." + str(digits) + "g") % v


def kib(b):
    b = int(b)
    if b == 0:
        return "0"
    if b < 1024:
        return "%d B" % b
    return ("%.1f KiB" % (b / 1024)) if b < 1024 * 1024 else ("%.2f MiB" % (b / 1048576))


def p99_text(v):
    return "< 0.01" if v is not None and 0 < v < 0.01 else fmt(v)  # the histogram's resolution


def ms_at_180(instr):
    return None if instr is None else instr / CLOCK_HZ * 1e3


def tick_text(r):
    return ("≈" if r["m4_tick_estimated"] else "") + fmt(r["m4_tick"])


def pareto(points):
    """Points (x, y) on the lower-left front: no other point is cheaper and at least as accurate."""
    front = []
    best = math.inf
    for x, y in sorted(points):
        if y < best:
            front.append((x, y))
            best = y
    return front


FAMILIES = [
    ("closed-form", "closed form", "#000000", "o"),
    ("float-gradient", "table, float, gradient", "#1f77b4", "s"),
    ("int16-gradient", "table, int16, gradient", "#17becf", "s"),
    ("float-height-cd", "table, float, height + central diff.", "#d62728", "^"),
    ("int16-height-cd", "table, int16, height + central diff.", "#ff9896", "^"),
    ("float-profile", "table, float, profile", "#2ca02c", "D"),
    ("int16-profile", "table, int16, profile", "#98df8a", "D"),
]


def family(strategy):
    for key, label, color, marker in FAMILIES:
        if strategy == key or strategy.endswith(key):
            return key, label, color, marker
    return FAMILIES[0]


def plot(rows, path, have_m4, metadata=()):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    panels = ["heightmap-top", "heightmap-middle", "tunnel-pilot-a", "tunnel-pilot-b", "pilot-c-top",
              "bump-map", "frictionmap-top", "familiarisation-path", "general-6"]
    fig, axes = plt.subplots(3, 3, figsize=(15, 13), constrained_layout=True)
    floor = 1e-4
    for ax, scene in zip(axes.flat, panels):
        pts = []
        for r in rows:
            if r["scene"] != scene:
                continue
            x = r["m4_tick"] if have_m4 else fnum(r["host_eval_ns"])
            y = fnum(r["max_lsb"])
            if x is None or y is None:
                continue
            y = max(y, floor)
            _, _, color, marker = family(r["strategy"])
            size = 12 + 220 * math.sqrt(r["memory_bytes"] / 3.1e6)
            filled = r["fits_teensy"] == 1
            ax.scatter([x], [y], s=size, marker=marker, facecolors=color if filled else "none",
                       edgecolors=color, linewidths=1.2, alpha=0.85, zorder=3)
            if r["strategy"] == "closed-form" or r["strategy"].startswith("table-4px") and "int16" in r["strategy"]:
                ax.annotate(r["strategy"].replace("table-", ""), (x, y), fontsize=7, xytext=(4, 3),
                            textcoords="offset points")
            pts.append((x, y))
        front = pareto(pts)
        if front:
            fx, fy = zip(*front)
            ax.step(fx, fy, where="post", color="grey", linestyle="--", linewidth=1, zorder=2)
        ax.axhline(ERROR_GOAL_LSB, color="green", linewidth=0.8, linestyle=":")
        if have_m4:
            ax.axvline(TICK_GOAL_INSTR, color="green", linewidth=0.8, linestyle=":")
        ax.set_yscale("log")
        ax.set_ylim(floor / 2, 5000)
        ax.set_title(scene)
        ax.set_xlabel("M4 instructions per whole tick (≈ = estimated)" if have_m4 else "host ns per evaluation")
        ax.set_ylabel("max amplitude error, DAC LSB")
        ax.grid(True, which="both", alpha=0.2)
    handles = [Line2D([], [], marker=m, color=c, linestyle="", label=l) for _, l, c, m in FAMILIES]
    handles.append(Line2D([], [], marker="s", markerfacecolor="none", color="grey", linestyle="",
                          label="hollow: does not fit the Teensy's 96 KiB table slot"))
    handles.append(Line2D([], [], color="grey", linestyle="--", label="Pareto front"))
    handles.append(Line2D([], [], color="green", linestyle=":", label="goals: 1 LSB, 1,000 instructions"))
    fig.legend(handles=handles, loc="outside lower center", ncol=4, fontsize=9)
    fig.suptitle("Cost against error for every evaluation strategy (marker area ~ table + plan bytes; "
                 "errors below 1e-4 LSB drawn at 1e-4)")
    ff_files.save_figure(fig, path, "tools/bench/make_report.py", "; ".join(
        ["every evaluation strategy's cost against its error"] + ["%s: %s" % kv for kv in metadata if kv[0] != "what"]),
        dpi=90, bbox_inches="tight")


def write_csv(rows, path, metadata):
    cols = ["id", "scene", "strategy", "default", "fits_teensy", "table_bytes", "plan_bytes", "max_lsb", "p99_lsb",
            "rms_lsb", "max_interior_lsb", "worst_x", "worst_y", "worst_direction_deg", "where", "max_g_core",
            "max_g_ref", "m4_eval_instr", "m4_tick_instr", "m4_tick_estimated", "m4_tick_max_instr",
            "m4_prepare_instr", "gradient_evaluations", "host_eval_ns", "host_prepare_us", "host_tick_ns",
            "checksum_match"]
    ff_files.write_whole(path, lambda f: write_csv_rows(rows, cols, f, metadata))


def write_csv_rows(rows, cols, f, metadata):
    for key, value in metadata:
        f.write("# %s: %s\n" % (key, value))
    w = csv.writer(f)
    w.writerow(cols)
    for r in rows:
        def g(v, d=6):
            return "" if v is None else (("%." + str(d) + "g") % v if isinstance(v, float) else v)
        w.writerow([r["id"], r["scene"], r["strategy"], r["default"], r["fits_teensy"], r["table_bytes"],
                    r["plan_bytes"], r["max_lsb"], r["p99_lsb"], r["rms_lsb"], r["max_interior_lsb"],
                    r["worst_x"], r["worst_y"], r["worst_direction_deg"], r["where"], r["max_g_core"],
                    r["max_g_ref"], g(r["m4_eval"], 5), g(r["m4_tick"], 5), int(r["m4_tick_estimated"]),
                    g(r["m4_tick_max"]), g(r["m4_prepare"]), r["gradient_evaluations"], r["host_eval_ns"],
                    r["host_prepare_us"], r["host_tick_ns"],
                    "" if r["checksum_match"] is None else int(r["checksum_match"])])


def host_cpu():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "?"


def default_choice_text(rows, have_m4):
    """Which strategy each built-in scene uses and why, from the numbers."""
    lines = []
    scenes = [r["scene"] for r in rows if r["default"] == "1" and r["builtin"] == "1"]
    for scene in scenes:
        mine = [r for r in rows if r["scene"] == scene]
        default = next(r for r in mine if r["default"] == "1")
        good = [r for r in mine if (fnum(r["max_lsb"]) or 0) <= ERROR_GOAL_LSB and r["fits_teensy"]
                and r["id"] != default["id"]]
        if not good:
            lines.append("%s: only its %s is within 1 LSB" % (scene, default["strategy"]))
        else:
            alt = ", ".join("%s (%s LSB%s)" % (r["strategy"], fmt(fnum(r["max_lsb"])),
                                                ", %s instr/tick" % fmt(r["m4_tick"]) if r["m4_tick"] else "")
                            for r in good)
            lines.append("%s: also within 1 LSB and fitting the Teensy: %s" % (scene, alt))
    alone = sum(1 for l in lines if "only its" in l)
    return ("Every built-in scene defaults to its closed form: it needs no table RAM and is the most accurate "
            "strategy; for %d of the %d built-in scenes it is the only one within 1 LSB that fits the Teensy "
            "(the tables' worst spots are under *Where the error goes*). Per scene: " % (alone, len(lines)) +
            "; ".join(lines) + ".")


def table_saving_text(rows, have_m4):
    if not have_m4:
        return ""
    parts = []
    for scene in sorted({r["scene"] for r in rows}):
        mine = [r for r in rows if r["scene"] == scene]
        closed = next((r for r in mine if r["strategy"] == "closed-form"), None)
        tables = [r for r in mine if r["strategy"] != "closed-form" and r["fits_teensy"] and r["m4_tick"]
                  and not r["m4_tick_estimated"]]
        if not closed or not closed["m4_tick"] or not tables:
            continue
        best = min(tables, key=lambda r: r["m4_tick"])
        change = 100 * (best["m4_tick"] / closed["m4_tick"] - 1)
        parts.append("%s %s %% (%s, %s LSB)" % (scene, "±0" if abs(change) < 0.5 else "%+.0f" % change,
                                                   best["strategy"], fmt(fnum(best["max_lsb"]))))
    grad = [r["m4_eval"] for r in rows if r["strategy"].endswith("gradient") and r["m4_eval"]]
    hcd = [r["m4_eval"] for r in rows if r["strategy"].endswith("height-cd") and r["m4_eval"]]
    return ("Whole tick with the cheapest measured table that fits, against the closed form (and that table's "
            "max error): " + "; ".join(parts) + ". A bilinear gradient table costs the same whatever the scene "
            "(%s–%s instructions per evaluation), height + central differences %s–%s (four bilinear samples). "
            "Tables save time only where the closed form is expensive (sin/cos in the bump map, six elements); "
            "elsewhere the tick's fixed costs (tracker, amplitude map) dominate." % (
                fmt(min(grad)) if grad else "–", fmt(max(grad)) if grad else "–",
                fmt(min(hcd)) if hcd else "–", fmt(max(hcd)) if hcd else "–"))


def error_analysis(rows):
    out = []
    closed = [r for r in rows if r["strategy"] == "closed-form" and fnum(r["max_g_ref"])]
    if closed:
        worst = max(closed, key=lambda r: fnum(r["max_lsb"]) or 0)
        rel = max((r["max_g_rel_error"] or 0) for r in closed)
        out.append("Closed forms: at most %s LSB (%s). The core's max|G| (coarse scan + compass search) "
                   "is within %.1e of the reference's everywhere, worth at most %.3f LSB (0.5 x relative "
                   "error x 4095); the rest is float rounding." % (
                       fmt(fnum(worst["max_lsb"])), worst["scene"], rel, 0.5 * rel * 4095))
    tables = [r for r in rows if r["strategy"].startswith("table-") and (fnum(r["max_lsb"]) or 0) >= 1.0]
    counts = {}
    for r in tables:
        key = r["where"].split(" (")[0]
        counts[key] = counts.get(key, 0) + 1
    if counts:
        out.append("Tables over 1 LSB, by where their worst sample sits: " + ", ".join(
            "%s %d" % (k, v) for k, v in sorted(counts.items(), key=lambda kv: -kv[1])) + " (of %d)." % len(tables))
    apex = [r for r in tables if r["where"] == "cone apex" and "gradient" in r["strategy"]]
    if apex:
        best = min(apex, key=lambda r: fnum(r["max_lsb"]))
        out.append("Cone apex: the cone's gradient turns through 180 degrees across the target point, which "
                   "bilinear interpolation of a gradient table cannot follow at any spacing (best: %s %s, "
                   "%s LSB); away from it the same table has p99 %s LSB." % (
                       best["scene"], best["strategy"], fmt(fnum(best["max_lsb"])), fmt(fnum(best["p99_lsb"]))))
    hcd = [r for r in rows if r["strategy"].endswith("height-cd")]
    if hcd:
        edge = [r for r in hcd if r["where"] == "screen edge"]
        # The bump map is smooth everywhere: its interior error is the method's, its edge error the clamp's.
        example = next((r for r in hcd if r["id"] == "bump-map/table-4px-float-height-cd"), None) or hcd[0]
        out.append("Height + central differences: %d of %d have their worst sample on the screen edge, where "
                   "`ScenePlan::scaled_field` samples one spacing outside the table; `GridTable` clamps the "
                   "position, so the difference spans one spacing but is divided by two: the gradient "
                   "across the edge is halved (%s: %s LSB at the edge, %s LSB at least 16 px inside). "
                   "One-sided differences at the border (or a one-node margin) would fix it." % (
                       len(edge), len(hcd), example["id"], fmt(fnum(example["max_lsb"])),
                       fmt(fnum(example["max_interior_lsb"]))))
    tun = [r for r in tables if r["where"].startswith("tunnel end")]
    if tun:
        out.append("Tunnel ends (x = 100 and 500): the width's slope jumps there, so G_x is discontinuous "
                   "and tables smear it over one spacing (%d strategies)." % len(tun))
    prof = [r for r in rows if r["strategy"].endswith("profile")]
    if prof:
        best = min(prof, key=lambda r: fnum(r["max_lsb"]))
        out.append("Position-only (profile) tables: bilinear interpolation rounds the corners where the flat "
                   "slippery band meets the 20 px quintic feather (best: %s %s, %s LSB)." % (
                       best["scene"], best["strategy"], fmt(fnum(best["max_lsb"]))))
    return out


CYCLE_GOAL_PERCENT = 2.0  # of the 90,000-cycle budget, at a scene's worst modelled tick
PREPARE_GOAL_MS = 2.0


def read_plain_csv(path, columns=(), whole_numbers=(), numbers=()):
    """The rows after a CSV's '#' metadata lines, as dicts (None without a path). Refused with the file (and
    line): a column the report reads missing, a row with more or fewer fields than the header, a count that is
    no whole number or a figure the report adds up that is no number."""
    if not path:
        return None
    numbered = [(number, line) for number, line in enumerate(text_lines(path), start=1) if not line.startswith("#")]
    records = csv.reader(line for _, line in numbered)
    header = next(records, [])
    missing = [c for c in columns if c not in header]
    if missing:
        raise BadInput("%s: no column %s" % (path, ", ".join(missing)))
    rows = []
    for (number, _), fields in zip(numbered[1:], records):  # a row per line: none of these CSVs quotes a newline
        if not fields:
            continue  # a blank line
        if len(fields) != len(header):
            raise BadInput("%s:%d: %d fields, the header names %d" % (path, number, len(fields), len(header)))
        row = dict(zip(header, fields))
        for column in whole_numbers:
            try:
                int(row[column])
            except ValueError:
                raise BadInput("%s:%d: %s '%s' is not a whole number" % (path, number, column, row[column])) from None
        for column in numbers:
            if fnum(row[column]) is None:
                raise BadInput("%s:%d: %s '%s' is not a number" % (path, number, column, row[column]))
        rows.append(row)
    return rows


def pct_range(lo, hi):
    return "%.2f–%.2f %%" % (100 * lo / BUDGET_CYCLES, 100 * hi / BUDGET_CYCLES)


def cycles_section(cycles, accuracy):
    """Markdown lines: per built-in scene, exact instructions, modelled cycles (range) and % of budget."""
    out = []
    w = out.append
    w("## Cycles on the MK66 (modelled), per built-in scene")
    w("")
    isr_best, isr_worst = int(cycles[0]["isr_best"]), int(cycles[0]["isr_worst"])
    w("**Instructions** are exact: qemu's per-instruction execution log (`-singlestep -d exec,nochain`) "
      "counted from `HapticPipeline::tick`'s entry to its return (`tools/cyclemodel`, `ff-m4trace`). "
      "**Cycles** are a model, not a measurement: each executed instruction costed from the Cortex-M4 "
      "TRM's timing tables, flash wait states behind the code cache, the tick path in RAM (`FF_FASTRUN`), "
      "given as best–worst assumptions (docs/cycle-model.md says which and what the model cannot know). "
      "The interrupt around the tick (exception entry/exit with lazy FP stacking, `pit0_isr`, `micros()`, "
      "the DAC write, the DWT reads) is estimated from its code at %d–%d cycles and added to the "
      "*%% of budget* columns only. Workload: each scene's own stroke (1 s at 600 px/s along its valley "
      "or tunnel, otherwise across the screen), reports every 5 ms, 2,000 ticks; percentiles are over "
      "those ticks; *worst* is the worst tick of the scene including the events below." % (isr_best, isr_worst))
    w("")
    w("| scene | instr mean / p99.9 / worst | cycles mean | cycles p99.9 | cycles worst (event) "
      "| % of 90,000 mean | % p99.9 | % worst | preparation: instr, modelled ms |")
    w("|---|---|---|---|---|---|---|---|---|")
    for c in cycles:
        f = {k: fnum(v) for k, v in c.items()}
        w("| %s | %s / %s / %s | %s–%s | %s–%s | %s–%s (%s) | %s | %s | %s | %s, %.2f–%.2f |" % (
            c["scene"], fmt(f["instructions_mean"]), fmt(f["instructions_p99.9"]), fmt(f["instructions_max"]),
            fmt(f["cycles_best_mean"]), fmt(f["cycles_worst_mean"]),
            fmt(f["cycles_best_p99.9"]), fmt(f["cycles_worst_p99.9"]),
            fmt(f["cycles_best_max"]), fmt(f["cycles_worst_max"]), c["worst_tick_kind"],
            pct_range(f["cycles_best_mean"] + isr_best, f["cycles_worst_mean"] + isr_worst),
            pct_range(f["cycles_best_p99.9"] + isr_best, f["cycles_worst_p99.9"] + isr_worst),
            pct_range(f["cycles_best_max"] + isr_best, f["cycles_worst_max"] + isr_worst),
            fmt(f["prepare_instructions"]), f["prepare_ms_best"], f["prepare_ms_worst"]))
    w("")
    w("Events, worst instructions / worst-case cycles of the tick (without the interrupt):")
    w("")
    events = ("swap", "mailbox-full", "mailbox-drain", "lift-off", "no-finger", "touch-down")
    w("| scene | " + " | ".join(events) + " |")
    w("|---|" + "---|" * len(events))
    for c in cycles:
        w("| %s | %s |" % (c["scene"], " | ".join(
            "%s / %s" % (fmt(fnum(c.get(e + "_instructions"))), fmt(fnum(c.get(e + "_cycles_worst"))))
            for e in events)))
    w("")
    w("*swap*: the first tick after `set_condition` switched scenes (finger down); *mailbox-full*: eight "
      "reports waiting at one tick (the main loop stalled), each with its own stamp, all accepted; the tick "
      "takes one report at most, so the burst is taken in order by that tick and the seven *mailbox-drain* "
      "ticks after it; *lift-off*: the tick that takes the lift "
      "report; *no-finger*: the four ticks after it; *touch-down*: the tick that takes the first report. "
      "A tick during preparation runs the same code as any other; what preparation changes is the "
      "cache, which the worst case already assumes cold.")
    w("")
    if accuracy:
        w("## Accuracy on the target (M4 build under qemu)")
        w("")
        w("`ff-m4trace accuracy` prints the M4 build's raw amplitude, the amplitude after strength 0.8 and "
          "the DAC code after a three-point decreasing calibration (4000 at 0, 2500 at 0.4, 300 at 1) at 256 "
          "points per built-in scene; `ff-m4accuracy` recomputes each in double with the independent "
          "reference (`test/support/reference/`, max|G| by a dense scan) and the exact calibration. "
          "LSB = 1/4095 of the amplitude range; the code column includes the DAC's rounding (0.5 alone).")
        w("")
        w("| scene | points | raw amplitude max (LSB) | after strength max / RMS (LSB) | DAC code vs exact, max | codes ≠ round(exact) |")
        w("|---|---|---|---|---|---|")
        for a in accuracy:
            w("| %s | %s | %s | %s / %s | %s | %s |" % (
                a["scene"], a["points"], fmt(fnum(a["raw_max_lsb"])), fmt(fnum(a["scaled_max_lsb"])),
                fmt(fnum(a["scaled_rms_lsb"])), fmt(fnum(a["code_max_lsb"])), a["codes_off"]))
        w("")
    return out


def cycle_goal_rows(cycles):
    isr_worst = int(cycles[0]["isr_worst"])
    worst = max(cycles, key=lambda c: fnum(c["cycles_worst_max"]))
    pct = 100 * (fnum(worst["cycles_worst_max"]) + isr_worst) / BUDGET_CYCLES
    over = [c["scene"] for c in cycles
            if 100 * (fnum(c["cycles_worst_max"]) + isr_worst) / BUDGET_CYCLES > CYCLE_GOAL_PERCENT]
    rows = ["| every built-in scene ≤ %g %% of the 90,000-cycle budget at its worst modelled tick "
            "(worst assumptions, interrupt included) | worst: %s, %.2f %% (%s); over: %s | %s |" % (
                CYCLE_GOAL_PERCENT, worst["scene"], pct, worst["worst_tick_kind"],
                ", ".join(over) if over else "none", "yes" if not over else "**no**")]
    prep = [c for c in cycles if c.get("prepare_ms_worst")]
    worst_prep = max(prep, key=lambda c: fnum(c["prepare_ms_worst"]))
    over = [c["scene"] for c in prep if fnum(c["prepare_ms_worst"]) > PREPARE_GOAL_MS]
    rows.append("| every built-in scene prepares in ≤ %g ms of modelled MK66 time (worst assumptions) "
                "| worst: %s, %.2f ms; over: %s | %s |" % (
                    PREPARE_GOAL_MS, worst_prep["scene"], fnum(worst_prep["prepare_ms_worst"]),
                    ", ".join(over) if over else "none", "yes" if not over else "**no**"))
    return rows


def report(rows, m4, host_trackers, args):
    cycles = read_plain_csv(args.cycles, CYCLE_COLUMNS, ("isr_best", "isr_worst"), CYCLE_NUMBERS)
    accuracy = read_plain_csv(args.m4_accuracy, ACCURACY_COLUMNS)
    have_m4 = m4 is not None and bool(m4["cases"])
    by_id = {r["id"]: r for r in rows}
    defaults = [r for r in rows if r["default"] == "1" and r["builtin"] == "1"]
    neutral = by_id.get("neutral/closed-form")
    heightmap = by_id.get("heightmap-top/closed-form")
    out = []
    w = out.append
    w("# Benchmarks: run time against error for every evaluation strategy")
    w("")
    w("Generated by `scripts/run-benchmarks` (%s) with `ff-bench` (host) and `ff-m4bench` "
      "(Cortex-M4F under qemu); do not edit by hand. The per-strategy figures (*Built-in scenes at their default*, "
      "*Scene preparation*, *Every strategy*) are in `docs/benchmarks.csv` too, one row per scene and strategy; "
      "the cycle model's, the trackers', *Where the time goes* and the accuracy on the target are only here." % datetime.date.today().isoformat())
    w("")
    w("- **Error**: amplitude of the float core against an independent double-precision implementation "
      "written from the [spec](spec.md#scenes) (`test/support/reference/`), on %s, between pixel centres so "
      "never on a table node) and 16 directions of motion; max|G| of the reference by a scan of every pixel plus a compass search to 1e-9 px. "
      "In DAC LSB = 1/4095 of the amplitude range (strength 1). *max*: the worst sample; *p99*: 99 %% of "
      "samples are at most this; *interior max*: the worst at least 16 px inside the screen." %
      error_grid_text(args.host))
    w("- **M4 instructions** (SysTick stopwatch, the *instr* columns outside the cycles section): the core "
      "cross-compiled with arm-none-eabi-gcc as the firmware is (`-O2`, `-fsingle-precision-constant`, "
      "Cortex-M4F hard float, the Teensyduino defines; `cmake/arm-none-eabi.cmake`) "
      "and run under `qemu-system-arm -M mps2-an386 -icount shift=0`: one guest instruction = 1 ns of virtual "
      "time; SysTick runs from the 25 MHz AN386 system clock, so one SysTick count = 40 instructions "
      "(measured at start-up against a loop of known length: %s). Repeated operations are timed as a block "
      "(evaluation: 2,048 calls), so the 40-instruction step averages out; single ticks (the *max* columns) "
      "are ±40. Two runs give identical numbers (checked by `scripts/m4-smoke`)." %
      (("%d instructions per count" % m4["calibration"]) if have_m4 else "not run"))
    w("- **Instructions are not cycles.** qemu counts instructions, not the M4's cycles. Modelled MK66 cycles "
      "and the % of the 90,000-cycle budget (one 500 µs tick at 180 MHz) are in *Cycles on the MK66* "
      "(from exact per-call instruction traces); where a % appears next to instructions elsewhere it is "
      "instructions / 90,000, a lower bound, to be confirmed with the DWT cycle counter on the Teensy.")
    w("- **Whole tick**: `HapticPipeline::tick()` (static pipeline, two 96 KiB table slots, `recommended()` "
      "tracker) while a finger strokes along heightmap-top's path at 600 px/s with a ±30 px wave, reports "
      "every 5 ms: mean over 2,000 ticks (`≈`: the Teensy refuses the table, too large for the slot or too "
      "costly to prepare, so the tick is estimated as "
      "the closed-form tick minus its evaluation plus this strategy's evaluation).")
    w("- **Host**: Google Benchmark, ns per call on %s, a machine shared with other jobs: "
      "compare host numbers with each other only roughly." % host_cpu())
    if args.environment:
        w("- **Run**: " + args.environment)
    w("")

    # ---------------------------------------------------------------- goals
    w("## Goals")
    w("")
    w("| goal | measured | met |")
    w("|---|---|---|")
    if cycles:
        out.extend(cycle_goal_rows(cycles))
    if defaults:
        worst_err = max(defaults, key=lambda r: fnum(r["max_lsb"]) or 0)
        w("| every built-in scene's default ≤ %g LSB max error | worst: %s, %s LSB | %s |" % (
            ERROR_GOAL_LSB, worst_err["scene"], fmt(fnum(worst_err["max_lsb"])),
            "yes" if all((fnum(r["max_lsb"]) or 0) <= ERROR_GOAL_LSB for r in defaults) else "**no**"))
        if have_m4:
            ticked = [r for r in defaults if r["m4_tick"] is not None]
            worst_tick = max(ticked, key=lambda r: r["m4_tick"])
            w("| every built-in scene's default ≤ %s M4 instructions per whole tick (mean) | worst: %s, %s "
              "(%.2f %% of 90,000); worst single tick %s | %s |" % (
                  "{:,}".format(TICK_GOAL_INSTR), worst_tick["scene"], fmt(worst_tick["m4_tick"]),
                  100 * worst_tick["m4_tick"] / BUDGET_CYCLES, fmt(max(r["m4_tick_max"] or 0 for r in ticked)),
                  "yes" if all(r["m4_tick"] <= TICK_GOAL_INSTR for r in ticked) else "**no**"))
            closed = [r for r in rows if r["strategy"] == "closed-form" and r["builtin"] == "1" and r["m4_prepare"]]
            worst_prep = max(closed, key=lambda r: r["m4_prepare"])
            over = [r["scene"] for r in closed if r["m4_prepare"] > PREPARE_GOAL_INSTR]
            w("| closed-form preparation ≤ 2 ms of M4 time = 360,000 instructions at 180 MHz "
              "(1 instruction counted as 1 cycle) | worst: %s, %s instructions = %.2f ms; over: %s | %s |" % (
                  worst_prep["scene"], fmt(worst_prep["m4_prepare"]), ms_at_180(worst_prep["m4_prepare"]),
                  ", ".join(over) if over else "none", "yes" if not over else "**no**"))
            if neutral and heightmap and neutral["m4_tick"] and heightmap["m4_tick"]:
                ratio = neutral["m4_tick"] / heightmap["m4_tick"]
                w("| neutral costs a small fraction of heightmap (whole tick) | %s / %s instructions = %.0f %%; "
                  "scene evaluation alone %s / %s = %.0f %% | %s |" % (
                      fmt(neutral["m4_tick"]), fmt(heightmap["m4_tick"]), 100 * ratio,
                      fmt(neutral["m4_eval"]), fmt(heightmap["m4_eval"]),
                      100 * neutral["m4_eval"] / heightmap["m4_eval"],
                      "yes" if ratio <= 0.25 else "**no** (see *Where the time goes*)"))
    w("")

    if cycles:
        out.extend(cycles_section(cycles, accuracy))

    # ------------------------------------------------------ built-in defaults
    w("## Built-in scenes at their default")
    w("")
    w(default_choice_text(rows, have_m4))
    w("")
    w("| scene | max error (LSB) | RMS (LSB) | M4 instr / evaluation | M4 instr / whole tick (mean, max) "
      "| % of 90,000 | M4 preparation (instr, ms at 180 MHz if 1 instruction = 1 cycle) | host ns / evaluation | host ns / tick |")
    w("|---|---|---|---|---|---|---|---|---|")
    for r in defaults:
        pct = 100 * r["m4_tick"] / BUDGET_CYCLES if r["m4_tick"] else None
        w("| %s | %s | %s | %s | %s, %s | %s | %s, %s | %s | %s |" % (
            r["scene"], fmt(fnum(r["max_lsb"])), fmt(fnum(r["rms_lsb"])), fmt(r["m4_eval"]), tick_text(r),
            fmt(r["m4_tick_max"]), ("%.2f %%" % pct) if pct else "–", fmt(r["m4_prepare"]),
            fmt(ms_at_180(r["m4_prepare"])), fmt(fnum(r["host_eval_ns"])), fmt(fnum(r["host_tick_ns"]))))
    w("")

    # ----------------------------------------------------------------- plot
    png_link = args.png_link or os.path.relpath(args.png, os.path.dirname(args.md) or ".")
    w("## Cost against error")
    w("")
    w("![M4 instructions per tick against max error, one point per strategy](%s)" % png_link)
    w("")
    w("One point per strategy; marker area grows with table + plan bytes; hollow markers do not fit the "
      "Teensy's 96 KiB table slot (1 and 2 px tables, float 4 px gradients), measured anyway because the "
      "AN386 has 4 MiB SRAM + 16 MiB PSRAM. The dashed line is the Pareto front (nothing cheaper is more "
      "accurate).")
    w("")
    w(table_saving_text(rows, have_m4))
    w("")
    w("## Where the error goes")
    w("")
    for line in error_analysis(rows):
        w("- " + line)
    w("")
    # -------------------------------------------------------- where the time goes
    missing = [cid for cid, r in (("neutral/closed-form", neutral), ("heightmap-top/closed-form", heightmap))
               if not r or r["m4_tick"] is None]
    if have_m4 and missing:
        w("## Where the time goes (M4 instructions per tick)")
        w("")
        w("No %s row in this run (a filtered run?): the tick's pieces, set against neutral's, are left out." %
          " or ".join(missing))
        w("")
    elif have_m4:
        w("## Where the time goes (M4 instructions per tick)")
        w("")
        comp = m4["components"]
        every = 10  # a report every 10th tick
        on_sample = comp.get("Tracker::on_sample (recommended(); per report)", 0) / every
        tick_nofilter = comp.get("Tracker::on_tick need_filter=false (finger present)", 0)
        tick_filter = comp.get("Tracker::on_tick need_filter=true (recommended())", 0)
        scale = comp.get("AmplitudeMap::scale (strength 1)", 0)
        code = comp.get("AmplitudeMap::dac_code (linear calibration)", 0)
        take = comp.get("SampleMailbox::take", 0)
        w("Each piece timed alone on the same stroke (call by call, the stopwatch's own %s instructions "
          "subtracted); the rest is the difference to the measured whole tick." % fmt(m4.get("stopwatch", 0)))
        w("")
        w("| piece | neutral | heightmap-top |")
        w("|---|---|---|")
        # ff-m4bench times on_sample with filtering on; neutral (need_filter = false) never filters, so that
        # cost is not neutral's: its own on_sample stays in its rest.
        w("| `Tracker::on_sample` (%s per report with filtering, one report every %d ticks) "
          "| — (not timed without filtering) | %s |" % (fmt(on_sample * every), every, fmt(on_sample)))
        w("| `Tracker::on_tick` (neutral: `need_filter = false`; heightmap: filtering, `recommended()`) | %s | %s |" % (
            fmt(tick_nofilter), fmt(tick_filter)))
        # A constant scene's amplitude and code are computed once, at preparation.
        w("| `ScenePlan::amplitude` | — (at preparation) | %s |" % fmt(heightmap["m4_eval"]))
        w("| `AmplitudeMap::scale` | — (at preparation) | %s |" % fmt(scale))
        w("| `AmplitudeMap::dac_code` | — (at preparation) | %s |" % fmt(code))
        w("| `SampleMailbox::take` (about one per tick) | %s | %s |" % (fmt(take), fmt(take)))
        parts_n = tick_nofilter + take
        parts_h = on_sample + tick_filter + heightmap["m4_eval"] + scale + code + take
        w("| rest: `HapticPipeline::tick` itself (slot selection, `TickOutput`, calls; neutral: and its "
          "`on_sample`) | %s | %s |" % (
            fmt(neutral["m4_tick"] - parts_n), fmt(heightmap["m4_tick"] - parts_h)))
        w("| **whole tick (measured)** | **%s** | **%s** |" % (fmt(neutral["m4_tick"]), fmt(heightmap["m4_tick"])))
        w("")
        w("A tick with no finger on the glass: %s instructions (`Tracker::on_tick` without a finger alone: %s). "
          "Field elements, one `element_gradient` call each: %s." % (
              fmt(comp.get("HapticPipeline::tick without a finger")), fmt(comp.get("Tracker::on_tick without a finger")),
              ", ".join("%s %s" % (k.replace("element_gradient ", ""), fmt(v)) for k, v in comp.items()
                        if k.startswith("element_gradient"))))
        w("")
    # ---------------------------------------------------------- trackers
    w("## Tracker update cost")
    w("")
    w("`Tracker::on_sample` (every 10th tick, 200 Hz) + `on_tick(now, need_filter = true)` on the stroke, per tick.")
    w("")
    w("A new sensor profile: the main loop derives the fade's noise (`fade_noise`), the tick then configures the "
      "tracker with it (`configure`), once.")
    w("")
    w("| configuration | M4 instr / tick (mean) | M4 max single tick | M4 `configure` (tick) | M4 `fade_noise` (loop) "
      "| host ns / tick |")
    w("|---|---|---|---|---|---|")
    names = list(m4["trackers"].keys()) if have_m4 else list(host_trackers.keys())
    for name in names:
        t = m4["trackers"].get(name, {}) if have_m4 else {}
        w("| `%s` | %s | %s | %s | %s | %s |" % (name, fmt(t.get("mean")), fmt(t.get("max")), fmt(t.get("configure")),
                                               fmt(t.get("fade_noise")), fmt(host_trackers.get(name))))
    w("")

    # ---------------------------------------------------------- preparation
    w("## Scene preparation")
    w("")
    w("`ScenePlan::prepare` (max|G| search: a 32 px scan of the screen — an eighth of the shortest texture "
      "wavelength where there is one, a closed form for a lone texture — plus a compass search from the best "
      "node of each of the 6 highest hills; tables: every node, twice for int16 because the scale needs the range first, then the max|G| "
      "scan on the table). heightmap-top, M4 instructions (ms at 180 MHz, 1 instruction = 1 cycle):")
    w("")
    w("| spacing | float gradient | int16 gradient | float height | int16 height | table bytes (int16 gradient) |")
    w("|---|---|---|---|---|---|")
    cf = by_id.get("heightmap-top/closed-form")
    if cf:
        w("| closed form | %s (%s ms) | | | | 0 |" % (fmt(cf["m4_prepare"]), fmt(ms_at_180(cf["m4_prepare"]))))
    for sp in (1, 2, 4, 8, 16):
        cells = []
        for suffix in ("float-gradient", "int16-gradient", "float-height-cd", "int16-height-cd"):
            r = by_id.get("heightmap-top/table-%dpx-%s" % (sp, suffix))
            cells.append("%s (%s ms)" % (fmt(r["m4_prepare"]), fmt(ms_at_180(r["m4_prepare"]))) if r else "–")
        tb = by_id.get("heightmap-top/table-%dpx-int16-gradient" % sp)
        w("| %d px | %s | %s |" % (sp, " | ".join(cells), kib(tb["table_bytes"]) if tb else "–"))
    w("")
    closed = [r for r in rows if r["strategy"] == "closed-form" and r["m4_prepare"]]
    if closed:
        w("Closed forms: preparation is the max|G| scan alone (position-only and constant scenes need none). "
          "Its cost is the number of field evaluations times the cost of one (the field's elements, see "
          "*Where the time goes*, plus |G|^2: a multiply-add; one square root at the end):")
        w("")
        w("| scene | M4 instructions | ms at 180 MHz if 1 instruction = 1 cycle | field evaluations | instructions per evaluation "
          "| max\|G\| relative error | host µs |")
        w("|---|---|---|---|---|---|---|")
        for r in closed:
            evals = int(r["gradient_evaluations"] or 0)
            w("| %s | %s | %s | %s | %s | %s | %s |" % (
                r["scene"], fmt(r["m4_prepare"]), fmt(ms_at_180(r["m4_prepare"])), evals or "–",
                fmt(r["m4_prepare"] / evals) if evals else "–",
                ("%.1e" % r["max_g_rel_error"]) if r["max_g_rel_error"] is not None else "–",
                fmt(fnum(r["host_prepare_us"]))))
        w("")

    # ------------------------------------------------------------ full table
    w("## Every strategy")
    w("")
    w("`fits`: the Teensy accepts it: the table fits one 96 KiB slot (else `TableTooLarge`) and its preparation "
      "is priced within the watchdog's budget (else `TooCostlyToPrepare`). "
      "`where`: the worst sample's place for errors ≥ 1 LSB. `M4 = host`: the M4 and the host give the "
      "same DAC codes on the 256 cost points (a difference means libm or rounding differences between "
      "newlib and glibc).")
    w("")
    w("| id | memory | fits | max | p99 | RMS | interior max | where | M4 instr / eval | M4 instr / tick "
      "| M4 prepare | host ns / eval | host µs / prepare | M4 = host |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        w("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["id"] + (" **(default)**" if r["default"] == "1" else ""), kib(r["memory_bytes"]),
            "yes" if r["fits_teensy"] else "no", fmt(fnum(r["max_lsb"])), p99_text(fnum(r["p99_lsb"])),
            fmt(fnum(r["rms_lsb"])), fmt(fnum(r["max_interior_lsb"])), r["where"], fmt(r["m4_eval"]),
            tick_text(r), fmt(r["m4_prepare"]), fmt(fnum(r["host_eval_ns"])), fmt(fnum(r["host_prepare_us"])),
            "–" if r["checksum_match"] is None else ("yes" if r["checksum_match"] else "no")))
    w("")
    return "\n".join(out) + "\n"


def main():
    args = parse_args()
    try:
        write_report(args)
    except (OSError, ff_files.OutputIsInput, BadInput) as e:
        # an input that cannot be read or is malformed, an output that cannot be written: docs/tools.md, exit 2
        print("make_report: %s" % ff_files.error_text(e), file=sys.stderr)
        sys.exit(2)


def write_report(args):
    ff_files.refuse_overwriting_inputs(
        [args.md, args.csv, args.png],
        [os.path.join(args.host, "host_cases.csv"), os.path.join(args.host, "host_trackers.csv"), args.m4,
         args.cycles, args.m4_accuracy])
    host_cases, host_trackers = read_host(args.host)
    m4 = read_m4(args.m4)
    if m4 is not None:
        check_m4_complete(m4, args.m4)
        if m4["errors"]:  # whole, but a case failed on the M4: a check that failed, exit 1
            sys.exit("make_report: the harness reported errors: " + "; ".join(m4["errors"]))
        if m4["done"] > 0:  # its own checks on the outputs (tools/m4bench/main.cpp g_failures)
            sys.exit("make_report: the harness counted %d failed checks (its done line)" % m4["done"])
        check_m4_measured_every_closed_form(m4, args.m4, host_cases, os.path.join(args.host, "host_cases.csv"))
    rows = merge(host_cases, m4)
    text = report(rows, m4, host_trackers, args)  # before any file is written: the three stay consistent
    inputs = ", ".join("%s %s" % (flag, value) for flag, value in
                       (("--host", args.host), ("--m4", args.m4), ("--cycles", args.cycles),
                        ("--m4-accuracy", args.m4_accuracy)) if value)
    metadata = [("tool", "tools/bench/make_report.py"),
                ("date", datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")),
                ("input", inputs),
                ("environment", args.environment or "not given"),  # the commit, compilers, ff-bench's options
                ("what", "every figure of %s, one row per scene and evaluation strategy" % args.md)]
    write_csv(rows, args.csv, metadata)
    plot(rows, args.png, m4 is not None and bool(m4["cases"]), metadata)

    ff_files.write_whole(args.md, lambda f: f.write(text))
    print("make_report: wrote %s, %s, %s (%d strategies)" % (args.md, args.csv, args.png, len(rows)))


if __name__ == "__main__":
    main()
