#!/usr/bin/env python3
"""Draw a frictionfield scene to a PNG: what a finger feels where, and why.

Directional scenes (heightmap, tunnels, vortex, bumps) get two panels: the
amplitude felt when moving in the chosen direction, and the field as arrows
(arrows point "downhill": moving along them is slippery). Position-only scenes
(frictionmap) get one panel: the amplitude map itself.

Example:
  render_scene.py --scene heightmap --target top --direction 0 -o heightmap_top.png
Any other option is passed to ff-scene-render (see its --help).
"""
import argparse
import io
import os
import subprocess
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_BIN = os.path.join(HERE, "..", "..", "build", "native", "tools", "scene_render", "ff-scene-render")


def sample(binary, args, step, direction):
    cmd = [binary, "--step", str(step), "--direction", str(direction)] + args
    out = subprocess.run(cmd, check=False, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(out.stderr.strip() or f"{binary} failed")
    lines = out.stdout.splitlines()
    meta = dict(kv.split("=", 1) for kv in lines[0].lstrip("# ").split())
    data = np.loadtxt(io.StringIO("\n".join(lines[1:])), delimiter=",", skiprows=1)
    return meta, data


def grid(data, column):
    xs, ys = np.unique(data[:, 0]), np.unique(data[:, 1])
    return xs, ys, data[:, column].reshape(len(ys), len(xs))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", required=True, help="PNG file to write")
    ap.add_argument("--direction", type=float, default=0.0, help="direction of motion in degrees (0 right, 90 down)")
    ap.add_argument("--step", type=float, default=4.0, help="sampling step in px")
    ap.add_argument("--bin", default=DEFAULT_BIN, help="path to ff-scene-render")
    ap.add_argument("--title", default=None)
    args, rest = ap.parse_known_args()

    meta, data = sample(args.bin, rest, args.step, args.direction)
    xs, ys, amp = grid(data, 4)
    directional = meta["needs"] == "position+direction"
    title = args.title or f"{meta['scene']} (target {meta['target']}, strength {float(meta['strength']):.2f})"

    panels = 2 if directional else 1
    fig, axes = plt.subplots(1, panels, figsize=(6.4 * panels, 4.4), squeeze=False)
    ax = axes[0][0]
    im = ax.imshow(amp, extent=(xs[0], xs[-1], ys[-1], ys[0]), vmin=0, vmax=1, cmap="viridis")
    label = f"amplitude moving {args.direction:.0f}°" if directional else "amplitude (position only)"
    ax.set_title(label)
    if directional:
        rad = np.deg2rad(args.direction)
        ax.annotate("", xy=(60 + 40 * np.cos(rad), 40 + 40 * np.sin(rad)), xytext=(60, 40),
                    arrowprops=dict(color="white", width=2, headwidth=8))
    fig.colorbar(im, ax=ax, fraction=0.03, label="A (1 = slippery)")

    if directional:
        _, _, gx = grid(data, 2)
        _, _, gy = grid(data, 3)
        ax = axes[0][1]
        mag = np.hypot(gx, gy)
        im = ax.imshow(mag, extent=(xs[0], xs[-1], ys[-1], ys[0]), vmin=0, vmax=0.5, cmap="magma")
        k = max(1, int(round(32 / args.step)))
        X, Y = np.meshgrid(xs[::k], ys[::k])
        ax.quiver(X, Y, -gx[::k, ::k], -gy[::k, ::k], color="cyan", angles="xy", scale_units="xy",
                  scale=0.5 / (0.9 * 32), width=0.003)
        ax.set_title("|G_norm| and downhill arrows")
        fig.colorbar(im, ax=ax, fraction=0.03, label="|G| / (2 max|G|)")
    for a in axes[0]:
        a.set_xlim(0, 800)
        a.set_ylim(480, 0)
        a.set_aspect("equal")
        a.set_xlabel("x [px]")
        a.set_ylabel("y [px]")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(args.output, dpi=90)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
