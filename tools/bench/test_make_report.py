"""make_report.py's outputs are written whole: through NAME.partial, renamed
only once complete, so a failed or killed run leaves the old file."""
import pytest

import make_report


def test_a_complete_write_replaces_the_file_and_leaves_no_partial(tmp_path):
    path = tmp_path / "sub" / "benchmarks.md"
    make_report.write_whole(str(path), lambda partial: open(partial, "w").write("new\n"))
    assert path.read_text() == "new\n"
    assert sorted(p.name for p in path.parent.iterdir()) == ["benchmarks.md"]


def test_a_failed_write_leaves_the_old_file_as_it_was(tmp_path):
    path = tmp_path / "benchmarks.md"
    path.write_text("old\n")

    def half_then_fail(partial):
        with open(partial, "w") as f:
            f.write("half")
        raise OSError("disk full")

    with pytest.raises(OSError):
        make_report.write_whole(str(path), half_then_fail)
    assert path.read_text() == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["benchmarks.md"]


def test_the_csv_starts_with_its_metadata_and_reads_back_without_it(tmp_path):
    path = tmp_path / "benchmarks.csv"
    row = {k: "" for k in ("id", "scene", "strategy", "default", "fits_teensy", "table_bytes", "plan_bytes",
                           "max_lsb", "p99_lsb", "rms_lsb", "max_interior_lsb", "worst_x", "worst_y",
                           "worst_direction_deg", "where", "max_g_core", "max_g_ref", "gradient_evaluations",
                           "host_eval_ns", "host_prepare_us", "host_tick_ns")}
    row.update(id="neutral/closed-form", scene="neutral", m4_eval=None, m4_tick=33.5, m4_tick_estimated=False,
               m4_tick_max=None, m4_prepare=None, checksum_match=True)
    make_report.write_csv([row], str(path), [("tool", "make_report.py"), ("what", "a test")])
    lines = path.read_text().splitlines()
    assert lines[:2] == ["# tool: make_report.py", "# what: a test"]
    rows = make_report.read_plain_csv(str(path))
    assert len(rows) == 1
    assert rows[0]["id"] == "neutral/closed-form"
    assert rows[0]["m4_tick_instr"] == "33.5" and rows[0]["m4_eval_instr"] == ""
    assert rows[0]["checksum_match"] == "1"
