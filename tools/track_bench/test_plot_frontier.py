"""plot_frontier.py on a hand-made --frontier CSV: the front and the verdict
per class (worked out by hand below), the figure, and bad input refused with
exit 2."""
import pytest

import plot_frontier
import plot_test_support

HEADER = "class,rest_sigmas,moving_sigmas,heightmap_vs_thesis,rest_rms,pareto,shipping,heightmap_goal,rest_goal"

# white-200hz: (1, 3) is beaten by (1, 4) on both, the others form the front;
# the only point at chatter <= 0.01 is (2.5, 5) at 0.47x, over white's 0.35x.
# slow-fingers: (3, 4) at 0.39x and 0.009 beats the shipping fade on both and
# meets both goals.
ROWS = [
    "white-200hz,1.00,3.00,0.50,0.080,0,0,0.35,0.010",
    "white-200hz,1.00,4.00,0.42,0.040,1,0,0.35,0.010",
    "white-200hz,0.50,2.00,0.37,0.150,1,0,0.35,0.010",
    "white-200hz,2.50,5.00,0.47,0.010,1,1,0.35,0.010",
    "slow-fingers,2.50,5.00,0.40,0.011,0,1,0.45,0.010",
    "slow-fingers,3.00,4.00,0.39,0.009,1,0,0.45,0.010",
]


def write_csv(path, rows, metadata=("tool: ff-track-bench --frontier 0.1.0", "traces: made by hand")):
    plot_test_support.write_csv(path, HEADER, rows, metadata)


def test_front_and_verdict_by_hand(tmp_path):
    path = tmp_path / "frontier.csv"
    write_csv(path, ROWS)
    metadata, classes = plot_frontier.read_frontier(str(path))
    assert metadata["tool"] == "ff-track-bench --frontier 0.1.0"
    assert list(classes) == ["white-200hz", "slow-fingers"]
    front = plot_frontier.pareto(classes["white-200hz"])
    assert [(p["rest_sigmas"], p["moving_sigmas"]) for p in front] == [(2.5, 5.0), (1.0, 4.0), (0.5, 2.0)]
    verdict = plot_frontier.summary(classes)
    assert verdict["white-200hz"][0]["heightmap_vs_thesis"] == 0.47
    assert verdict["white-200hz"][1] is False
    assert verdict["slow-fingers"][0]["rest_sigmas"] == 3.0
    assert verdict["slow-fingers"][1] is True


def test_writes_the_figure_and_prints_the_verdict(tmp_path, capsys):
    path = tmp_path / "frontier.csv"
    write_csv(path, ROWS)
    out = tmp_path / "frontier.png"
    assert plot_frontier.main([str(path), "-o", str(out)]) == 0
    plot_test_support.assert_png_with_metadata(out, "ff-track-bench --frontier 0.1.0")
    printed = capsys.readouterr().out
    assert "classes where some fade meets both goals: 1/2" in printed
    assert "0.47x (2.5 / 5.0 sigma)" in printed


@pytest.mark.parametrize("rows,message", [
    ([], "no rows"),
    (["white-200hz,1.00,3.00,0.50,0.080,1,0,0.35"], "empty field"),
    (["white-200hz,1.00,3.00,fast,0.080,1,0,0.35,0.010"], "not a number"),
    # (1, 3) marked on the front although (1, 4) beats it.
    ([r.replace("0.080,0,0", "0.080,1,0") for r in ROWS], "pareto column of white-200hz disagrees"),
])
def test_bad_input_exits_2_with_one_line(tmp_path, capsys, rows, message):
    path = tmp_path / "bad.csv"
    write_csv(path, rows)
    plot_test_support.assert_refused(plot_frontier.main, path, tmp_path / "x.png", capsys, message)


def test_a_classes_csv_exits_2(tmp_path, capsys):
    path = tmp_path / "classes.csv"
    path.write_text("class,tracker,lag_ms\nwhite-200hz,thesis,6.7\n")
    assert plot_frontier.main([str(path)]) == 2
    assert "not the CSV of ff-track-bench --frontier" in capsys.readouterr().err


def test_an_output_that_is_the_csv_under_any_name_is_refused(tmp_path, capsys, monkeypatch):
    path = tmp_path / "frontier.csv"
    write_csv(path, ROWS)
    plot_test_support.assert_never_writes_over_its_csv(plot_frontier.main, "plot_frontier.py", path, capsys,
                                                       monkeypatch)
