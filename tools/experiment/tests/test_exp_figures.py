"""The figures draw what the logs say: each panel's data recomputed from
trials.csv by hand (numpy), and the axes a reader needs."""
import math
import os
import subprocess
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from PIL import Image  # noqa: E402

from ffexp import analysis, figures, geometry, logs, metrics  # noqa: E402
from exp_synthetic import write_participant  # noqa: E402

STRENGTHS = (1.0, 0.66, 0.33)


@pytest.fixture(scope="module")
def two(tmp_path_factory):
    root = tmp_path_factory.mktemp("figures")
    folders = [write_participant(str(root), n, lambda r, s: 0.9 if r == "frictionmap" else 0.5 * s,
                                 lambda r, i: 2.0 + 3.0 / i) for n in (1, 2)]
    return [analysis.Participant(f) for f in folders], [logs.read_trials(f) for f in folders]


@pytest.fixture
def ax():
    fig, ax = plt.subplots()
    yield ax
    plt.close(fig)


def _hits(trials, r, s):
    return np.mean([t["hit"] for t in trials if t["rendering"] == r and t["strength"] == s])


def _labels(ax):
    return [t.get_text() for t in ax.get_legend().get_texts()]


def test_hit_rates_are_each_participants_and_their_mean(two, ax):
    ps, trials = two
    figures.hit_rates(ax, ps)
    lines = ax.get_lines()
    for i, r in enumerate(("heightmap", "frictionmap")):
        mine = lines[3 * i:3 * i + 3]  # two participants' dots, then the mean
        expected = [[_hits(tr, r, s) for s in STRENGTHS] for tr in trials]
        for line, e in zip(mine[:2], expected):
            assert line.get_marker() == "." and list(line.get_xdata()) == [0, 1, 2]
            np.testing.assert_allclose(line.get_ydata(), e)
        np.testing.assert_allclose(mine[2].get_ydata(), np.mean(expected, axis=0))
        assert mine[2].get_label() == r and {to_rgba(l.get_color()) for l in mine} == {to_rgba(figures.COLOURS[r])}
    assert list(lines[6].get_ydata()) == [1 / 3, 1 / 3]
    assert _labels(ax) == ["heightmap", "frictionmap", "chance"]
    assert ax.get_ylim() == (0, 1.02) and ax.get_ylabel() == "hit rate" and ax.get_xlabel() == "strength"
    assert [t.get_text() for t in ax.get_xticklabels()] == ["1.00", "0.66", "0.33"]


def test_movement_time_boxes_hold_the_correct_trials(two, ax):
    ps, trials = two
    figures.per_trial_boxes(ax, ps, "movement_time", "movement time (s)")
    # a median line spans its box (0.25 wide); caps are half that
    medians = sorted((float(np.mean(l.get_xdata())), l.get_ydata()[0]) for l in ax.get_lines()
                     if len(l.get_xdata()) == 2 and math.isclose(np.ptp(l.get_xdata()), 0.25))
    expected = sorted((k + (i - 0.5) * 0.3, np.median([t["movement_time"] for tr in trials for t in tr
                                                       if t["hit"] and t["rendering"] == r and t["strength"] == s]))
                      for i, r in enumerate(("heightmap", "frictionmap")) for k, s in enumerate(STRENGTHS))
    np.testing.assert_allclose(medians, expected, rtol=1e-9)
    faces = [to_rgba(p.get_facecolor()) for p in ax.patches]
    assert faces == [to_rgba(figures.COLOURS[r], 0.5) for r in ("heightmap", "frictionmap") for _ in STRENGTHS]
    assert ax.get_ylabel() == "movement time (s)" and ax.get_xlabel() == "strength"


def test_an_empty_cell_is_an_empty_box_not_an_error(two, ax):
    ps, _ = two
    p = analysis.Participant.__new__(analysis.Participant)
    p.trials = [t for t in ps[0].trials if not (t["rendering"] == "heightmap" and t["strength"] == 0.33)]
    figures.per_trial_boxes(ax, [p], "movement_time", "movement time (s)")
    assert len(ax.patches) == 6


def test_angle_histograms_are_normalised_with_the_paths_marked(two, ax):
    ps, _ = two
    figures.angles(ax, ps)
    steps = [l for l in ax.get_lines() if l.get_label() in ("heightmap", "frictionmap")]
    assert [l.get_label() for l in steps] == ["heightmap", "frictionmap"]
    for line, r in zip(steps, ("heightmap", "frictionmap")):
        a = np.concatenate([t["angles"] for p in ps for t in p.trials if t["rendering"] == r])
        counts, edges = np.histogram(a, bins=72, range=(-180, 180))
        np.testing.assert_allclose(line.get_xdata(), edges[:-1])
        np.testing.assert_allclose(line.get_ydata(), counts / counts.sum())
    marks = sorted(l.get_xdata()[0] for l in ax.get_lines() if l.get_linestyle() == "--")
    steepest = math.degrees(math.atan(0.5))  # the top path's slope mid-way: 6 * 200 * 300 * 300 / 600^3
    np.testing.assert_allclose(marks, [-steepest, 0.0, steepest])
    assert ax.get_xlim() == (-180, 180)
    assert _labels(ax) == ["heightmap", "frictionmap", "paths' ends, 0°", "paths' steepest, ±26.6°"]
    assert ax.get_ylabel() == "fraction" and ax.get_xlabel().startswith("movement angle (deg")


def test_block_hit_rates_are_the_mean_and_sd_of_each_half(two, ax):
    ps, trials = two
    figures.blocks(ax, ps)
    means = [l for l in ax.get_lines() if l.get_marker() == "o"]
    assert len(means) == 2
    for line, r in zip(means, ("heightmap", "frictionmap")):
        per = [[np.mean([t["hit"] for t in sorted((t for t in tr if t["rendering"] == r), key=lambda t: t["trial"])
                         ][k * 45:(k + 1) * 45]) for k in (0, 1)] for tr in trials]
        np.testing.assert_allclose(line.get_ydata(), np.mean(per, axis=0))
        assert list(line.get_xdata()) == [1, 2] and to_rgba(line.get_color()) == to_rgba(figures.COLOURS[r])
    for bars, r in zip([c for c in ax.containers], ("heightmap", "frictionmap")):
        per = np.array([[np.mean([t["hit"] for t in tr if t["rendering"] == r and (t["trial"] - 1) % 90 // 45 == k])
                         for k in (0, 1)] for tr in trials])
        # two participants: the sample SD of a and b is |a - b| / sqrt(2)
        half_bars = [abs(seg[1][1] - seg[0][1]) / 2 for seg in bars.lines[2][0].get_segments()]
        np.testing.assert_allclose(half_bars, np.abs(per[0] - per[1]) / math.sqrt(2))
    assert ax.get_ylim() == (0, 1.02) and [t for t in ax.get_xticks()] == [1, 2]
    assert ax.get_xlabel() == "block of 45 trials" and ax.get_ylabel() == "hit rate"


def test_the_learning_curve_and_its_fit_are_drawn_as_given(ax):
    x = np.arange(1.0, 6.0)
    stats = {"heightmap": dict(x=x, mean=2.0 + 4.0 / x, sd=np.full(5, 0.5), fit=(4.0, 1.0, 2.0)),
             "frictionmap": dict(x=x, mean=np.full(5, 3.0), sd=np.zeros(5), fit=(math.nan,) * 3)}
    figures.learning(ax, stats)
    lines = ax.get_lines()
    assert len(lines) == 3  # no fit line for a failed fit
    np.testing.assert_allclose(lines[0].get_ydata(), 2.0 + 4.0 / x)
    np.testing.assert_allclose(lines[1].get_ydata(), 4.0 * x ** -1.0 + 2.0)
    assert lines[1].get_linestyle() == "--" and lines[1].get_label() == "4.0 x^-1.00 + 2.0"
    band = ax.collections[0].get_paths()[0].vertices
    assert band[:, 1].min() == pytest.approx((2.0 + 4.0 / x - 0.5).min())
    assert band[:, 1].max() == pytest.approx((2.0 + 4.0 / x + 0.5).max())
    assert _labels(ax) == ["heightmap", "4.0 x^-1.00 + 2.0", "frictionmap"]
    assert ax.get_ylabel() == "movement time (s)" and ax.get_xlabel() == "trial of the rendering (window end - 9)"


def test_raw_paths_colour_each_trial_by_its_hit(two, ax):
    ps, trials = two
    figures.raw_paths(ax, ps[0], "heightmap")
    assert len([l for l in ax.get_lines() if l.get_color() == "black"]) == 3  # the three paths
    (collection,) = [c for c in ax.collections if isinstance(c, LineCollection)]
    mine = [t for t in trials[0] if t["rendering"] == "heightmap"]
    assert [to_rgba(c) for c in collection.get_colors()] == [to_rgba("green" if t["hit"] else "red", 0.6)
                                                              for t in mine]
    first = [t for t in ps[0].trials if t["rendering"] == "heightmap"][0]["path"]
    np.testing.assert_allclose(collection.get_segments()[0], np.column_stack(first[1:]))
    assert ax.get_title() == "heightmap: trials 91-180"  # participant 1 does the frictionmap first
    assert ax.get_xlim() == (0, geometry.WIDTH) and ax.get_ylim() == (geometry.HEIGHT, 0)  # y down, as on screen
    assert ax.get_aspect() == 1.0  # a stroke's angles as drawn on the screen


def _saved(monkeypatch):
    """Every figure saved, by file name, kept open for the test to read (and still written)."""
    saved = {}
    real = figures.ff_files.save_figure

    def keep(fig, path, software, **kw):
        saved[os.path.basename(path)] = fig
        fig.canvas.draw()  # what the file shows: text extents need a draw
        _clear_of_each_other(fig)
        real(fig, path, software, **kw)
    monkeypatch.setattr(figures.ff_files, "save_figure", keep)
    return saved


def _clear_of_each_other(fig):
    """Each panel with its labels lies inside the figure and clear of the others."""
    renderer = fig.canvas.get_renderer()
    boxes = [ax.get_tightbbox(renderer) for ax in fig.axes]
    for i, box in enumerate(boxes):
        assert box.x0 >= 0 and box.y0 >= 0 and box.x1 <= fig.bbox.x1 and box.y1 <= fig.bbox.y1
        for other in boxes[i + 1:]:
            assert not box.overlaps(other)


def test_the_group_figures_hold_their_panels_readably(two, tmp_path, monkeypatch):
    ps, _ = two
    saved = _saved(monkeypatch)
    open_before = plt.get_fignums()
    names = figures.group_figures(ps, analysis.group_statistics(ps), str(tmp_path))
    assert names == ["fig11_hit_rates.png", "fig12_movement_times.png", "fig13_direction_changes.png",
                     "fig14_movement_angles.png", "fig15_learning.png"] == list(saved)
    assert plt.get_fignums() == open_before  # each closed once written
    ylabels = {n: [ax.get_ylabel() for ax in f.axes] for n, f in saved.items()}
    assert ylabels == {"fig11_hit_rates.png": ["hit rate"], "fig12_movement_times.png": ["movement time (s)"],
                       "fig13_direction_changes.png": ["direction changes"], "fig14_movement_angles.png": ["fraction"],
                       "fig15_learning.png": ["hit rate", "movement time (s)"]}
    assert len(saved["fig11_hit_rates.png"].axes[0].get_lines()) == 2 * 3 + 1  # 2 x (2 participants + mean), chance
    assert len(saved["fig12_movement_times.png"].axes[0].patches) == 6
    blocks, learning = saved["fig15_learning.png"].axes
    assert len([l for l in blocks.get_lines() if l.get_marker() == "o"]) == 2
    assert [l.get_label() for l in learning.get_lines()][0::2] == ["heightmap", "frictionmap"]
    for name in names:
        with Image.open(tmp_path / name) as im:
            assert im.info["Software"] == figures.SOFTWARE


def test_the_participant_page_has_panels_a_to_j(two, tmp_path, monkeypatch):
    ps, trials = two
    saved = _saved(monkeypatch)
    open_before = plt.get_fignums()
    figures.participant_page(ps[0], str(tmp_path / "participant_1.png"))
    assert plt.get_fignums() == open_before
    fig = saved["participant_1.png"]
    axes = fig.axes
    assert len(axes) == 10 and fig._suptitle.get_text() == "participant 1 (order fm-hm)"
    assert [ax.get_title() for ax in axes[:2]] == ["frictionmap: trials 1-90", "heightmap: trials 91-180"]
    assert [ax.get_ylabel() for ax in axes[2:]] == ["hit rate", "movement time (s)", "direction changes", "hit rate",
                                                    "MT, moving avg (s)", "direction changes, moving avg",
                                                    "total |dy| (px)", "fraction"]
    assert len(axes[2].get_lines()) == 2 * 2 + 1 and len(axes[3].patches) == 6 and len(axes[4].patches) == 6
    assert len([l for l in axes[5].get_lines() if l.get_marker() == "o"]) == 2
    for ax, key in ((axes[6], "movement_time"), (axes[7], "direction_changes")):
        for line, r in zip(ax.get_lines(), ("heightmap", "frictionmap"), strict=True):
            series = [t[key] for t in sorted((t for t in ps[0].trials if t["rendering"] == r), key=lambda t: t["trial"])]
            np.testing.assert_allclose(line.get_ydata(), np.convolve(series, np.ones(10) / 10, mode="valid"))
            assert to_rgba(line.get_color()) == to_rgba(figures.COLOURS[r])
    (dots,) = axes[8].collections
    by_hand = [(np.abs(np.diff(t["path"][1])).sum() - 610.0, np.abs(np.diff(t["path"][2])).sum()) for t in ps[0].trials]
    np.testing.assert_allclose(dots.get_offsets(), by_hand)
    np.testing.assert_allclose(dots.get_sizes(), [8 + 20 * t["strength"] for t in trials[0]])
    assert axes[8].get_xlabel() == "extra |dx| (px)"
    assert len([l for l in axes[9].get_lines() if l.get_label() in ("heightmap", "frictionmap")]) == 2
    with Image.open(tmp_path / "participant_1.png") as im:
        assert im.size == (880, 800) and im.info["Software"] == figures.SOFTWARE  # 11 x 10 in at 80 dpi


def test_figures_are_drawn_without_a_display_whatever_the_environment_asks():
    # a lab computer may set another backend: the report is still written to files, headless
    code = "import matplotlib; import ffexp.figures; print(matplotlib.get_backend())"
    here = os.path.dirname(os.path.abspath(__file__))
    paths = [os.path.join(here, ".."), os.path.join(here, "..", "..", "common"), os.environ.get("PYTHONPATH")]
    env = dict(os.environ, MPLBACKEND="svg", PYTHONPATH=os.pathsep.join(p for p in paths if p))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    assert out.strip().lower() == "agg"
