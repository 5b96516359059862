#!/usr/bin/env python3
"""Plot a replay: the finger's path over the scene, coloured by the rendered
amplitude, and the amplitude against time.

Inputs are the files of docs/spec.md#trace-files: the sensor trace given to
ff-replay (t_us,x,y,touch; optional ground truth x_true,y_true) and its output
(t_us,x,y,vx,vy,amplitude,dac). With --scene the scene is drawn behind the path
(heightmap: its height Z with contours, downhill is slippery; frictionmap: the
amplitude map), all three paths are outlined, and when the trace carries ground
truth the amplitude an ideal, noise-free and lag-free renderer would output is
drawn next to the replayed one.

Example:
  ff-replay --scene heightmap --target top --strength 0.66 test/traces/gen_across_high_px.csv -o out.csv
  plot_replay.py test/traces/gen_across_high_px.csv out.csv --scene heightmap --target top \\
      --strength 0.66 -o replay.png
Needs only numpy and matplotlib; the scene is computed from the formulas of docs/spec.md#scenes.
"""
import argparse
import csv
import math
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

WIDTH, HEIGHT = 800, 480
TARGETS = {"top": -200.0, "middle": 0.0, "bottom": 200.0}
TICK_US = 500
LIFT_TIMEOUT_US = 250_000  # a tick this long after the last report draws no finger


# ---- docs/spec.md#paths and #scenes -------------------------------

def path_y(x, rise):
    d = np.clip(np.asarray(x, dtype=float) - 100.0, 0.0, 600.0)
    return -2.0 * rise / 600.0 ** 3 * d ** 3 + 3.0 * rise / 600.0 ** 2 * d ** 2 + 240.0


def path_slope(x, rise):
    x = np.asarray(x, dtype=float)
    d = x - 100.0
    s = -6.0 * rise / 600.0 ** 3 * d ** 2 + 6.0 * rise / 600.0 ** 2 * d
    return np.where((x > 100.0) & (x < 700.0), s, 0.0)


def heightmap_z(x, y, rise, a=0.2):
    u = y - path_y(x, rise)
    return 0.5 * np.abs(np.arctan(a * u) / a - u) + 0.5 * np.hypot(x - 700.0, y - (240.0 + rise))


def heightmap_gradient(x, y, rise, a=0.2):
    u = y - path_y(x, rise)
    d = np.sign(u) * a * a * u * u / (1.0 + a * a * u * u)
    r = np.hypot(x - 700.0, y - (240.0 + rise))
    r = np.where(r > 0, r, 1.0)
    gx = 0.5 * d * -path_slope(x, rise) + 0.5 * (x - 700.0) / r
    gy = 0.5 * d + 0.5 * (y - (240.0 + rise)) / r
    return gx, gy


def max_gradient(rise):
    X, Y = np.meshgrid(np.arange(0, WIDTH, 1.0), np.arange(0, HEIGHT, 1.0))
    gx, gy = heightmap_gradient(X, Y, rise)
    return float(np.max(np.hypot(gx, gy)))


def frictionmap_amplitude(x, y, rise):
    t = np.clip((30.0 - np.abs(y - path_y(x, rise))) / 20.0, 0.0, 1.0)
    return t * t * t * (10.0 + t * (-15.0 + 6.0 * t))


# ---- files ------------------------------------------------------------------

def read_csv(path, required):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit(f"plot_replay: {path}: {e.strerror}")
    if rows and not all(c in rows[0] for c in required):
        sys.exit(f"plot_replay: {path}: expected columns {','.join(required)}")
    cols = {}
    for name in (rows[0].keys() if rows else required):
        if name is None:
            continue
        values = []
        for r in rows:
            v = (r.get(name) or "").strip()
            try:
                values.append(float(v) if v else math.nan)
            except ValueError:
                values.append(math.nan)
        cols[name] = np.array(values)
    return cols


def touching_at(ticks_us, trace):
    """Whether a finger is down at each tick: the newest report at or before it
    says touch = 1 and is not older than the sensor time-out."""
    order = np.argsort(trace["t_us"], kind="stable")
    t = trace["t_us"][order]
    touch = trace["touch"][order]
    idx = np.searchsorted(t, ticks_us, side="right") - 1
    valid = idx >= 0
    idx = np.clip(idx, 0, len(t) - 1)
    return valid & (touch[idx] == 1) & (ticks_us - t[idx] <= LIFT_TIMEOUT_US)


def ideal_amplitude(ticks_us, trace, scene, rise, strength):
    """The ideal renderer: ground truth position and direction at each tick."""
    if "x_true" not in trace or scene not in ("heightmap", "frictionmap"):
        return None
    ok = np.isfinite(trace["x_true"]) & np.isfinite(trace["y_true"]) & (trace["touch"] == 1)
    t, xt, yt = trace["t_us"][ok], trace["x_true"][ok], trace["y_true"][ok]
    if len(t) < 3:
        return None
    t, first = np.unique(t, return_index=True)
    xt, yt = xt[first], yt[first]
    x = np.interp(ticks_us, t, xt)
    y = np.interp(ticks_us, t, yt)
    if scene == "frictionmap":
        a = frictionmap_amplitude(x, y, rise)
    else:
        vx, vy = np.gradient(xt, t), np.gradient(yt, t)
        vx, vy = np.interp(ticks_us, t, vx), np.interp(ticks_us, t, vy)
        speed = np.hypot(vx, vy)
        gx, gy = heightmap_gradient(x, y, rise)
        with np.errstate(invalid="ignore", divide="ignore"):
            a = np.where(speed > 1e-6, 0.5 - (vx * gx + vy * gy) / speed / (2.0 * max_gradient(rise)), 0.5)
    a = 0.5 + strength * (a - 0.5)
    inside = (ticks_us >= t[0]) & (ticks_us <= t[-1])
    return np.where(inside, a, np.nan)


# ---- drawing ----------------------------------------------------------------

def draw_scene(ax, scene, rise):
    X, Y = np.meshgrid(np.arange(0, WIDTH, 2.0), np.arange(0, HEIGHT, 2.0))
    extent = (0, WIDTH, HEIGHT, 0)
    if scene == "heightmap":
        Z = heightmap_z(X, Y, rise)
        ax.imshow(Z, extent=extent, cmap="Greys", alpha=0.55, interpolation="bilinear")
        ax.contour(X, Y, Z, levels=18, colors="0.45", linewidths=0.5, alpha=0.7)
        ax.text(6, 14, "background: height Z (dark = high); moving downhill renders A > 0.5", fontsize=8,
                color="0.15", bbox=dict(facecolor="white", alpha=0.7, lw=0))
    elif scene == "frictionmap":
        ax.text(6, 14, "background: frictionmap (dark = slippery band around the target's path)", fontsize=8,
                color="0.15", bbox=dict(facecolor="white", alpha=0.7, lw=0))
        ax.imshow(frictionmap_amplitude(X, Y, rise), extent=extent, cmap="Greys", vmin=0, vmax=1.6, alpha=0.6,
                  interpolation="bilinear")
    xs = np.linspace(0, WIDTH, 400)
    for name, r in TARGETS.items():
        chosen = scene in ("heightmap", "frictionmap") and r == rise
        ax.plot(xs, path_y(xs, r), "--", color="tab:red" if chosen else "0.6", lw=1.2 if chosen else 0.8)
        ax.plot([700], [240 + r], "o", ms=9, mfc="none", mec="tab:red" if chosen else "0.6", mew=1.5)
    ax.axvspan(0, 100, color="tab:green", alpha=0.06)
    ax.axvspan(700, WIDTH, color="tab:blue", alpha=0.06)


def coloured_path(ax, x, y, amplitude, present, cmap, norm):
    points = np.column_stack([x, y])
    segments = np.stack([points[:-1], points[1:]], axis=1)
    keep = present[:-1] & present[1:] & np.all(np.isfinite(segments), axis=(1, 2))
    lc = LineCollection(segments[keep], cmap=cmap, norm=norm, linewidths=2.2)
    lc.set_array(0.5 * (amplitude[:-1] + amplitude[1:])[keep])
    ax.add_collection(lc)
    return lc


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("trace", help="sensor trace given to ff-replay (t_us,x,y,touch[,x_true,y_true])")
    ap.add_argument("replay", help="ff-replay output (t_us,x,y,vx,vy,amplitude,dac)")
    ap.add_argument("-o", "--output", required=True, help="PNG file to write")
    ap.add_argument("--scene", default="none", choices=["heightmap", "frictionmap", "neutral", "none"],
                    help="scene to draw behind the path (the one replayed)")
    ap.add_argument("--target", default="middle", choices=list(TARGETS), help="the scene's target")
    ap.add_argument("--strength", type=float, default=1.0, help="strength s used in the replay (for the ideal curve)")
    ap.add_argument("--from", dest="t_from", type=float, default=None, help="first second to draw (from the start)")
    ap.add_argument("--to", dest="t_to", type=float, default=None, help="last second to draw")
    ap.add_argument("--title", default=None)
    args = ap.parse_args()

    trace = read_csv(args.trace, ["t_us", "x", "y", "touch"])
    replay = read_csv(args.replay, ["t_us", "x", "y", "vx", "vy", "amplitude", "dac"])
    if len(replay.get("t_us", [])) == 0:
        sys.exit(f"plot_replay: {args.replay}: no ticks")
    rise = TARGETS[args.target]
    t0 = replay["t_us"][0]
    ticks = replay["t_us"]
    seconds = (ticks - t0) * 1e-6
    window = np.ones_like(seconds, dtype=bool)
    if args.t_from is not None:
        window &= seconds >= args.t_from
    if args.t_to is not None:
        window &= seconds <= args.t_to
    present = touching_at(ticks, trace) & window
    amplitude = replay["amplitude"]
    ideal = ideal_amplitude(ticks, trace, args.scene, rise, args.strength)

    fig = plt.figure(figsize=(11, 9.2))
    grid = fig.add_gridspec(2, 2, height_ratios=[2.2, 1], width_ratios=[40, 1], hspace=0.28, wspace=0.03)
    ax = fig.add_subplot(grid[0, 0])
    cax = fig.add_subplot(grid[0, 1])
    draw_scene(ax, args.scene, rise)
    reports = (trace["touch"] == 1) & np.isfinite(trace["x"]) & np.isfinite(trace["y"])
    rs = (trace["t_us"] - t0) * 1e-6
    if args.t_from is not None:
        reports &= rs >= args.t_from
    if args.t_to is not None:
        reports &= rs <= args.t_to
    ax.plot(trace["x"][reports], trace["y"][reports], ".", color="0.25", ms=1.6, label="sensor reports")
    norm = plt.Normalize(0.0, 1.0)
    lc = coloured_path(ax, replay["x"], replay["y"], amplitude, present, "plasma", norm)
    first = np.argmax(present) if present.any() else None
    if first is not None:
        ax.plot(replay["x"][first], replay["y"][first], "o", color="tab:green", ms=8, label="start")
    fig.colorbar(lc, cax=cax, label="rendered amplitude A (1 = slippery)")
    ax.set_xlim(0, WIDTH)
    ax.set_ylim(HEIGHT, 0)
    ax.set_aspect("equal")
    ax.set_xlabel("x [px]  (1 px ≈ 0.2 mm)")
    ax.set_ylabel("y [px]")
    ax.legend(loc="lower right", fontsize=8, framealpha=0.85)
    ax.set_title(args.title or f"{args.trace.split('/')[-1]}: scene {args.scene}"
                 + (f", target {args.target}, strength {args.strength:g}" if args.scene != "none" else ""))

    bx = fig.add_subplot(grid[1, :])
    shown = np.where(window, amplitude, np.nan)
    bx.plot(seconds, shown, color="tab:purple", lw=0.9, label="rendered (replay)")
    if ideal is not None:
        bx.plot(seconds, np.where(window & present, ideal, np.nan), color="tab:green", lw=0.8, alpha=0.8,
                label="ideal: true position and direction")
        err = np.abs(amplitude - ideal)[present & np.isfinite(ideal)]
        if len(err):
            bx.text(0.01, 0.04, f"|rendered - ideal| RMS {np.sqrt(np.mean(err ** 2)):.3f}, p95 {np.percentile(err, 95):.3f}"
                    " (all ticks with a finger)", transform=bx.transAxes, fontsize=8)
    lifted = window & ~touching_at(ticks, trace)
    if lifted.any():
        bx.fill_between(seconds, 0, 1, where=lifted, color="0.85", step="mid", label="no finger")
    bx.set_ylim(-0.02, 1.02)
    bx.set_xlim(seconds[window][0], seconds[window][-1])
    bx.set_xlabel("time since the first report [s]")
    bx.set_ylabel("amplitude A")
    bx.legend(loc="upper right", fontsize=8, ncol=3, framealpha=0.85)
    bx.grid(alpha=0.3)
    fig.savefig(args.output, dpi=90, bbox_inches="tight")
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
