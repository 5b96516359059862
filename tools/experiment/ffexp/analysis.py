"""From participant folders to the study's numbers: per-participant cells,
group statistics (RM-ANOVA, post-hoc, Wilcoxon), learning curves."""
import math
import os

import numpy as np

from . import exclusions, logs, metrics, stats

RENDERINGS = logs.RENDERINGS
STRENGTHS = logs.STRENGTHS
MEASURES = ("hit_rate", "movement_time", "direction_changes")


class Participant:
    """One folder, read and measured."""

    def __init__(self, folder):
        self.session = logs.read_session(folder)
        self.number = self.session["participant"]
        self.order = self.session["order"]
        self.excluded = exclusions.read_exclusions(folder)
        all_trials = logs.read_trials(folder)
        if not all_trials:
            raise logs.LogError(os.path.join(folder, "trials.csv"), 0, "no finished trials")
        self.trials = [t for t in all_trials if t["trial"] not in self.excluded]
        self.frames = logs.read_frames(folder)
        for t in self.trials:
            ts, xs, ys = metrics.movement_samples(self.frames, t)
            t["path"] = (ts, xs, ys)
            xf, yf = metrics.filtered_path(ts, xs, ys)
            t["direction_changes"] = metrics.direction_changes_filtered(xf, yf)[0]
            t["angles"] = metrics.angles_of_filtered(xf, yf)

    def correct(self):
        return [t for t in self.trials if t["hit"]]

    def cells(self, measure):
        """{(rendering, strength): value}: hit rate over all trials, the
        others the mean over correct trials."""
        if measure == "hit_rate":
            return metrics.cell_table(self.trials, metrics.hit_rate, RENDERINGS, STRENGTHS)
        def mean_of(ts):
            return float(np.mean([t[measure] for t in ts])) if ts else math.nan
        return metrics.cell_table(self.correct(), mean_of, RENDERINGS, STRENGTHS)

    def rendering_series(self, rendering, key):
        ordered = sorted((t for t in self.trials if t["rendering"] == rendering), key=lambda t: t["trial"])
        return np.array([t[key] for t in ordered], float)


def cell_array(participants, measure):
    """n x 2 renderings x 3 strengths."""
    return np.array([[[p.cells(measure)[(r, s)] for s in STRENGTHS] for r in RENDERINGS]
                     for p in participants], float)


def group_statistics(participants):
    """Everything the summary and the figures print, as plain dicts."""
    out = {"n": len(participants), "anova": {}, "posthoc": {}, "wilcoxon": {}, "notes": []}
    orders = [p.order for p in participants]
    for measure in MEASURES:
        y = cell_array(participants, measure)
        complete = np.all(np.isfinite(y), axis=(1, 2))
        if np.sum(~complete):
            out["notes"].append(f"{measure}: {int(np.sum(~complete))} participant(s) with an empty cell left out of the ANOVA")
        yc = y[complete]
        groups = [o for o, c in zip(orders, complete) if c]
        if len(yc) >= 2:
            use_groups = groups if len(set(groups)) == 2 and len(yc) > 2 else None
            out["anova"][measure] = stats.rm_anova(yc, use_groups, names=("rendering", "strength"))
            strength_means = {s: yc[:, :, k].mean(axis=1) for k, s in enumerate(STRENGTHS)}
            out["posthoc"][measure] = stats.bonferroni_pairwise(strength_means)
        out["wilcoxon"][measure] = {s: stats.wilcoxon_paired(y[:, 0, k], y[:, 1, k]) for k, s in enumerate(STRENGTHS)}
    if len(participants) < 2:
        out["notes"].append("one participant: no group statistics")
    out["blocks"] = {}
    for r in RENDERINGS:
        b = np.array([(metrics.block_hit_rates(p.trials, r) + [math.nan, math.nan])[:2] for p in participants])
        out["blocks"][r] = dict(rates=b, test=stats.wilcoxon_paired(b[:, 0], b[:, 1]))
    out["learning"] = {}
    for r in RENDERINGS:
        curves = [metrics.moving_average(p.rendering_series(r, "movement_time")) for p in participants]
        n = min((len(c) for c in curves), default=0)
        if n >= 4:
            m = np.array([c[:n] for c in curves])
            mean, sd = m.mean(axis=0), stats.sample_sd(m, axis=0)  # sd nan for one participant
            x = np.arange(1, n + 1, dtype=float)
            out["learning"][r] = dict(x=x, mean=mean, sd=sd, fit=metrics.fit_power_law(x, mean))
    return out
