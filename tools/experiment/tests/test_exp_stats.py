"""The ANOVA against independent implementations: statsmodels' AnovaRM
(within part), Box's epsilon formula, one-way ANOVA and t-tests (between part)."""
import math
import warnings

import numpy as np
import pandas as pd
import pytest
from scipy import stats as sps
from statsmodels.stats.anova import AnovaRM

from ffexp import stats


def random_design(n=12, p=2, q=3, seed=1, effect_a=0.0, effect_b=0.0):
    rng = np.random.default_rng(seed)
    subj = rng.normal(0, 1, (n, 1, 1))
    y = subj + rng.normal(0, 1, (n, p, q))
    y += effect_a * np.arange(p)[None, :, None]
    y += effect_b * np.arange(q)[None, None, :]
    # non-spherical: one level noisier
    y[:, :, -1] += rng.normal(0, 2, (n, p))
    return y


def anovarm(y):
    n, p, q = y.shape
    rows = [dict(s=s, a=a, b=b, v=y[s, a, b]) for s in range(n) for a in range(p) for b in range(q)]
    return AnovaRM(pd.DataFrame(rows), "v", "s", within=["a", "b"]).fit().anova_table


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_within_effects_equal_statsmodels(seed):
    y = random_design(seed=seed, effect_b=0.3)
    ours = stats.rm_anova(y)
    ref = anovarm(y)
    for name, key in (("A", "a"), ("B", "b"), ("A x B", "a:b")):
        assert ours[name]["F"] == pytest.approx(ref.loc[key, "F Value"], rel=1e-9)
        assert ours[name]["df1"] == ref.loc[key, "Num DF"]
        assert ours[name]["df2"] == ref.loc[key, "Den DF"]
        assert ours[name]["p"] == pytest.approx(ref.loc[key, "Pr > F"], rel=1e-6)


def box_epsilon(cov):
    """Greenhouse-Geisser epsilon from the k x k covariance of the levels (Box 1954)."""
    k = cov.shape[0]
    mean_diag = np.mean(np.diag(cov))
    grand = np.mean(cov)
    row = np.mean(cov, axis=1)
    num = (k * (mean_diag - grand)) ** 2
    den = (k - 1) * (np.sum(cov ** 2) - 2 * k * np.sum(row ** 2) + k ** 2 * grand ** 2)
    return num / den


def test_greenhouse_geisser_epsilon_equals_box_formula():
    y = random_design(n=15, p=2, q=4, seed=7)
    ours = stats.rm_anova(y)
    strength_means = y.mean(axis=1)  # subjects x q
    assert ours["B"]["epsilon"] == pytest.approx(box_epsilon(np.cov(strength_means.T)), rel=1e-9)
    assert 1 / 3 <= ours["B"]["epsilon"] <= 1
    assert ours["A"]["epsilon"] == 1.0  # one contrast: always spherical


def test_between_factor_equals_one_way_anova_of_subject_means():
    y = random_design(n=13, seed=4)  # unequal groups: 7 and 6
    groups = ["hf" if i % 2 else "fh" for i in range(13)]
    ours = stats.rm_anova(y, groups)
    means = y.mean(axis=(1, 2))
    f, p = sps.f_oneway(means[[g == "hf" for g in groups]], means[[g == "fh" for g in groups]])
    assert ours["group"]["F"] == pytest.approx(f, rel=1e-9)
    assert ours["group"]["p"] == pytest.approx(p, rel=1e-9)


def test_rendering_by_order_interaction_equals_t_test_of_differences():
    y = random_design(n=12, seed=5)
    groups = ["hf" if i % 2 else "fh" for i in range(12)]
    ours = stats.rm_anova(y, groups)
    diff = y[:, 1, :].mean(axis=1) - y[:, 0, :].mean(axis=1)
    g = np.array(groups)
    t, p = sps.ttest_ind(diff[g == "hf"], diff[g == "fh"])
    assert ours["A x group"]["F"] == pytest.approx(t ** 2, rel=1e-9)
    assert ours["A x group"]["p"] == pytest.approx(p, rel=1e-9)
    assert ours["A"]["df2"] == 10  # the error term loses the group df


def test_textbook_one_within_two_levels_is_paired_t():
    rng = np.random.default_rng(3)
    a = rng.normal(5, 1, 10)
    b = a + rng.normal(0.5, 0.5, 10)
    y = np.stack([np.stack([a, a], axis=1), np.stack([b, b], axis=1)], axis=1)  # n x 2 x 2
    t, p = sps.ttest_rel(a, b)
    assert stats.rm_anova(y)["A"]["F"] == pytest.approx(t ** 2, rel=1e-9)


def test_planted_effect_found_and_null_not():
    planted = stats.rm_anova(random_design(n=20, seed=11, effect_a=1.5))
    null = stats.rm_anova(random_design(n=20, seed=11, effect_a=0.0))
    assert planted["A"]["p"] < 0.001
    assert null["A"]["p"] > 0.05


def test_bonferroni_multiplies_by_pairs():
    rng = np.random.default_rng(0)
    lv = {s: rng.normal(i, 1, 10) for i, s in enumerate((0.33, 0.66, 1.0))}
    out = stats.bonferroni_pairwise(lv)
    assert list(out) == [(0.33, 0.66), (0.33, 1.0), (0.66, 1.0)]
    for (a, b), r in out.items():
        ref = sps.ttest_rel(lv[a], lv[b])
        assert r["t"] == pytest.approx(ref.statistic, rel=1e-12)
        assert r["p"] == pytest.approx(ref.pvalue, rel=1e-12)
        assert r["p_bonferroni"] == pytest.approx(min(1.0, 3 * ref.pvalue))
    # a pair far apart is capped at 1, not 3 p
    assert stats.bonferroni_pairwise({1: [1.0, 2.0, 3.0], 2: [1.1, 1.9, 3.05]})[(1, 2)]["p_bonferroni"] < 1
    same = stats.bonferroni_pairwise({1: [1.0, 2.0, 3.0], 2: [1.1, 1.9, 3.05], 3: [1.0, 2.1, 2.95]})
    assert max(r["p_bonferroni"] for r in same.values()) == 1.0


def test_wilcoxon_all_equal_is_nan_not_error():
    assert np.isnan(stats.wilcoxon_paired([1, 2, 3], [1, 2, 3])["p"])


def test_wilcoxon_drops_pairs_with_a_missing_value():
    a = [1.0, 2.0, 3.0, float("nan"), 5.0, 6.5]
    b = [2.0, 4.5, 1.0, 7.0, 9.0, float("inf")]
    ours = stats.wilcoxon_paired(a, b)
    ref = sps.wilcoxon([1.0, 2.0, 3.0, 5.0], [2.0, 4.5, 1.0, 9.0])
    assert ours == dict(statistic=float(ref.statistic), p=float(ref.pvalue), n=4)
    assert np.isnan(stats.wilcoxon_paired([1.0, float("nan")], [2.0, 3.0])["p"])  # one pair left


def test_anova_refuses_what_it_cannot_test():
    y = random_design(n=6)
    assert stats.rm_anova(y.tolist())["B"]["F"] == stats.rm_anova(y)["B"]["F"]  # nested lists are fine
    with pytest.raises(ValueError, match="complete"):
        stats.rm_anova(y[:, :, 0])
    y[2, 1, 1] = np.nan
    with pytest.raises(ValueError, match="complete"):
        stats.rm_anova(y)
    with pytest.raises(ValueError, match="two groups"):
        stats.rm_anova(random_design(n=6), groups=["fh"] * 6)


def test_the_summary_prints_p_and_f_as_papers_do():
    assert stats.format_p(float("nan")) == "p = n/a"
    assert stats.format_p(0.0009) == "p < 0.001"
    assert stats.format_p(0.001) == "p = 0.001"
    assert stats.format_p(0.04449) == "p = 0.044"
    r = dict(F=5.4321, df1=2, df2=20, p=0.0123, df1_gg=1.234, df2_gg=12.34, p_gg=0.0346, epsilon=0.617)
    assert stats.format_f(r) == "F(2, 20) = 5.43, p = 0.012"
    assert stats.format_f(r, corrected=True) == "F(1.2, 12.3) = 5.43, p = 0.035, GG eps = 0.62"


def test_the_sd_over_participants_is_the_sample_sd():
    # by hand: 1, 2, 3, 4 have mean 2.5 and squared deviations 2.25 + 0.25 + 0.25 + 2.25 = 5; 5 / (4 - 1)
    assert stats.sample_sd([1.0, 2.0, 3.0, 4.0]) == pytest.approx(math.sqrt(5 / 3), rel=1e-12)
    assert stats.sample_sd([2.0, 4.0, math.nan]) == pytest.approx(math.sqrt(2), rel=1e-12)  # (1 + 1) / 1
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # one participant: no spread, and nothing to warn about
        assert math.isnan(stats.sample_sd([0.7]))
        got = stats.sample_sd([[1.0, 5.0, math.nan], [3.0, math.nan, math.nan]], axis=0)
    assert got[0] == pytest.approx(math.sqrt(2)) and np.isnan(got[1]) and np.isnan(got[2])
