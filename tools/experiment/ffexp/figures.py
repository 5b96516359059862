"""The study's figures (like the paper's 11-15 and appendix L's panels)."""
import math

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
import numpy as np  # noqa: E402

import ff_files  # noqa: E402

from . import VERSION, analysis, geometry, metrics, stats  # noqa: E402

SOFTWARE = "ff-analyse " + VERSION

COLOURS = {"heightmap": "tab:blue", "frictionmap": "tab:red"}
STRENGTH_LABELS = [f"{s:.2f}" for s in analysis.STRENGTHS]


def _strength_axis(ax):
    ax.set_xticks(range(3))
    ax.set_xticklabels(STRENGTH_LABELS)
    ax.set_xlabel("strength")


def hit_rates(ax, participants):
    """Fig. 11: hit rate per strength, one line per rendering (mean, participants as dots)."""
    y = analysis.cell_array(participants, "hit_rate")
    for i, r in enumerate(analysis.RENDERINGS):
        for row in y[:, i, :]:
            ax.plot(range(3), row, ".", color=COLOURS[r], alpha=0.4)
        ax.plot(range(3), np.nanmean(y[:, i, :], axis=0), "-o", color=COLOURS[r], label=r)
    ax.axhline(1 / 3, color="grey", ls=":", lw=1, label="chance")
    ax.set_ylim(0, 1.02)
    ax.set_ylabel("hit rate")
    _strength_axis(ax)
    ax.legend(fontsize=7)


def per_trial_boxes(ax, participants, key, label):
    """Figs. 12/13: one value per correct trial, boxes per strength and rendering."""
    for i, r in enumerate(analysis.RENDERINGS):
        data = [[t[key] for p in participants for t in p.correct()
                 if t["rendering"] == r and math.isclose(t["strength"], s)] or [math.nan]
                for s in analysis.STRENGTHS]
        pos = np.arange(3) + (i - 0.5) * 0.3
        b = ax.boxplot(data, positions=pos, widths=0.25, patch_artist=True, showfliers=False)
        for patch in b["boxes"]:
            patch.set_facecolor(COLOURS[r])
            patch.set_alpha(0.5)
    ax.set_ylabel(label)
    _strength_axis(ax)


def angles(ax, participants):
    """Fig. 14: normalised histogram of the movement angle per rendering."""
    for r in analysis.RENDERINGS:
        a = np.concatenate([t["angles"] for p in participants for t in p.trials if t["rendering"] == r] or [np.array([])])
        edges, h = metrics.angle_histogram(a)
        ax.step(edges[:-1], h, where="post", color=COLOURS[r], label=r)
    # the paths start and end at 0 deg and are steepest (top +, bottom -) mid-way
    ends, up, down = metrics.PATH_ANGLES_DEG
    ax.axvline(ends, color="grey", ls="--", lw=0.8, label="paths' ends, 0°")
    ax.axvline(up, color="grey", ls="--", lw=0.8, label=f"paths' steepest, ±{up:.1f}°")
    ax.axvline(down, color="grey", ls="--", lw=0.8)
    ax.set_xlim(-180, 180)
    ax.set_xlabel("movement angle (deg, 0 = right, + = up)")
    ax.set_ylabel("fraction")
    ax.legend(fontsize=7)


def blocks(ax, participants):
    """Fig. 15 top: hit rate per 45-trial block."""
    for r in analysis.RENDERINGS:
        b = np.array([(metrics.block_hit_rates(p.trials, r) + [math.nan] * 2)[:2] for p in participants])
        # the sample SD over participants: no bar for one participant
        ax.errorbar([1, 2], np.nanmean(b, axis=0), yerr=stats.sample_sd(b, axis=0), color=COLOURS[r], marker="o",
                    label=r, capsize=3)
    ax.set_xticks([1, 2])
    ax.set_xlabel("block of 45 trials")
    ax.set_ylabel("hit rate")
    ax.set_ylim(0, 1.02)


def learning(ax, learning_stats):
    """Fig. 15 bottom: 10-trial moving average of movement time, mean +- sample SD, power-law fit
    (analysis.group_statistics' "learning")."""
    for r, d in learning_stats.items():
        ax.plot(d["x"], d["mean"], color=COLOURS[r], label=r)
        ax.fill_between(d["x"], d["mean"] - d["sd"], d["mean"] + d["sd"], color=COLOURS[r], alpha=0.2)
        a, b, c = d["fit"]
        if np.isfinite(a):
            ax.plot(d["x"], metrics.power_law(d["x"], a, b, c), "--", color=COLOURS[r], lw=1,
                    label=f"{a:.1f} x^-{b:.2f} + {c:.1f}")
    ax.set_xlabel("trial of the rendering (window end - 9)")
    ax.set_ylabel("movement time (s)")
    ax.legend(fontsize=6)


def raw_paths(ax, participant, rendering):
    """Appendix L A/B: every trial's path, green correct, red wrong."""
    for xs, y in geometry.path_polylines():
        ax.plot(xs, y, color="black", lw=0.8)
    mine = [t for t in participant.trials if t["rendering"] == rendering]
    ns = [t["trial"] for t in mine]
    segments = [np.column_stack(t["path"][1:]) for t in mine if len(t["path"][1]) > 1]
    colours = ["green" if t["hit"] else "red" for t in mine if len(t["path"][1]) > 1]
    ax.add_collection(LineCollection(segments, colors=colours, linewidths=0.5, alpha=0.6))
    ax.set_xlim(0, geometry.WIDTH)
    ax.set_ylim(geometry.HEIGHT, 0)
    ax.set_aspect("equal")
    ax.set_title(f"{rendering}: trials {min(ns, default=0)}-{max(ns, default=0)}", fontsize=8)


def participant_page(participant, path):
    """Appendix L: panels A-J for one participant."""
    ps = [participant]
    fig = plt.figure(figsize=(11, 10))
    grid = fig.add_gridspec(4, 3, left=0.07, right=0.98, bottom=0.06, top=0.93, hspace=0.45, wspace=0.3)
    raw_paths(fig.add_subplot(grid[0, 0:2]), participant, "frictionmap")
    ax = fig.add_subplot(grid[0, 2]); raw_paths(ax, participant, "heightmap")
    hit_rates(fig.add_subplot(grid[1, 0]), ps)
    per_trial_boxes(fig.add_subplot(grid[1, 1]), ps, "movement_time", "movement time (s)")
    per_trial_boxes(fig.add_subplot(grid[1, 2]), ps, "direction_changes", "direction changes")
    blocks(fig.add_subplot(grid[2, 0]), ps)
    ax = fig.add_subplot(grid[2, 1])
    for r in analysis.RENDERINGS:
        ax.plot(metrics.moving_average(participant.rendering_series(r, "movement_time")), color=COLOURS[r])
    ax.set_ylabel("MT, moving avg (s)")
    ax = fig.add_subplot(grid[2, 2])
    for r in analysis.RENDERINGS:
        ax.plot(metrics.moving_average(participant.rendering_series(r, "direction_changes")), color=COLOURS[r])
    ax.set_ylabel("direction changes, moving avg")
    ax = fig.add_subplot(grid[3, 0])
    excess = np.array([metrics.path_length_excess(*t["path"]) for t in participant.trials]).reshape(-1, 2)
    ax.scatter(excess[:, 0], excess[:, 1], s=[8 + 20 * t["strength"] for t in participant.trials],
               c=[COLOURS[t["rendering"]] for t in participant.trials], alpha=0.5)
    ax.set_xlabel("extra |dx| (px)"); ax.set_ylabel("total |dy| (px)")
    angles(fig.add_subplot(grid[3, 1:3]), ps)
    fig.suptitle(f"participant {participant.number} (order {participant.order})")
    ff_files.save_figure(fig, path, SOFTWARE, dpi=80)
    plt.close(fig)


def group_figures(participants, group, folder):
    """fig11..fig15 PNGs; returns their file names."""
    import os
    names = []
    specs = [("fig11_hit_rates.png", lambda ax: hit_rates(ax, participants)),
             ("fig12_movement_times.png", lambda ax: per_trial_boxes(ax, participants, "movement_time", "movement time (s)")),
             ("fig13_direction_changes.png", lambda ax: per_trial_boxes(ax, participants, "direction_changes", "direction changes")),
             ("fig14_movement_angles.png", lambda ax: angles(ax, participants))]
    for name, draw in specs:
        fig, ax = plt.subplots(figsize=(5, 3.5))
        draw(ax)
        fig.tight_layout()
        ff_files.save_figure(fig, os.path.join(folder, name), SOFTWARE, dpi=100)
        plt.close(fig)
        names.append(name)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(5, 6))
    blocks(a1, participants)
    learning(a2, group["learning"])
    fig.tight_layout()
    ff_files.save_figure(fig, os.path.join(folder, "fig15_learning.png"), SOFTWARE, dpi=100)
    plt.close(fig)
    names.append("fig15_learning.png")
    return names
