"""Repeated-measures ANOVA (two within factors, optional between factor) with
Greenhouse-Geisser correction, Bonferroni post-hoc tests and Wilcoxon tests.

The ANOVA is the multivariate-contrast formulation: each within effect is a
set of orthonormal contrasts of a subject's cells; its F is the squared mean
contrast over the residual spread (sphericity assumed), and the
Greenhouse-Geisser epsilon comes from the contrasts' residual covariance. A
between-subjects factor (the order of the renderings) enters as an
effect-coded regressor (type III sums of squares, so unequal groups are fine).
Checked against statsmodels' AnovaRM, Box's epsilon formula and one-way ANOVA
in tests/test_stats.py."""
import itertools
import math

import numpy as np
from scipy import stats as sps


def sample_sd(values, axis=None):
    """The SD over participants: the sample standard deviation (n - 1 in the
    denominator) of the finite values, along axis; nan, without a warning,
    where fewer than two values have one (a single participant has no spread)."""
    v = np.asarray(values, float)
    ok = np.isfinite(v)
    n = ok.sum(axis=axis)
    mean = np.where(ok, v, 0.0).sum(axis=axis) / np.maximum(n, 1)
    dev = np.where(ok, v - (mean if axis is None else np.expand_dims(mean, axis)), 0.0)
    var = (dev ** 2).sum(axis=axis) / np.maximum(n - 1, 1)
    sd = np.where(n >= 2, np.sqrt(var), np.nan)
    return float(sd) if axis is None else sd


def _orthonormal_contrasts(k):
    """k x (k-1) matrix with orthonormal columns, each orthogonal to ones."""
    helmert = np.zeros((k, k - 1))
    for j in range(1, k):
        helmert[:j, j - 1] = 1.0
        helmert[j, j - 1] = -j
    return helmert / np.linalg.norm(helmert, axis=0)


def _mean_vector(k):
    return np.full((k, 1), 1.0 / math.sqrt(k))


def _effect_test(z, design, hypothesis):
    """Multivariate-regression test of L beta = 0 for contrast scores z (n x d)
    with sphericity assumed; returns F, df1, df2, p, GG epsilon, GG p, SS, SS error."""
    n, d = z.shape
    xtx_inv = np.linalg.pinv(design.T @ design)
    beta = xtx_inv @ design.T @ z
    resid = z - design @ beta
    l = np.atleast_2d(hypothesis)
    lb = l @ beta
    middle = np.linalg.pinv(l @ xtx_inv @ l.T)
    ss_h = float(np.trace(lb.T @ middle @ lb))
    e = resid.T @ resid
    ss_e = float(np.trace(e))
    q = l.shape[0]
    df_err_subjects = n - np.linalg.matrix_rank(design)
    df1, df2 = q * d, d * df_err_subjects
    f = (ss_h / df1) / (ss_e / df2) if ss_e > 0 else math.inf
    p = float(sps.f.sf(f, df1, df2)) if math.isfinite(f) else 0.0
    eps = float(np.trace(e) ** 2 / (d * np.trace(e @ e))) if d > 1 and ss_e > 0 else 1.0
    p_gg = float(sps.f.sf(f, df1 * eps, df2 * eps)) if math.isfinite(f) else 0.0
    return dict(F=f, df1=df1, df2=df2, p=p, epsilon=eps, df1_gg=df1 * eps, df2_gg=df2 * eps,
                p_gg=p_gg, ss=ss_h, ss_error=ss_e)


def rm_anova(y, groups=None, names=("A", "B")):
    """y: n subjects x p levels of A x q levels of B (no missing cells).
    groups: optional n labels of a between-subjects factor (2+ groups).
    Returns {effect name: result dict} for A, B, A x B, and with groups also
    group, A x group, B x group, A x B x group."""
    y = np.asarray(y, float)
    if y.ndim != 3 or not np.all(np.isfinite(y)):
        raise ValueError("rm_anova needs a complete subjects x A x B array")
    n, p, q = y.shape
    flat = y.reshape(n, p * q)
    ca, cb = _orthonormal_contrasts(p), _orthonormal_contrasts(q)
    ma, mb = _mean_vector(p), _mean_vector(q)
    within = {names[0]: np.kron(ca, mb), names[1]: np.kron(ma, cb),
              f"{names[0]} x {names[1]}": np.kron(ca, cb)}
    if groups is None:
        design = np.ones((n, 1))
        hyps = {"": np.array([1.0])}
    else:
        labels = sorted(set(groups))
        if len(labels) < 2:
            raise ValueError("a between factor needs at least two groups")
        design = np.ones((n, len(labels)))
        for j, lab in enumerate(labels[:-1]):
            design[:, j + 1] = [1.0 if g == lab else (-1.0 if g == labels[-1] else 0.0) for g in groups]
        hyps = {"": np.eye(1, len(labels)), " x group": np.eye(len(labels))[1:]}
    out = {}
    for name, c in within.items():
        z = flat @ c
        for suffix, h in hyps.items():
            out[name + suffix] = _effect_test(z, design, h)
    if groups is not None:
        z0 = flat @ np.kron(ma, mb)
        out["group"] = _effect_test(z0, design, hyps[" x group"])
    return out


def bonferroni_pairwise(levels):
    """Paired t-tests between every pair of levels (each an array over
    subjects); p multiplied by the number of pairs, capped at 1."""
    keys = list(levels)
    pairs = list(itertools.combinations(keys, 2))
    out = {}
    for a, b in pairs:
        t, p = sps.ttest_rel(levels[a], levels[b])
        out[(a, b)] = dict(t=float(t), p=float(p), p_bonferroni=min(1.0, float(p) * len(pairs)))
    return out


def wilcoxon_paired(a, b):
    """Two-sided Wilcoxon signed-rank test; nan when every pair is equal or too few pairs."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    ok = np.isfinite(a) & np.isfinite(b)
    a, b = a[ok], b[ok]
    if len(a) < 2 or np.all(a == b):
        return dict(statistic=math.nan, p=math.nan, n=int(len(a)))
    r = sps.wilcoxon(a, b)
    return dict(statistic=float(r.statistic), p=float(r.pvalue), n=int(len(a)))


def format_p(p):
    if not math.isfinite(p):
        return "p = n/a"
    return "p < 0.001" if p < 0.001 else f"p = {p:.3f}"


def format_f(r, corrected=False):
    if corrected:
        return f"F({r['df1_gg']:.1f}, {r['df2_gg']:.1f}) = {r['F']:.2f}, {format_p(r['p_gg'])}, GG eps = {r['epsilon']:.2f}"
    return f"F({r['df1']:.0f}, {r['df2']:.0f}) = {r['F']:.2f}, {format_p(r['p'])}"
