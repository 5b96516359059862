"""ffexp.files: outputs written whole, through NAME.partial, renamed only once
complete, so a failed or killed run leaves the old file and no partial one."""
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from ffexp import files  # noqa: E402


def test_a_complete_write_replaces_the_file_and_leaves_no_partial(tmp_path):
    path = tmp_path / "summary.md"
    path.write_text("old\n")
    files.write_whole(str(path), lambda f: f.write("new\n"))
    assert path.read_text() == "new\n"
    assert os.listdir(tmp_path) == ["summary.md"]


def test_a_failed_write_leaves_the_old_file_as_it_was(tmp_path):
    path = tmp_path / "exclusions.proposed.csv"
    path.write_text("old\n")

    def half_then_fail(f):
        f.write("half")
        raise OSError("disk full")

    with pytest.raises(OSError):
        files.write_whole(str(path), half_then_fail)
    assert path.read_text() == "old\n"
    assert os.listdir(tmp_path) == ["exclusions.proposed.csv"]


def test_a_figure_is_a_png_written_whole(tmp_path):
    fig, ax = plt.subplots(figsize=(2, 2))
    ax.plot([0, 1], [0, 1])
    path = tmp_path / "fig.png"
    files.save_figure(fig, str(path), dpi=50)
    plt.close(fig)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert os.listdir(tmp_path) == ["fig.png"]
