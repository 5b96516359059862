#!/usr/bin/env python3
"""Draw a frictionfield scene to a PNG: what a finger feels where, and why.

Directional scenes (heightmap, tunnels, vortex, bumps) get two panels: the
amplitude felt when moving in one direction, and the field as arrows
(arrows point "downhill": moving along them is slippery). Position-only scenes
(frictionmap) get one panel: the amplitude map itself. Constant scenes say so.

The direction defaults to the one that shows the scene best (the largest
spread of amplitude over the screen: a tunnel is flat moving at 0 degrees,
so it is drawn moving across). Everything is sampled by ff-scene-render,
so any scene it accepts (including --scene-file) can be drawn.

Example:
  render_scene.py --scene heightmap --target top -o heightmap_top.png
  render_scene.py --scene-file my_scene.txt --direction 90 -o my_scene.png
Any other option is passed to ff-scene-render (see its --help).
Exit codes: 0 ok, 2 bad usage or input (one line on stderr).
"""
import argparse
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from scene_sampler import ToolError, describe, find_binary, grid, sample  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import ff_files  # noqa: E402

CANDIDATE_DIRECTIONS = range(0, 360, 45)


def best_direction(binary, words, step):
    """The direction whose amplitude varies most over the screen."""
    spread = {}
    for d in CANDIDATE_DIRECTIONS:
        _, data = sample(binary, words, max(step, 16.0), d)
        spread[d] = float(np.std(data[:, 4]))
    return max(spread, key=lambda d: (spread[d], -d))


def scene_files(words):
    """The files among the words ff-scene-render reads: --scene-file F or --scene-file=F."""
    files = []
    for i, word in enumerate(words):
        if word == "--scene-file" and i + 1 < len(words):
            files.append(words[i + 1])
        elif word.startswith("--scene-file="):
            files.append(word.split("=", 1)[1])
    return files


def render(args, words):
    ff_files.refuse_overwriting_inputs([args.output], scene_files(words))
    binary = find_binary(args.bin)
    direction = args.direction
    meta, _ = sample(binary, words, 100.0, 0.0)  # cheap: the scene's metadata
    directional = meta.get("needs") == "position+direction"
    if direction is None:
        direction = best_direction(binary, words, args.step) if directional else 0.0
    meta, data = sample(binary, words, args.step, direction)
    xs, ys, amp = grid(data, 4)
    title = args.title or describe(meta.get("scene", ""))

    panels = 2 if directional else 1
    fig, axes = plt.subplots(1, panels, figsize=(6.4 * panels, 4.4), squeeze=False)
    ax = axes[0][0]
    im = ax.imshow(amp, extent=(xs[0], xs[-1], ys[-1], ys[0]), vmin=0, vmax=1, cmap="viridis")
    if directional:
        ax.set_title(f"amplitude moving {direction:.0f}°")
        rad = np.deg2rad(direction)
        ax.annotate("", xy=(60 + 40 * np.cos(rad), 40 + 40 * np.sin(rad)), xytext=(60, 40),
                    arrowprops=dict(color="white", width=2, headwidth=8))
    elif meta.get("needs") == "position":
        ax.set_title("amplitude (position only)")
    else:
        ax.set_title(f"constant amplitude {float(np.mean(amp)):.3f}")
    fig.colorbar(im, ax=ax, fraction=0.03, label="A (1 = slippery)")

    if directional:
        _, _, gx = grid(data, 2)
        _, _, gy = grid(data, 3)
        ax = axes[0][1]
        im = ax.imshow(np.hypot(gx, gy), extent=(xs[0], xs[-1], ys[-1], ys[0]), vmin=0, vmax=0.5, cmap="magma")
        k = max(1, int(round(32 / args.step)))
        X, Y = np.meshgrid(xs[::k], ys[::k])
        ax.quiver(X, Y, -gx[::k, ::k], -gy[::k, ::k], color="cyan", angles="xy", scale_units="xy",
                  scale=0.5 / (0.9 * 32), width=0.003)
        ax.set_title("|G_norm| and downhill arrows")
        fig.colorbar(im, ax=ax, fraction=0.03, label="|G| / (2 max|G|)")
    for a in axes[0]:
        a.set_xlim(0, 800)
        a.set_ylim(480, 0)
        a.set_xlabel("x [px]")
        a.set_ylabel("y [px]")
    fig.suptitle(title)
    fig.tight_layout()
    ff_files.save_figure(fig, args.output, "render_scene.py",
                         "; ".join(f"{key}: {value}" for key, value in meta.items()), dpi=90)
    plt.close(fig)
    return direction, title


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", required=True, help="PNG file to write")
    ap.add_argument("--direction", type=float, default=None,
                    help="direction of motion in degrees (0 right, 90 down); default: the one that shows the scene")
    ap.add_argument("--step", type=float, default=4.0, help="sampling step in px")
    ap.add_argument("--bin", default=None, help="path to ff-scene-render (default: build/native, or $FF_SCENE_RENDER)")
    ap.add_argument("--title", default=None)
    args, words = ap.parse_known_args()
    try:
        direction, title = render(args, words)
    except (ToolError, OSError, ValueError) as e:
        print(f"render_scene: {ff_files.error_text(e)}", file=sys.stderr)
        sys.exit(2)
    print(f"wrote {args.output}: {title}, moving {direction:.0f}°")


if __name__ == "__main__":
    main()
