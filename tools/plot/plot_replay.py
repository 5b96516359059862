#!/usr/bin/env python3
"""Plot a replay: the finger's path over the scene, coloured by the rendered
amplitude, and the amplitude against time.

Inputs are the sensor trace given to ff-replay (t_us,x,y,touch) and its
output (t_us,x,y,vx,vy,amplitude,dac,present with '#' metadata lines). The
scene is the one the replay's metadata names, drawn by ff-scene-render (any
scene, including --scene-file ones): the amplitude map for position-only
scenes, |G_norm| with downhill arrows for directional ones. Scene words
given on the command line must select the same condition (the scene hash in
the metadata), and the trace must be the replay's input (name and size):
otherwise the plot is refused. So is a replay without ff-replay's final
'# summary' line: killed midway or cut short, it is not the whole run.

Long replays stream through numpy: the amplitude is drawn as its minimum and
maximum per pixel column, the path from at most --max-segments segments, so
a 1 M-tick replay plots in seconds and well under 1 GB.

Example:
  ff-replay --scene heightmap --target top --strength 0.66 trace.csv -o out.csv
  plot_replay.py trace.csv out.csv -o replay.png
  plot_replay.py trace.csv out.csv -o part.png --from 2 --to 4
Exit codes: 0 ok, 2 bad usage or input (one line on stderr, never a traceback).
"""
import argparse
import csv
import os
import re
import shlex
import sys
import warnings

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

TOOLS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path[:0] = [os.path.join(TOOLS, "scene_render"), os.path.join(TOOLS, "common")]
import ff_files  # noqa: E402
from scene_sampler import ToolError, describe, find_binary, grid, parse_metadata, sample  # noqa: E402

WIDTH, HEIGHT = 800, 480
REPLAY_COLUMNS = ("t_us", "x", "y", "amplitude", "present")
COLUMNS_DRAWN = 1000  # pixel columns of the amplitude plot


# ---- files ------------------------------------------------------------------

def read_header(path):
    """Metadata, the line each metadata key is on, column names and the number
    of lines before the first row."""
    lines, meta, meta_lines = 0, {}, {}
    with open(path, encoding="utf-8-sig") as f:
        for line in f:
            lines += 1
            if line.startswith("#") or not line.strip():
                found = parse_metadata([line.rstrip("\n")])
                meta.update(found)
                meta_lines.update(dict.fromkeys(found, lines))
                continue
            return meta, meta_lines, [c.strip() for c in line.split(",")], lines
    raise ToolError(f"{path}: no header row")


def check_complete(path):
    """ff-replay writes '# summary:' after its last row: a replay killed midway
    (ff-replay leaves X.partial) or a capture of its output cut short, even at
    a row's end, has no such last line."""
    with open(path, "rb") as f:
        f.seek(0, os.SEEK_END)
        f.seek(max(0, f.tell() - 4096))
        tail = [line.strip() for line in f.read().splitlines() if line.strip()]
    if not tail or not tail[-1].startswith(b"# summary:"):
        raise ToolError(f"{path}: the replay is incomplete: no summary line (ff-replay writes it last)")


def read_replay(path):
    """Metadata, the replay's columns and the line of each metadata key; a row
    out of spec (docs/spec.md#replay-output) is refused with its line."""
    try:
        meta, meta_lines, names, skip = read_header(path)
        duplicated = sorted({c for c in names if names.count(c) > 1})
        if duplicated:
            raise ToolError(f"{path}:{skip}: column {', '.join(duplicated)} is named twice")
        missing = [c for c in REPLAY_COLUMNS if c not in names]
        if missing:
            raise ToolError(f"{path}: not an ff-replay output (no column {', '.join(missing)})")
        check_complete(path)
        with open(path, encoding="utf-8-sig") as f, warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # "input contained no data": said below, in one line
            try:
                # every column, so that a row wider than the header is seen
                data = np.loadtxt(f, delimiter=",", comments="#", skiprows=skip, ndmin=2)
            except ValueError:
                raise ToolError(first_bad_row(path, names, skip)) from None
    except UnicodeDecodeError as e:
        raise ToolError(f"{path}: not UTF-8 text ({e})") from None
    if len(data) == 0:
        raise ToolError(f"{path}: no ticks")
    if data.shape[1] != len(names):  # every row as wide, and wider than the header
        raise ToolError(f"{path}:{line_of_row(path, skip, 0)}: {data.shape[1]} fields, the header names {len(names)}")
    columns = {c: data[:, names.index(c)] for c in REPLAY_COLUMNS}
    check_rows(path, skip, columns)
    return meta, columns, meta_lines


def check_rows(path, skip, columns):
    """Ranges of docs/spec.md#replay-output: ticks one after another, a finite
    position, amplitude in [0, 1], present 0 or 1; the first row out of them is named."""
    t, amplitude, present = columns["t_us"], columns["amplitude"], columns["present"]
    later = np.ones(len(t), dtype=bool)
    later[1:] = t[1:] > t[:-1]
    checks = [(~np.isfinite(t), lambda i: f"t_us {t[i]:.0f} is not a finite time"),
              (~later, lambda i: f"t_us {t[i]:.0f} is not after the previous tick's {t[i - 1]:.0f}")]
    checks += [(~np.isfinite(columns[c]), lambda i, c=c: f"{c} {columns[c][i]:g} is not a finite position")
               for c in ("x", "y")]
    checks += [(~((amplitude >= 0) & (amplitude <= 1)), lambda i: f"amplitude {amplitude[i]:g} is outside [0, 1]"),
               (~((present == 0) | (present == 1)), lambda i: f"present {present[i]:g} is not 0 or 1")]
    firsts = [(int(np.argmax(bad)), n) for n, (bad, _) in enumerate(checks) if bad.any()]
    if firsts:
        row, n = min(firsts)
        raise ToolError(f"{path}:{line_of_row(path, skip, row)}: {checks[n][1](row)}")


def data_rows(path, skip):
    """(line number, fields) of each row after the header, as np.loadtxt reads
    them: '#' starts a comment, blank lines are skipped. Only to name a bad row."""
    with open(path, encoding="utf-8-sig") as f:
        for number, line in enumerate(f, start=1):
            text = line.split("#", 1)[0].strip()
            if number > skip and text:
                yield number, text.split(",")


def line_of_row(path, skip, row):
    return next(number for n, (number, _) in enumerate(data_rows(path, skip)) if n == row)


def first_bad_row(path, names, skip):
    """The first row np.loadtxt could not read, as file:line: why."""
    for number, fields in data_rows(path, skip):
        if len(fields) != len(names):
            return f"{path}:{number}: {len(fields)} fields, the header names {len(names)}"
        for name, field in zip(names, fields):
            try:
                float(field)
            except ValueError:
                return f"{path}:{number}: {name} '{field.strip()}' is not a number"
    return f"{path}: not a replay np.loadtxt can read"  # not reached: loadtxt and float() agree


def read_trace(path):
    """t_us, x, y, touch of every report (csv: rows may have empty x, y)."""
    try:
        return _read_trace(path)
    except UnicodeDecodeError as e:
        raise ToolError(f"{path}: not UTF-8 text ({e})") from None


def _read_trace(path):
    t, x, y, touch = [], [], [], []
    with open(path, newline="", encoding="utf-8-sig") as f:
        rows = csv.reader(line for line in f if not line.startswith("#"))
        header = [c.strip() for c in next(rows, [])]
        if not all(c in header for c in ("t_us", "x", "y", "touch")):
            raise ToolError(f"{path}: header must name t_us, x, y and touch")
        it, ix, iy, ic = (header.index(c) for c in ("t_us", "x", "y", "touch"))
        for n, r in enumerate(rows, start=2):
            if not r:
                continue
            try:
                t.append(float(r[it]))
                touch.append(int(r[ic]))
                x.append(float(r[ix]) if r[ix].strip() else np.nan)
                y.append(float(r[iy]) if r[iy].strip() else np.nan)
            except (ValueError, IndexError):
                raise ToolError(f"{path}: row {n} is not t_us,x,y,touch") from None
    return {"t_us": np.array(t), "x": np.array(x), "y": np.array(y), "touch": np.array(touch)}


# ---- checks -----------------------------------------------------------------

def screen_scale(meta, meta_lines, replay_path):
    """x and y factors from the trace's units to screen pixels: ff-replay --screen WxH
    scales the trace's reports by 800/W and 480/H before the tracker sees them, and
    says so in its '# screen: WxH scaled to 800x480' line (none in an older replay)."""
    if "screen" not in meta:
        return 1.0, 1.0
    match = re.match(r"(\d+)[xX](\d+)(?: |$)", meta["screen"])
    if not match or int(match[1]) == 0 or int(match[2]) == 0:
        raise ToolError(f"{replay_path}:{meta_lines['screen']}: screen '{meta['screen']}' is not WxH with W, H > 0")
    return WIDTH / int(match[1]), HEIGHT / int(match[2])


def check_trace(meta, trace_path, replay_path):
    """The replay's metadata names its input as 'NAME (N bytes)'."""
    if "input" not in meta:
        print(f"plot_replay: {replay_path} has no metadata (an old ff-replay?): not checked against the trace",
              file=sys.stderr)
        return
    expected = f"{os.path.basename(trace_path)} ({os.path.getsize(trace_path)} bytes)"
    if meta["input"] != expected:
        raise ToolError(f"{replay_path} is the replay of {meta['input']}, not of {expected}")


def scene_for(meta, meta_lines, words, binary, replay_path):
    """The words to draw with: those given (checked against the replay's hash) or the replay's own."""
    if not words:
        if "scene" not in meta:
            return None
        try:
            words = shlex.split(meta["scene"])
        except ValueError as e:  # quoting: "No closing quotation"
            raise ToolError(f"{replay_path}:{meta_lines['scene']}: scene words {meta['scene']}: {e}") from None
    scene_meta, _ = sample(binary, words, 100.0, 0.0)
    if "scene_hash" in meta and scene_meta.get("scene_hash") != meta["scene_hash"]:
        raise ToolError(f"{replay_path} was rendered with '{meta.get('scene')}' (scene hash {meta['scene_hash']}), "
                        f"not with '{scene_meta.get('scene')}' ({scene_meta.get('scene_hash')})")
    return words


def window_of(seconds, t_from, t_to):
    end = float(seconds[-1])
    if t_from is not None and t_from > end:
        raise ToolError(f"--from {t_from:g} s is beyond the end of the replay ({end:.3f} s)")
    if t_to is not None and t_to < 0:
        raise ToolError(f"--to {t_to:g} s is before the start of the replay")
    if t_from is not None and t_to is not None and t_to <= t_from:
        raise ToolError(f"--to {t_to:g} s is not after --from {t_from:g} s")
    lo = np.searchsorted(seconds, t_from, side="left") if t_from is not None else 0
    hi = np.searchsorted(seconds, t_to, side="right") if t_to is not None else len(seconds)
    if hi - lo < 1:
        raise ToolError("no tick between --from and --to")
    return lo, hi


# ---- drawing ----------------------------------------------------------------

def draw_scene(ax, binary, words):
    meta, data = sample(binary, words, 4.0, 0.0)
    xs, ys, amp = grid(data, 4)
    extent = (xs[0], xs[-1], ys[-1], ys[0])
    needs = meta.get("needs")
    if needs == "position":
        ax.imshow(amp, extent=extent, cmap="Greys", vmin=0, vmax=1.6, alpha=0.6, interpolation="bilinear")
        note = "background: amplitude map (dark = slippery)"
    elif needs == "position+direction":
        _, _, gx = grid(data, 2)
        _, _, gy = grid(data, 3)
        ax.imshow(np.hypot(gx, gy), extent=extent, cmap="Greys", vmin=0, vmax=0.6, alpha=0.5,
                  interpolation="bilinear")
        k = 10
        X, Y = np.meshgrid(xs[::k], ys[::k])
        ax.quiver(X, Y, -gx[::k, ::k], -gy[::k, ::k], color="0.35", angles="xy", scale_units="xy",
                  scale=0.5 / 30.0, width=0.002)
        note = "background: |G_norm|, arrows downhill (moving along them renders A > 0.5)"
    else:
        note = "constant scene: the amplitude does not depend on the finger"
    ax.text(6, 14, note, fontsize=8, color="0.15", bbox=dict(facecolor="white", alpha=0.7, lw=0))
    return describe(meta.get("scene", ""))


def min_max_per_column(seconds, values, columns):
    """Per pixel column: its time and the minimum and maximum of the values
    (NaN where no finger), so a long replay keeps its extremes."""
    n = len(values)
    if n <= 2 * columns:
        return seconds, values, values
    edges = np.linspace(0, n, columns + 1).astype(np.int64)
    starts = edges[:-1]
    lo = np.fmin.reduceat(values, starts)  # fmin/fmax skip NaN; all-NaN columns stay NaN
    hi = np.fmax.reduceat(values, starts)
    return seconds[starts], lo, hi


def path_segments(x, y, amplitude, present, max_segments):
    step = max(1, len(x) // max_segments)
    x, y, a, p = x[::step], y[::step], amplitude[::step], present[::step] > 0
    points = np.column_stack([x, y])
    segments = np.stack([points[:-1], points[1:]], axis=1)
    keep = p[:-1] & p[1:] & np.all(np.isfinite(segments), axis=(1, 2))
    return segments[keep], (0.5 * (a[:-1] + a[1:]))[keep]


def plot(args, words):
    ff_files.refuse_overwriting_inputs([args.output], [args.trace, args.replay])
    meta, replay, meta_lines = read_replay(args.replay)
    trace = read_trace(args.trace)
    check_trace(meta, args.trace, args.replay)
    sx, sy = screen_scale(meta, meta_lines, args.replay)
    trace["x"], trace["y"] = trace["x"] * sx, trace["y"] * sy  # where the tracker saw them
    binary = find_binary(args.bin)
    words = scene_for(meta, meta_lines, words, binary, args.replay)

    t0 = replay["t_us"][0]
    seconds = (replay["t_us"] - t0) * 1e-6
    lo, hi = window_of(seconds, args.t_from, args.t_to)
    sec = seconds[lo:hi]
    x, y = replay["x"][lo:hi], replay["y"][lo:hi]
    amplitude, present = replay["amplitude"][lo:hi], replay["present"][lo:hi]

    fig = plt.figure(figsize=(11, 9.2))
    layout = fig.add_gridspec(2, 2, height_ratios=[2.2, 1], width_ratios=[40, 1], hspace=0.28, wspace=0.03)
    ax = fig.add_subplot(layout[0, 0])
    cax = fig.add_subplot(layout[0, 1])
    scene_title = draw_scene(ax, binary, words) if words else "no scene"
    rs = (trace["t_us"] - t0) * 1e-6
    reports = (trace["touch"] == 1) & np.isfinite(trace["x"]) & np.isfinite(trace["y"])
    reports &= (rs >= sec[0]) & (rs <= sec[-1])
    step = max(1, int(np.count_nonzero(reports)) // args.max_segments)
    ax.plot(trace["x"][reports][::step], trace["y"][reports][::step], ".", color="0.25", ms=1.6,
            label="sensor reports")
    segments, colours = path_segments(x, y, amplitude, present, args.max_segments)
    lc = LineCollection(segments, cmap="plasma", norm=plt.Normalize(0.0, 1.0), linewidths=2.2)
    lc.set_array(colours)
    ax.add_collection(lc)
    if present.any():
        first = int(np.argmax(present > 0))
        ax.plot(x[first], y[first], "o", color="tab:green", ms=8, label="start")
    fig.colorbar(lc, cax=cax, label="rendered amplitude A (1 = slippery)")
    ax.set_xlim(0, WIDTH)
    ax.set_ylim(HEIGHT, 0)
    ax.set_aspect("equal")
    ax.set_xlabel("x [px]  (1 px ≈ 0.2 mm)")
    ax.set_ylabel("y [px]")
    ax.legend(loc="lower right", fontsize=8, framealpha=0.85)
    ax.set_title(args.title or f"{os.path.basename(args.trace)}: {scene_title}")

    bx = fig.add_subplot(layout[1, :])
    with_finger = np.where(present > 0, amplitude, np.nan)
    ts, lo_a, hi_a = min_max_per_column(sec, with_finger, COLUMNS_DRAWN)
    bx.fill_between(ts, lo_a, hi_a, color="tab:purple", lw=0.6, step="post", label="rendered (finger down)")
    bx.plot(ts, hi_a, color="tab:purple", lw=0.6, drawstyle="steps-post")
    lifted_ts, _, lifted = min_max_per_column(sec, (present == 0).astype(float), COLUMNS_DRAWN)
    if np.any(lifted > 0):
        bx.fill_between(lifted_ts, 0, 1, where=lifted > 0, color="0.85", step="post", label="no finger (idle)")
    bx.set_ylim(-0.02, 1.02)
    bx.set_xlim(sec[0], sec[-1] if sec[-1] > sec[0] else sec[0] + 1e-3)
    bx.set_xlabel("time since the first report [s]")
    bx.set_ylabel("amplitude A")
    bx.legend(loc="upper right", fontsize=8, ncol=3, framealpha=0.85)
    bx.grid(alpha=0.3)
    ff_files.save_figure(fig, args.output, "plot_replay.py", "; ".join(
        [f"trace: {args.trace}", f"replay: {args.replay}"] + [f"{key}: {value}" for key, value in meta.items()]),
        dpi=90, bbox_inches="tight")
    plt.close(fig)


def at_least_one(text):
    """An argparse type: a whole number from 1 on (--max-segments divides by it)."""
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text} is not a whole number from 1 on")
    return value


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                                 usage="%(prog)s trace replay -o PNG [--from S] [--to S] [scene words...]")
    ap.add_argument("trace", help="sensor trace given to ff-replay (t_us,x,y,touch)")
    ap.add_argument("replay", help="ff-replay output")
    ap.add_argument("-o", "--output", required=True, help="PNG file to write")
    ap.add_argument("--from", dest="t_from", type=float, default=None, help="first second to draw (from the start)")
    ap.add_argument("--to", dest="t_to", type=float, default=None, help="last second to draw")
    ap.add_argument("--title", default=None)
    ap.add_argument("--max-segments", type=at_least_one, default=20000, help="most path segments drawn (longer paths thinned)")
    ap.add_argument("--bin", default=None, help="path to ff-scene-render (default: build/native, or $FF_SCENE_RENDER)")
    args, words = ap.parse_known_args()
    try:
        plot(args, words)
    except ToolError as e:
        print(f"plot_replay: {e}", file=sys.stderr)
        sys.exit(2)
    except (OSError, ValueError, UnicodeDecodeError) as e:
        print(f"plot_replay: {ff_files.error_text(e)}", file=sys.stderr)
        sys.exit(2)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
