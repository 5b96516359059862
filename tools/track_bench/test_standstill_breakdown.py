"""standstill_breakdown.py on a hand-made tick file whose shares are worked
out by hand, and its exit codes on bad input."""
import math

import pytest

import standstill_breakdown
from plot_test_support import run_script

HEADER = "t_us,x_true,y_true,vx_true,vy_true,touching,resting,present,x,y,vx,vy,dx,dy,hm,hm_ideal,fm,fm_ideal,hm_true_dir,hm_unit_dir\n"


def tick(t_us, vx_true, touching, vx, dx, dy, error, full_length_error):
    # hm_ideal 0.5; hm and hm_unit_dir off it by the given errors
    return (f"{t_us},0,0,{vx_true},0,{touching},0,1,0,0,{vx},0,{dx},{dy},"
            f"{0.5 + error},0.5,0.5,0.5,0.5,{0.5 + full_length_error}\n")


def write_ticks(path, metadata=""):
    # A tick every 0.5 ms: still at 0, moving at 0.5-2 ms, lifted at 2.5, moving again at 3.
    rows = [tick(0, 0, 1, 0, 0, 0, 0.0, 0.0),
            tick(500, 100, 1, 50, 0.6, 0.8, 0.1, 0.2),   # 0.5 ms after the standstill
            tick(1000, 100, 1, 100, 0.3, 0.4, 0.2, 0.0),  # 1.0
            tick(1500, 100, 1, 100, 0.0, 0.5, 0.0, 0.0),  # 1.5
            tick(2000, 100, 1, 100, 1.0, 0.0, 0.3, 0.0),  # 2.0
            tick(2500, 0, 0, 0, 0, 0, 0.0, 0.0),          # lifted: a standstill
            tick(3000, 100, 1, 100, 0.0, 0.0, 0.1, 0.0)]  # 0.5
    path.write_text(metadata + HEADER + "".join(rows))


def test_shares_by_hand(tmp_path):
    path = tmp_path / "ticks.csv"
    write_ticks(path)
    rows, totals = standstill_breakdown.breakdown([standstill_breakdown.read_ticks(path)], 20.0, [1.0, 2.0])
    # squared errors 0.01 0.04 0 0.09 0.01 (total 0.15); at full length 0.04 at 0.5 ms only
    first, second, last = rows
    assert first[:2] == (0.0, 1.0) and second[:2] == (1.0, 2.0) and math.isinf(last[1])
    assert [r[2] for r in rows] == pytest.approx([2 / 5, 2 / 5, 1 / 5])
    assert [r[3] for r in rows] == pytest.approx([0.02 / 0.15, 0.04 / 0.15, 0.09 / 0.15])
    assert [r[4] for r in rows] == pytest.approx([0.04 / 0.15, 0.0, 0.0])
    assert [r[5] for r in rows] == pytest.approx([0.5, 0.5, 1.0])  # direction lengths 1 and 0, 0.5 and 0.5, 1
    assert [r[6] for r in rows] == pytest.approx([0.75, 1.0, 1.0])  # tracked / true speed 0.5 and 1
    assert totals["ticks"] == 5
    assert totals["rms"] == pytest.approx(math.sqrt(0.15 / 5))
    assert totals["full_length_rms"] == pytest.approx(math.sqrt(0.04 / 5))


def test_metadata_lines_before_the_header_are_skipped(tmp_path):
    # as ff-track-bench --dump-ticks writes them
    plain, dumped = tmp_path / "plain.csv", tmp_path / "dumped.csv"
    write_ticks(plain)
    write_ticks(dumped, "# tool: ff-track-bench --dump-ticks 0.1.0\n# trace: white-200hz along-top\n")
    a, b = standstill_breakdown.read_ticks(plain), standstill_breakdown.read_ticks(dumped)
    assert a.keys() == b.keys()
    for column in a:
        assert list(a[column]) == list(b[column]), column


def test_no_moving_ticks_is_an_error(tmp_path):
    path = tmp_path / "ticks.csv"
    write_ticks(path)
    # At 150 px/s or more nothing moves.
    with pytest.raises(standstill_breakdown.InputError):
        standstill_breakdown.breakdown([standstill_breakdown.read_ticks(path)], 150.0, [1.0])


def test_cli_prints_the_table(tmp_path, capsys):
    path = tmp_path / "ticks.csv"
    write_ticks(path)
    assert standstill_breakdown.main([str(path), "--bins", "1,2"]) == 0
    # 1-2 ms: the ticks 1.0 and 1.5 ms into the first stroke, 0.04 of the 0.15 squared, directions 0.5 long,
    # read at the true speed
    assert capsys.readouterr().out.splitlines() == [
        "| since the standstill | ticks | squared error | at full length | direction | speed ratio |",
        "|---|--:|--:|--:|--:|--:|",
        "| 0-1 ms | 40.0 % | 13.3 % | 26.7 % | 0.50 | 0.75 |",
        "| 1-2 ms | 40.0 % | 26.7 % | 0.0 % | 0.50 | 1.00 |",
        "| 2 ms and later | 20.0 % | 60.0 % | 0.0 % | 1.00 | 1.00 |",
        "",
        "5 moving ticks; heightmap error RMS 0.1732, 0.0894 with the tracked direction at full length"]


def test_a_file_of_one_tick_moving_since_it_began_is_in_the_last_bin(tmp_path, capsys):
    path = tmp_path / "ticks.csv"
    path.write_text(HEADER + tick(0, 100, 1, 100, 1.0, 0.0, 0.1, 0.0))  # no standstill before it
    assert standstill_breakdown.main([str(path), "--bins", "40"]) == 0
    assert capsys.readouterr().out.splitlines()[2:] == [
        "| 0-40 ms | 0.0 % | 0.0 % | 0.0 % | nan | nan |",
        "| 40 ms and later | 100.0 % | 100.0 % | 0.0 % | 1.00 | 1.00 |",
        "",
        "1 moving ticks; heightmap error RMS 0.1000, 0.0000 with the tracked direction at full length"]


@pytest.mark.parametrize("content,args,says", [
    ("t_us,x\n1,2\n", [], "not a --dump-ticks file (missing vx_true, vy_true, touching,"),
    (None, [], "No such file"),
    (HEADER, [], "no ticks"),
    ("ok", ["--bins", "80,40"], "--bins 80,40: positive and increasing edges wanted"),
    ("ok", ["--bins", "x"], "could not convert string to float"),
    ("ok", ["--moving-speed", "0"], "--moving-speed must be above 0"),
], ids=["not-a-tick-file", "missing", "no-ticks", "decreasing-bins", "bins-not-numbers", "no-moving-speed"])
def test_bad_input_exits_2_with_one_line(tmp_path, capsys, content, args, says):
    path = tmp_path / "ticks.csv"
    if content == "ok":
        write_ticks(path)
    elif content is not None:
        path.write_text(content)
    assert standstill_breakdown.main([str(path)] + args) == 2
    err = capsys.readouterr().err
    assert err.startswith("standstill_breakdown: ") and err.count("\n") == 1 and says in err


def test_run_as_a_script_it_exits_with_mains_code(tmp_path):
    path = tmp_path / "ticks.csv"
    write_ticks(path)
    r = run_script("standstill_breakdown.py", path, "--moving-speed", "150")
    assert r.returncode == 2 and r.stderr.startswith("standstill_breakdown: ") and r.stdout == ""
    r = run_script("standstill_breakdown.py", path)
    assert r.returncode == 0 and r.stdout.startswith("| since the standstill |")
