"""What plot_replay.py draws, read back from the figure: a hand-written replay
and trace whose points, segments, colours and limits follow by hand."""
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import plot_replay  # noqa: E402

# t_us, x, y, amplitude, present: the finger lifted at the fourth tick
TICKS = [(1_000_000, 100, 100, 0.2, 1), (1_005_000, 110, 100, 0.4, 1), (1_010_000, 120, 110, 0.8, 1),
         (1_015_000, 0, 0, 0.5, 0), (1_020_000, 200, 200, 1.0, 1), (1_025_000, 210, 200, 0.6, 1)]
# t_us, x, y, touch: a lifted report has no position; the last comes after the replay's last tick
REPORTS = [(1_000_000, 100, 100, 1), (1_002_500, 105, 100, 1), (1_005_000, 110, 100, 1), (1_010_000, 120, 110, 1),
           (1_012_000, "", "", 0), (1_015_000, "", "", 0), (1_020_000, 200, 200, 1), (1_025_000, 210, 200, 1),
           (1_030_000, 300, 300, 1)]


def write_pair(folder, ticks=TICKS, reports=REPORTS, meta=(), summary=True):
    trace = os.path.join(folder, "trace.csv")
    with open(trace, "w") as f:
        f.write("# a comment line the reader skips\nt_us,x,y,touch\n\n")
        f.writelines(f"{t},{x},{y},{touch}\n" for t, x, y, touch in reports)
    replay = os.path.join(folder, "trace.csv.replay.csv")
    with open(replay, "w") as f:
        f.write(f"# input: trace.csv ({os.path.getsize(trace)} bytes)\n")
        f.writelines(f"# {line}\n" for line in meta)
        f.write("t_us,x,y,vx,vy,amplitude,dac,present\n")
        f.writelines(f"{t},{x},{y},0,0,{a},0,{p}\n" for t, x, y, a, p in ticks)
        if summary:  # ff-replay's last line: without it the replay did not finish
            f.write(f"# summary: ticks={len(ticks)} samples={len(reports)} rejected=0 rows_left_out=0\n")
    return trace, replay


@pytest.fixture
def drawn(tmp_path, monkeypatch, ff_scene_render):
    """Runs plot_replay's main() on the files; returns the figure it saved and what it printed."""
    saved = []
    monkeypatch.setattr(plot_replay.ff_files, "save_figure",
                        lambda fig, path, software, description, **kw: saved.append((fig, path, software, description)))

    def draw(trace, replay, *options):
        monkeypatch.setattr(sys, "argv", ["plot_replay.py", trace, replay, "-o", str(tmp_path / "p.png"),
                                          "--bin", ff_scene_render, *options])
        plot_replay.main()
        (fig, path, software, description), = saved[-1:]
        assert path == str(tmp_path / "p.png") and software == "plot_replay.py"
        return fig, description
    return draw


def legend_labels(ax):
    return [t.get_text() for t in ax.get_legend().get_texts()]


def test_the_path_its_colours_the_reports_and_the_start(tmp_path, drawn, capsys):
    trace, replay = write_pair(str(tmp_path))
    fig, description = drawn(trace, replay)
    assert capsys.readouterr().out == f"wrote {tmp_path / 'p.png'}\n"
    top, bar, bottom = fig.axes
    (reports, start), (path,) = top.lines, top.collections
    # the touching reports up to the replay's last tick
    assert list(reports.get_xdata()) == [100, 105, 110, 120, 200, 210]
    assert list(reports.get_ydata()) == [100, 100, 100, 110, 200, 200]
    # segments only between ticks with a finger, coloured by their ends' mean amplitude
    assert np.array_equal(np.array(path.get_segments()),
                          [[[100, 100], [110, 100]], [[110, 100], [120, 110]], [[200, 200], [210, 200]]])
    assert np.allclose(path.get_array(), [0.3, 0.6, 0.8])
    assert (list(start.get_xdata()), list(start.get_ydata())) == ([100], [100])
    assert legend_labels(top) == ["sensor reports", "start"]
    assert top.get_xlim() == (0, 800) and top.get_ylim() == (480, 0) and top.get_aspect() == 1.0
    assert top.get_xlabel().startswith("x [px]") and top.get_ylabel() == "y [px]"
    assert top.get_title() == "trace.csv: no scene"
    assert bar.get_ylabel() == "rendered amplitude A (1 = slippery)"
    # the amplitude against time since the first tick; no value where no finger
    (upper,) = bottom.lines
    assert np.allclose(upper.get_xdata(), [0, 0.005, 0.01, 0.015, 0.02, 0.025])
    assert np.array_equal(upper.get_ydata(), [0.2, 0.4, 0.8, np.nan, 1.0, 0.6], equal_nan=True)
    assert legend_labels(bottom) == ["rendered (finger down)", "no finger (idle)"]
    assert bottom.get_xlim() == pytest.approx((0, 0.025)) and bottom.get_ylim() == (-0.02, 1.02)
    assert bottom.get_xlabel() == "time since the first report [s]" and bottom.get_ylabel() == "amplitude A"
    assert bottom.xaxis.get_gridlines()[0].get_visible() and not top.xaxis.get_gridlines()[0].get_visible()
    assert not plot_replay.plt.fignum_exists(fig.number)  # closed once saved: a batch of plots does not pile up
    assert description.startswith(f"trace: {trace}; replay: {replay}; input: trace.csv (")


def test_a_window_draws_only_its_ticks_and_reports(tmp_path, drawn):
    trace, replay = write_pair(str(tmp_path))
    fig, _ = drawn(trace, replay, "--from", "0.012", "--to", "0.03", "--title", "second stroke")
    top, _, bottom = fig.axes
    (reports, start), (path,) = top.lines, top.collections
    assert list(reports.get_xdata()) == [200, 210]
    assert np.array_equal(np.array(path.get_segments()), [[[200, 200], [210, 200]]])
    assert (list(start.get_xdata()), list(start.get_ydata())) == ([200], [200])  # the window's first finger
    assert top.get_title() == "second stroke"
    assert bottom.get_xlim() == pytest.approx((0.015, 0.025))


def test_without_a_lift_or_a_finger_there_is_nothing_to_mark(tmp_path, drawn):
    trace, replay = write_pair(str(tmp_path), ticks=[(t, x, y, a, 1) for t, x, y, a, _ in TICKS[:3]])
    _, _, bottom = drawn(trace, replay)[0].axes
    assert legend_labels(bottom) == ["rendered (finger down)"]
    trace, replay = write_pair(str(tmp_path), ticks=[(t, x, y, a, 0) for t, x, y, a, _ in TICKS[:1]])
    top, _, bottom = drawn(trace, replay)[0].axes
    assert [line.get_label() for line in top.lines] == ["sensor reports"]  # no start without a finger
    assert bottom.get_xlim() == pytest.approx((0, 1e-3))  # one tick: a span to draw in


def test_long_paths_are_thinned_to_max_segments(tmp_path, drawn):
    ticks = [(1_000_000 + 5000 * i, 10 + i, 100, 0.5, 1) for i in range(12)]
    trace, replay = write_pair(str(tmp_path), ticks=ticks, reports=[(t, x, y, 1) for t, x, y, _, _ in ticks])
    top = drawn(trace, replay, "--max-segments", "4")[0].axes[0]
    assert list(top.lines[0].get_xdata()) == [10, 13, 16, 19]  # every third report
    assert np.array_equal(np.array(top.collections[0].get_segments())[:, 0, 0], [10, 13, 16])


@pytest.mark.parametrize("words, needs, title", [
    (["--scene", "heightmap", "--target", "top"], "position+direction", "heightmap, target top"),
    (["--scene", "frictionmap", "--target", "top"], "position", "frictionmap, target top"),
    (["--scene", "neutral"], "constant", "neutral"),
])
def test_the_scene_is_drawn_as_what_it_needs(tmp_path, drawn, words, needs, title):
    trace, replay = write_pair(str(tmp_path), meta=[f"scene: {' '.join(words)}"])
    top = drawn(trace, replay)[0].axes[0]
    note = top.texts[0].get_text()
    if needs == "position+direction":
        assert len(top.images) == 1 and note.startswith("background: |G_norm|, arrows downhill")
        assert any(type(c).__name__ == "Quiver" for c in top.collections)
    elif needs == "position":
        assert len(top.images) == 1 and note == "background: amplitude map (dark = slippery)"
        assert top.images[0].get_array().max() > top.images[0].get_array().min()  # the path is brighter
    else:
        assert not top.images and note.startswith("constant scene")
    assert top.get_title().startswith(f"trace.csv: {title}")  # and what ff-scene-render adds (its strength)


def test_a_replay_without_metadata_is_plotted_with_a_warning(tmp_path, drawn, capsys):
    trace, replay = write_pair(str(tmp_path))
    lines = open(replay).read().splitlines()
    with open(replay, "w") as f:
        f.write("\n".join(lines[1:]) + "\n")
    drawn(trace, replay)
    assert "has no metadata (an old ff-replay?): not checked against the trace" in capsys.readouterr().err


def test_min_max_per_column_keeps_each_columns_extremes():
    seconds = np.arange(10) * 0.1
    values = np.array([0.1, 0.9, 0.5, 0.3, 0.2, np.nan, np.nan, np.nan, np.nan, np.nan])
    ts, lo, hi = plot_replay.min_max_per_column(seconds, values, 2)
    assert np.allclose(ts, [0.0, 0.5])
    assert np.array_equal(lo, [0.1, np.nan], equal_nan=True) and np.array_equal(hi, [0.9, np.nan], equal_nan=True)
    ts, lo, hi = plot_replay.min_max_per_column(seconds, values, 5)  # 10 <= 2 * 5: as they are
    assert ts is seconds and lo is values and hi is values


def test_the_trace_reader_skips_comments_and_empty_rows_and_names_a_bad_row(tmp_path):
    path = tmp_path / "t.csv"
    path.write_text("\ufeff# made by hand\nt_us, x, y, touch\n0,1.5,2,1\n\n5000,,,0\n")
    trace = plot_replay.read_trace(str(path))
    assert list(trace["t_us"]) == [0, 5000] and list(trace["touch"]) == [1, 0]
    assert trace["x"][0] == 1.5 and np.isnan(trace["x"][1]) and np.isnan(trace["y"][1])
    path.write_text("t_us,x,y,touch\n0,1,2,1\n5000,3\n")
    with pytest.raises(plot_replay.ToolError, match="row 3 is not t_us,x,y,touch"):
        plot_replay.read_trace(str(path))
    path.write_text("t_us,x,y\n0,1,2\n")
    with pytest.raises(plot_replay.ToolError, match="header must name t_us, x, y and touch"):
        plot_replay.read_trace(str(path))


@pytest.mark.parametrize("text, says", [
    ("# input: trace.csv (10 bytes)\n\n", "r.csv: no header row"),
    ("# input: trace.csv (10 bytes)\nt_us,x,y,vx,vy,amplitude,dac,present\n# summary: ticks=0\n", "r.csv: no ticks"),
    ("t_us,x,y,vx,vy,amplitude,dac\n0,1,2,0,0,0.5,0\n", "r.csv: not an ff-replay output \\(no column present\\)"),
    ("t_us,x,y,vx,vy,amplitude,dac,present\n0,1,2,0,0,0.5,0,1\n5000,1,2,0,0,half,0,1\n# summary: ticks=2\n",
     "r.csv:3: amplitude 'half' is not a number"),
], ids=["no-header", "no-ticks", "no-present-column", "not-a-number"])
def test_a_replay_that_is_not_one_is_refused_in_one_line(tmp_path, text, says):
    path = tmp_path / "r.csv"
    path.write_text(text)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # one line for the user, not numpy's warning before it
        with pytest.raises(plot_replay.ToolError, match=says):
            plot_replay.read_replay(str(path))


def test_a_window_between_two_ticks_is_refused(tmp_path):
    with pytest.raises(plot_replay.ToolError, match="no tick between --from and --to"):
        plot_replay.window_of(np.array([0.0, 0.005, 0.01]), 0.006, 0.009)
    assert plot_replay.window_of(np.array([0.0, 0.005, 0.01]), 0.005, 0.01) == (1, 3)  # both ends count


def test_the_plot_is_drawn_headless_whatever_backend_the_user_set():
    # a desktop may set an interactive backend: the plot only ever goes to a file
    code = "import sys; sys.path.insert(0, sys.argv[1]); import plot_replay, matplotlib; print(matplotlib.get_backend())"
    res = subprocess.run([sys.executable, "-c", code, os.path.dirname(plot_replay.__file__)], capture_output=True,
                         text=True, env=dict(os.environ, MPLBACKEND="pdf"))
    assert res.returncode == 0 and res.stdout.strip().lower() == "agg", res.stderr


def refused(capsys, monkeypatch, *argv):
    """Runs main() on argv; returns its one line on stderr, after checking it exited 2."""
    monkeypatch.setattr(sys, "argv", ["plot_replay.py", *map(str, argv)])
    with pytest.raises(SystemExit) as stop:
        plot_replay.main()
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1, err
    return err


def test_an_output_that_is_an_input_is_refused_before_anything_is_written(tmp_path, monkeypatch, capsys,
                                                                          ff_scene_render):
    trace, replay = write_pair(str(tmp_path))
    os.symlink(replay, tmp_path / "replay-link.png")
    os.link(trace, tmp_path / "trace-hardlink.png")
    before = {name: (tmp_path / name).read_bytes() for name in ("trace.csv", "trace.csv.replay.csv")}
    monkeypatch.chdir(tmp_path)
    for output, source in ((replay, replay), (trace, trace), ("./trace.csv", trace),
                           (tmp_path / "replay-link.png", replay), (tmp_path / "trace-hardlink.png", trace)):
        err = refused(capsys, monkeypatch, trace, replay, "-o", output, "--bin", ff_scene_render)
        assert err == f"plot_replay: output {output} is the input {source}: a tool never writes over its own input\n"
    assert {name: (tmp_path / name).read_bytes() for name in before} == before
    assert os.path.islink(tmp_path / "replay-link.png")  # the link itself is left too
    assert sorted(os.listdir(tmp_path)) == ["replay-link.png", "trace-hardlink.png", "trace.csv",
                                            "trace.csv.replay.csv"]


@pytest.mark.parametrize("cut", ["summary", "rows", "row"])
def test_a_replay_without_its_summary_line_is_refused_as_incomplete(tmp_path, monkeypatch, capsys, ff_scene_render,
                                                                     cut):
    # ff-replay writes '# summary:' last: a replay killed midway (X.partial) or a capture cut at a row's end
    # lacks it, and plotting it would draw part of a run as the whole
    trace, replay = write_pair(str(tmp_path))
    text = open(replay).read()
    lines = text.splitlines(keepends=True)
    kept = {"summary": lines[:-1], "rows": lines[:-3], "row": lines[:-2] + [lines[-2][:9]]}[cut]
    with open(replay, "w") as f:
        f.writelines(kept)
    err = refused(capsys, monkeypatch, trace, replay, "-o", tmp_path / "p.png", "--bin", ff_scene_render)
    assert err == f"plot_replay: {replay}: the replay is incomplete: no summary line (ff-replay writes it last)\n"
    assert not os.path.exists(tmp_path / "p.png")
    with open(replay, "w") as f:  # blank lines after the summary are no matter
        f.write(text + "\n\n")
    assert plot_replay.read_replay(replay)[1]["t_us"][-1] == 1_025_000


@pytest.mark.parametrize("value", ["0", "-3", "2.5", "many"])
def test_max_segments_below_one_is_a_usage_error(tmp_path, monkeypatch, capsys, value):
    # 0 segments divided the report count by zero (a traceback)
    trace, replay = write_pair(str(tmp_path))
    monkeypatch.setattr(sys, "argv", ["plot_replay.py", trace, replay, "-o", str(tmp_path / "p.png"),
                                      f"--max-segments={value}"])
    with pytest.raises(SystemExit) as stop:
        plot_replay.main()
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert err.endswith(f"plot_replay.py: error: argument --max-segments: {value} is not a whole number "
                        "from 1 on\n") and "Traceback" not in err
    assert not os.path.exists(tmp_path / "p.png")


def test_reports_of_a_replay_made_with_screen_are_scaled_as_ff_replay_scaled_them(tmp_path, drawn):
    # ff-replay --screen 1600x1440 scales x by 800 / 1600 = 1/2 and y by 480 / 1440 = 1/3: the trace's
    # reports, in that screen's units, land on the replay's path only scaled the same way
    reports = [(t, 2 * x, 3 * y, touch) if touch else (t, x, y, touch) for t, x, y, touch in REPORTS]
    trace, replay = write_pair(str(tmp_path), reports=reports, meta=["screen: 1600x1440 scaled to 800x480"])
    reports_drawn = drawn(trace, replay)[0].axes[0].lines[0]
    assert list(reports_drawn.get_xdata()) == [100, 105, 110, 120, 200, 210]
    assert list(reports_drawn.get_ydata()) == [100, 100, 100, 110, 200, 200]
    trace, replay = write_pair(str(tmp_path), meta=["screen: 800x480"])  # the sensor's own screen: as they are
    assert list(drawn(trace, replay)[0].axes[0].lines[0].get_xdata()) == [100, 105, 110, 120, 200, 210]


def test_a_screen_line_that_is_not_w_x_h_is_refused(tmp_path, monkeypatch, capsys, ff_scene_render):
    trace, replay = write_pair(str(tmp_path), meta=["screen: 0x480"])
    err = refused(capsys, monkeypatch, trace, replay, "-o", tmp_path / "p.png", "--bin", ff_scene_render)
    assert err == f"plot_replay: {replay}:2: screen '0x480' is not WxH with W, H > 0\n"



# The third tick (line 5: the input line, the header, two ticks before it) made out of spec (docs/spec.md#replay-output)
@pytest.mark.parametrize("third, says", [
    ((1_010_000, 120, 110, 7.5, 1), "amplitude 7.5 is outside [0, 1]"),
    ((1_010_000, 120, 110, -3, 1), "amplitude -3 is outside [0, 1]"),
    ((1_010_000, 120, 110, "nan", 1), "amplitude nan is outside [0, 1]"),
    ((1_010_000, 120, 110, 0.8, 3), "present 3 is not 0 or 1"),
    ((1_010_000, 120, 110, 0.8, 0.5), "present 0.5 is not 0 or 1"),
    ((1_010_000, "inf", 110, 0.8, 1), "x inf is not a finite position"),
    ((1_010_000, 120, "nan", 0.8, 1), "y nan is not a finite position"),
    ((1_004_000, 120, 110, 0.8, 1), "t_us 1004000 is not after the previous tick's 1005000"),
    ((1_005_000, 120, 110, 0.8, 1), "t_us 1005000 is not after the previous tick's 1005000"),
    (("inf", 120, 110, 0.8, 1), "t_us inf is not a finite time"),
    ((1_010_000, 120, 110, 0.8, "1,9"), "9 fields, the header names 8"),
    ((1_010_000, 120, 110, 0.8, "1;"), "present '1;' is not a number"),
], ids=["amplitude-7.5", "amplitude-3", "amplitude-nan", "present-3", "present-half", "x-inf", "y-nan",
        "t-backwards", "t-repeated", "t-inf", "row-wider", "not-a-number"])
def test_a_row_out_of_spec_is_refused_with_its_line(tmp_path, third, says):
    ticks = TICKS[:2] + [third] + TICKS[3:]
    trace, replay = write_pair(str(tmp_path), ticks=ticks)
    with pytest.raises(plot_replay.ToolError) as e:
        plot_replay.read_replay(replay)
    assert str(e.value) == f"{replay}:5: {says}"


def test_every_row_wider_than_the_header_is_refused_at_the_first_and_a_narrower_one_too(tmp_path):
    trace, replay = write_pair(str(tmp_path), ticks=[(t, x, y, a, f"{p},0") for t, x, y, a, p in TICKS])
    with pytest.raises(plot_replay.ToolError, match=r"trace.csv.replay.csv:3: 9 fields, the header names 8$"):
        plot_replay.read_replay(replay)
    trace, replay = write_pair(str(tmp_path))
    lines = open(replay).read().splitlines(keepends=True)
    lines[5] = "1010000,120,110\n"  # line 6
    lines.insert(4, "# a comment between rows\n\n")  # counted as the lines they are: now line 8
    with open(replay, "w") as f:
        f.writelines(lines)
    with pytest.raises(plot_replay.ToolError, match=r"trace.csv.replay.csv:8: 3 fields, the header names 8$"):
        plot_replay.read_replay(replay)


def test_a_column_named_twice_is_refused(tmp_path):
    path = tmp_path / "r.csv"
    path.write_text("# input: t.csv (1 bytes)\nt_us,x,y,vx,vy,amplitude,dac,present,x\n0,1,2,0,0,0.5,0,1,3\n"
                    "# summary: ticks=1\n")
    with pytest.raises(plot_replay.ToolError, match=r"r.csv:2: column x is named twice$"):
        plot_replay.read_replay(str(path))


def test_errors_name_their_file_and_line(tmp_path, monkeypatch, capsys, ff_scene_render):
    trace, replay = write_pair(str(tmp_path), meta=["scene: --scene 'heightmap"])
    err = refused(capsys, monkeypatch, trace, replay, "-o", tmp_path / "p.png", "--bin", ff_scene_render)
    assert err == f"plot_replay: {replay}:2: scene words --scene 'heightmap: No closing quotation\n"
    with open(replay, "ab") as f:  # after its summary: read first by the tail check, then by the reader
        f.write(b"\xff\n# summary: ticks=6\n")
    err = refused(capsys, monkeypatch, trace, replay, "-o", tmp_path / "p.png", "--bin", ff_scene_render)
    assert err.startswith(f"plot_replay: {replay}: not UTF-8 text (") and "0xff" in err
    trace, replay = write_pair(str(tmp_path))
    with open(trace, "ab") as f:
        f.write(b"1040000,\xff,1,1\n")
    with pytest.raises(plot_replay.ToolError, match=f"^{trace}: not UTF-8 text \\("):
        plot_replay.read_trace(trace)
