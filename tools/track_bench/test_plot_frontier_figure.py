"""plot_frontier.py's figure and printed verdict, read back on
test_plot_frontier.py's hand-made CSV: the points, the front, the shipping
star, the goal region and the axes worked out from its rows by hand (the
smallest chatter is slow-fingers' 0.009, so a chatter is drawn no lower than
half of it, 0.0045, and the axes start at half of that)."""
import os

import pytest

import plot_frontier
from plot_test_support import run_script
from test_plot_frontier import ROWS, write_csv

FLOOR = 0.0045


def draw(tmp_path, monkeypatch, rows):
    path = tmp_path / "frontier.csv"
    write_csv(path, rows)
    saved = []
    monkeypatch.setattr("plot_classes.ff_files.save_figure",
                        lambda fig, output, software, description, **kw: saved.append((fig, software, kw)))
    assert plot_frontier.main([str(path), "-o", str(tmp_path / "frontier.png")]) == 0
    assert len(saved) == 1
    return saved[0]


def xy(line):
    return list(zip(line.get_xdata(), line.get_ydata()))


def test_each_class_has_its_points_front_shipping_fade_and_goals(tmp_path, monkeypatch):
    fig, software, options = draw(tmp_path, monkeypatch, ROWS)
    assert software == "plot_frontier.py" and options == {"dpi": 100}
    assert tuple(fig.get_size_inches()) == pytest.approx((3.6 * 2 + 1, 3.4 + 0.8))  # two panels side by side
    white, slow = fig.axes
    assert not plot_frontier.plt.fignum_exists(fig.number)  # closed once written (read back all the same)
    assert (white.get_title(), slow.get_title()) == ("white-200hz", "slow-fingers")
    points, front, star, goal_hm, goal_rest = white.lines
    assert xy(points) == [(0.08, 0.5), (0.04, 0.42), (0.15, 0.37), (0.01, 0.47)]
    assert xy(front) == [(0.01, 0.47), (0.04, 0.42), (0.15, 0.37)] and front.get_linestyle() == "-"
    assert xy(star) == [(0.01, 0.47)] and star.get_label() == "shipping (2.5 / 5.0 σ)"
    assert list(goal_hm.get_ydata()) == [0.35, 0.35] and list(goal_rest.get_xdata()) == [0.01, 0.01]
    # both goals met: left of the chatter goal, under the heightmap goal
    (region,) = white.collections
    corners = region.get_paths()[0].vertices
    assert (corners[:, 0].min(), corners[:, 0].max()) == pytest.approx((FLOOR / 2, 0.01))
    assert (corners[:, 1].min(), corners[:, 1].max()) == pytest.approx((0, 0.35))
    assert white.get_xscale() == "log"
    assert white.get_xlim() == pytest.approx((FLOOR / 2, 0.3)) and white.get_ylim() == (0, 1.0)
    assert (white.get_xlabel(), white.get_ylabel()) == ("chatter at rest (RMS of A - 0.5)", "heightmap error / thesis")
    assert all(g.get_visible() for g in white.xaxis.get_gridlines() + white.yaxis.get_gridlines())
    assert [t.get_text() for t in white.get_legend().get_texts()] == [
        "both goals", "a fade of the grid", "Pareto front", "shipping (2.5 / 5.0 σ)"]
    # slow-fingers: (3, 4) beats the shipping fade on both, so the front is that one point
    assert xy(slow.lines[1]) == [(0.009, 0.39)] and xy(slow.lines[2]) == [(0.011, 0.40)]
    assert slow.get_xlim() == pytest.approx((FLOOR / 2, 0.022))
    assert fig._suptitle.get_text() == ("ff-track-bench --frontier: the fade's trade per class; made by hand; "
                                        "ff-track-bench --frontier 0.1.0")


def test_a_chatter_of_0_sits_at_the_floor_a_ratio_over_1_widens_the_axis_and_spare_panels_are_blank(
        tmp_path, monkeypatch):
    rows = ["white-200hz,1.00,3.00,1.40,0.000,1,0,0.35,0.010", "white-200hz,2.50,5.00,0.47,0.020,1,1,0.35,0.010"]
    rows += ["class-%d,2.50,5.00,0.40,0.020,1,1,0.45,0.010" % k for k in range(4)]
    fig = draw(tmp_path, monkeypatch, rows)[0]
    assert len(fig.axes) == 8 and [ax.axison for ax in fig.axes] == [True] * 5 + [False] * 3  # 4 columns, 2 rows
    white = fig.axes[0]
    # the least chatter above 0 is 0.02: a chatter of 0 is drawn at half of it, 0.01
    assert xy(white.lines[0]) == [(0.01, 1.40), (0.02, 0.47)]
    assert white.get_ylim() == pytest.approx((0, 1.40 * 1.05)) and white.get_xlim() == pytest.approx((0.005, 0.04))
    # no chatter above 0 anywhere: the floor is 1e-4 / 2
    flat = ["white-200hz,2.50,5.00,0.47,0.000,1,1,0.35,0.010"]
    assert xy(draw(tmp_path, monkeypatch, flat)[0].axes[0].lines[0]) == [(5e-5, 0.47)]


def test_the_printed_verdict_per_class(tmp_path, capsys):
    path = tmp_path / "frontier.csv"
    write_csv(path, ROWS + ["tremor,2.50,5.00,0.40,0.020,1,1,0.45,0.010"])
    assert plot_frontier.main([str(path), "-o", str(tmp_path / "f.png")]) == 0
    assert capsys.readouterr().out.splitlines() == [
        "class              best heightmap at the chatter goal both goals",
        "white-200hz        0.47x (2.5 / 5.0 sigma)            NOT met",
        "slow-fingers       0.39x (3.0 / 4.0 sigma)            met",
        "tremor             none that quiet                    NOT met",
        "classes where some fade meets both goals: 1/3",
        "wrote %s" % (tmp_path / "f.png")]


def test_run_as_a_script_it_finds_its_modules_and_exits_with_mains_code(tmp_path):
    path = tmp_path / "frontier.csv"
    write_csv(path, ROWS)
    r = run_script("plot_frontier.py", path, "-o", tmp_path / "f.png", cwd=tmp_path)
    assert r.returncode == 0 and os.path.getsize(tmp_path / "f.png") > 0, r.stderr
    r = run_script("plot_frontier.py", path, "-o", path, cwd=tmp_path)
    assert r.returncode == 2 and r.stderr == "plot_frontier.py: output %s is the input %s: a tool never writes over " \
                                             "its own input\n" % (path, path)
