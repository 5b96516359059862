"""make_report.py's CSV: metadata first, then the rows (the files are
written whole by ff_files, tools/common/test_ff_files.py)."""
import make_report


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
