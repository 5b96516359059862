"""plot_classes.py's figure and printed table, read back from the figure on
test_plot_classes.py's hand-made CSV: every bar, goal and marker worked out
from that CSV's rows by hand (row(): heightmap RMS 0.2 x the ratio, the
steady chatter a third of the chatter, the start floor 0.04, the bounds 0.08
/ 0.05 / 0.06 / 0.055 / 0.05 / 0.056 and each heightmap marker over the
thesis row's 0.2)."""
import os

import pytest

import plot_classes
from plot_test_support import run_script
from test_plot_classes import ROWS, write_csv

WIDTH = 0.38  # of a bar; the two trackers' bars sit half a width either side of each class


@pytest.fixture
def figure(tmp_path, monkeypatch):
    path = tmp_path / "classes.csv"
    write_csv(path, ROWS)
    saved = []
    monkeypatch.setattr(plot_classes.ff_files, "save_figure",
                        lambda fig, output, software, description, **kw: saved.append(
                            (fig, output, software, description, kw)))
    assert plot_classes.main([str(path), "-o", str(tmp_path / "classes.png")]) == 0
    assert len(saved) == 1
    return saved[0]


def bars(ax):
    return [(round(p.get_x() + p.get_width() / 2, 6), round(p.get_height(), 6)) for p in ax.patches]


def test_each_panel_has_both_trackers_bars_per_class(figure):
    fig = figure[0]
    hm, fm, lag, chatter = fig.axes
    assert [ax.get_title() for ax in fig.axes] == [
        "heightmap amplitude error / thesis", "frictionmap amplitude error / thesis", "lag [ms]",
        "chatter at rest: RMS of A - 0.5 (log)"]
    left, right = -WIDTH / 2, WIDTH / 2
    # recommended()'s bars first (white-200hz, realistic-100hz), then recommended(profile)'s
    assert bars(hm) == [(left, 0.40), (1 + left, 0.49), (right, 0.40), (1 + right, 0.44)]
    assert bars(fm) == [(left, 0.38), (1 + left, 0.85), (right, 0.38), (1 + right, 0.79)]
    assert bars(lag) == [(left, 0.09), (1 + left, 2.45), (right, 0.09), (1 + right, 1.01)]
    assert bars(chatter) == [(left, 0.014), (1 + left, 0.127), (right, 0.01), (1 + right, 0.02)]
    assert {p.get_facecolor()[:3] for p in hm.patches[2:]} == {(0x1f / 255, 0x5f / 255, 0xa8 / 255)}
    for ax in fig.axes:
        assert list(ax.get_xticks()) == [0, 1]
        assert [t.get_text() for t in ax.get_xticklabels()] == ["white-200hz", "realistic-100hz"]
        assert ax.get_xticklabels()[0].get_rotation() == 30
        assert all(g.get_visible() for g in ax.yaxis.get_gridlines())
        assert not any(g.get_visible() for g in ax.xaxis.get_gridlines())


def test_the_goals_are_dashed_lines_and_the_heightmaps_is_per_class(figure):
    hm, fm, lag, chatter = figure[0].axes
    for ax, goal in ((fm, 0.8), (lag, 1.0), (chatter, 0.01)):
        assert list(ax.lines[0].get_ydata()) == [goal, goal] and ax.lines[0].get_linestyle() == "--"
    (per_class,) = hm.collections
    # white-200hz's own 0.35x, 0.45x elsewhere, each across its class's slot
    assert [seg.tolist() for seg in per_class.get_segments()] == [[[-0.5, 0.35], [0.5, 0.35]],
                                                                  [[0.5, 0.45], [1.5, 0.45]]]


def test_the_heightmap_panel_marks_the_floor_and_the_bounds_over_the_thesis_error(figure):
    hm = figure[0].axes[0]
    at = [WIDTH / 2, 1 + WIDTH / 2]
    marks = {line.get_label(): list(line.get_ydata()) for line in hm.lines}
    assert all(list(line.get_xdata()) == at for line in hm.lines)
    expected = {
        "recommended(profile), never faded": [0.061 / 0.2, 0.11 / 0.2],
        "start floor (direction after 1 px)": [0.2, 0.2],
        "best CV filter, perfect motion detector": [0.4, 0.4],
        "the same, seeing 30 ms ahead": [0.25, 0.25],
        "the same, held at rest, perfect start detector": [0.3, 0.3],
        "heading model, told every standstill": [0.275, 0.275],
        "told all but each stroke's direction (a floor)": [0.25, 0.25],
        "heading model, min-jerk ends predicted": [0.28, 0.28],
    }
    assert marks.keys() == expected.keys()
    assert all(marks[k] == pytest.approx(v) for k, v in expected.items())
    assert [line.get_marker() for line in hm.lines] == ["D", "v", "_", "x", "+", "^", "*", "p"]
    assert [line.get_markersize() for line in hm.lines[2:]] == [14, 8, 8, 8, 8, 8]


def test_the_chatter_panel_is_logarithmic_with_the_steady_rest_and_the_observer(figure):
    chatter = figure[0].axes[3]
    assert chatter.get_yscale() == "log"
    goal, steady, predicted = chatter.lines
    assert list(steady.get_ydata()) == pytest.approx([0.01 / 3, 0.02 / 3])
    assert steady.get_label() == "recommended(profile), after the first 100 ms of each rest"
    assert list(predicted.get_ydata()) == [0.2, 0.2]


def test_each_panel_leaves_room_for_its_legend_and_names_each_thing_once(figure):
    hm, fm, lag, chatter = figure[0].axes
    # above the tallest bar or marker: 1.5 x the autoscaled top (8 x on the log scale)
    assert hm.get_ylim()[1] > 1.5 * 0.55 and fm.get_ylim()[1] > 1.5 * 0.85 and lag.get_ylim()[1] > 1.5 * 2.45
    assert chatter.get_ylim()[1] > 8 * 0.2
    labels = [t.get_text() for t in fm.get_legend().get_texts()]
    assert labels == ["goal", "recommended()", "recommended(profile)"]
    hm_labels = [t.get_text() for t in hm.get_legend().get_texts()]
    assert hm_labels.count("goal") == 1 and len(hm_labels) == 2 + 1 + 8


def test_the_figure_is_titled_and_written_with_the_csvs_metadata(figure, tmp_path):
    fig, output, software, description, options = figure
    assert output == str(tmp_path / "classes.png") and software == "plot_classes.py" and options == {"dpi": 110}
    assert description == "tool: ff-track-bench --classes 0.1.0; traces: 2 classes, made by hand"
    assert fig._suptitle.get_text() == ("ff-track-bench --classes against issue 14's goals; 2 classes, made by hand; "
                                        "ff-track-bench --classes 0.1.0")
    assert fig.axes[0].get_position().x0 < 0.1  # laid out tight (the default margin is 0.125), under the title
    assert not plot_classes.plt.fignum_exists(fig.number)  # closed once written


def test_the_printed_table_says_each_goal_per_class(tmp_path, capsys):
    path = tmp_path / "classes.csv"
    write_csv(path, ROWS)
    assert plot_classes.main([str(path), "-o", str(tmp_path / "classes.png")]) == 0
    assert capsys.readouterr().out.splitlines() == [
        "class              lag         heightmap   frictionmap chatter    ",
        "white-200hz        met         NOT met     met         met        ",
        "realistic-100hz    NOT met     met         met         NOT met    ",
        "goals met (recommended(profile)): lag 1/2, heightmap 1/2, frictionmap 2/2, chatter 1/2",
        "wrote %s" % (tmp_path / "classes.png")]


def test_run_as_a_script_it_finds_ff_files_and_exits_with_mains_code(tmp_path):
    path = tmp_path / "classes.csv"
    write_csv(path, ROWS)
    r = run_script("plot_classes.py", path, "-o", tmp_path / "c.png", cwd=tmp_path)
    assert r.returncode == 0 and os.path.getsize(tmp_path / "c.png") > 0, r.stderr
    r = run_script("plot_classes.py", tmp_path / "none.csv", cwd=tmp_path)
    assert r.returncode == 2 and r.stderr.startswith("plot_classes.py: cannot read")
