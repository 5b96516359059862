"""plot_classes.py on a hand-made --classes CSV: which goals each class meets
(worked out by hand below), the figure, and bad input refused with exit 2."""
import pytest

import plot_classes
import plot_test_support

HEADER = ("class,tracker,lag_ms,position_rmse_px,direction_mean_deg,heightmap_rms,heightmap_vs_thesis,frictionmap_rms,"
          "frictionmap_vs_thesis,rest_rms,rest_vs_thesis,rest_first_share,rest_steady_rms,stops,settle_median_ms,"
          "settle_max_ms,unsettled_stops,slow_share,floor_0.5px_rms,floor_1.0px_rms,floor_2.0px_rms,"
          "unfaded_heightmap_rms,lookahead_0ms_rms,lookahead_10ms_rms,lookahead_30ms_rms,lookahead_100ms_rms,"
          "lookahead_whole_rms,anchored_0ms_rms,heading_bound_rms,direction_bound_rms,predicted_ends_rms,"
          "predicted_ends_rest_rms")


def row(cls, tracker, lag, hm_ratio, fm_ratio, rest, unfaded=""):
    return ",".join(str(v) for v in (cls, tracker, lag, 1.0, 4.0, 0.2 * hm_ratio, hm_ratio, 0.04 * fm_ratio, fm_ratio,
                                     rest, rest / 0.3, 0.8, rest / 3, 12, 0.0, 29.5, 0, 0.13, 0.02, 0.04, 0.06, unfaded,
                                     0.08, 0.07, 0.05, 0.03, 0.02, 0.06, 0.055, 0.05, 0.056, 0.2))


def write_csv(path, rows, metadata=("tool: ff-track-bench --classes 0.1.0", "traces: 2 classes, made by hand")):
    plot_test_support.write_csv(path, HEADER, rows, metadata)


ROWS = [
    row("white-200hz", "thesis", 6.7, 1.0, 1.0, 0.3),
    row("white-200hz", "recommended()", 0.09, 0.40, 0.38, 0.014),
    # 0.40x: under the general 0.45x but over white's own 0.35x; chatter exactly at the goal counts as met.
    row("white-200hz", "recommended(profile)", 0.09, 0.40, 0.38, 0.01, 0.061),
    row("realistic-100hz", "thesis", 8.6, 1.0, 1.0, 0.32),
    row("realistic-100hz", "recommended()", 2.45, 0.49, 0.85, 0.127),
    # lag just over 1 ms, frictionmap just under 0.8x.
    row("realistic-100hz", "recommended(profile)", 1.01, 0.44, 0.79, 0.02, 0.11),
]


def test_goal_status_of_the_shipping_rows_by_hand(tmp_path):
    path = tmp_path / "classes.csv"
    write_csv(path, ROWS)
    metadata, rows = plot_classes.read_classes(str(path))
    assert metadata["tool"] == "ff-track-bench --classes 0.1.0"
    assert plot_classes.goal_status(rows) == {
        "white-200hz": {"lag": True, "heightmap": False, "frictionmap": True, "chatter": True},
        "realistic-100hz": {"lag": False, "heightmap": True, "frictionmap": True, "chatter": False},
    }


def test_writes_the_figure_and_prints_the_goals(tmp_path, capsys):
    path = tmp_path / "classes.csv"
    write_csv(path, ROWS)
    out = tmp_path / "classes.png"
    assert plot_classes.main([str(path), "-o", str(out)]) == 0
    plot_test_support.assert_png_with_metadata(out, "ff-track-bench --classes 0.1.0")
    printed = capsys.readouterr().out
    assert "goals met (recommended(profile)): lag 1/2, heightmap 1/2, frictionmap 2/2, chatter 1/2" in printed


def test_a_csv_without_the_predicted_ends_still_plots(tmp_path):
    # Written before those columns existed: the figure leaves them out.
    old_header = HEADER.rsplit(",", 2)[0]
    old_rows = [r.rsplit(",", 2)[0] for r in ROWS]
    path = tmp_path / "classes.csv"
    plot_test_support.write_csv(path, old_header, old_rows, ("tool: ff-track-bench --classes 0.1.0",))
    out = tmp_path / "classes.png"
    assert plot_classes.main([str(path), "-o", str(out)]) == 0
    plot_test_support.assert_png_with_metadata(out, "ff-track-bench --classes 0.1.0")


@pytest.mark.parametrize("content,message", [
    ("", "no rows"),
    ("# only metadata\n", "no rows"),
    ("class,tracker\nwhite-200hz,thesis\n", "no column"),
    (HEADER + "\n" + row("white-200hz", "recommended(profile)", "fast", 0.4, 0.4, 0.01) + "\n", "not a number"),
    (HEADER + "\n" + row("white-200hz", "thesis", 6.7, 1.0, 1.0, 0.3) + "\n", "no recommended(profile) rows"),
])
def test_bad_input_exits_2_with_one_line(tmp_path, capsys, content, message):
    path = tmp_path / "bad.csv"
    path.write_text(content)
    plot_test_support.assert_refused(plot_classes.main, path, tmp_path / "x.png", capsys, message)


def test_a_missing_file_exits_2(tmp_path, capsys):
    assert plot_classes.main([str(tmp_path / "none.csv")]) == 2
    assert "cannot read" in capsys.readouterr().err


def test_an_output_that_is_the_csv_under_any_name_is_refused(tmp_path, capsys, monkeypatch):
    path = tmp_path / "classes.csv"
    write_csv(path, ROWS)
    plot_test_support.assert_never_writes_over_its_csv(plot_classes.main, "plot_classes.py", path, capsys, monkeypatch)
