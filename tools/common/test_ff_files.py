"""ff_files: the Python tools' outputs written whole, through NAME.partial,
flushed to disk and renamed only once complete, so a failed or killed run
leaves the old file and no partial one."""
import errno
import os
import threading

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from PIL import Image  # noqa: E402
import pytest  # noqa: E402

import ff_files  # noqa: E402


def test_a_complete_write_replaces_the_file_and_leaves_no_partial(tmp_path):
    path = tmp_path / "summary.md"
    path.write_text("old\n")
    ff_files.write_whole(str(path), lambda f: f.write("new é\r\n"))
    assert path.read_bytes() == "new é\r\n".encode("utf-8")  # UTF-8, line ends as written
    assert os.listdir(tmp_path) == ["summary.md"]


def test_a_missing_folder_is_refused_not_made(tmp_path):
    # docs/tools.md: an output in a missing folder cannot be written (exit 2); a typo must not make folders
    path = tmp_path / "report" / "benchmarks.md"
    with pytest.raises(FileNotFoundError) as e:
        ff_files.write_whole(str(path), lambda f: f.write("new\n"))
    assert ff_files.error_text(e.value) == f"{path}: no such folder: {tmp_path / 'report'}"
    assert os.listdir(tmp_path) == []


def test_a_failed_write_leaves_the_old_file_as_it_was(tmp_path):
    path = tmp_path / "exclusions.proposed.csv"
    path.write_text("old\n")

    def half_then_fail(f):
        f.write("half")
        raise OSError("disk full")

    with pytest.raises(OSError):
        ff_files.write_whole(str(path), half_then_fail)
    assert path.read_text() == "old\n"
    assert os.listdir(tmp_path) == ["exclusions.proposed.csv"]


def test_a_failed_write_names_the_file_it_was_writing(tmp_path):
    path = tmp_path / "summary.md"

    def fill_the_disk(f):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))  # as a write() raises it: no file name

    with pytest.raises(OSError) as e:
        ff_files.write_whole(str(path), fill_the_disk)
    assert ff_files.error_text(e.value) == f"{path}.partial: No space left on device"
    assert ff_files.error_text(OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))) == "No space left on device"
    assert ff_files.error_text(OSError("no errno")) == "no errno"
    assert ff_files.error_text(ValueError("not a number")) == "not a number"
    with pytest.raises(OSError) as e:  # a device is written straight into, and named too
        ff_files.write_whole("/dev/full", lambda f: f.write("x" * 100000))
    assert ff_files.error_text(e.value) == "/dev/full: No space left on device"
    with pytest.raises(OSError) as e:  # one that names its file keeps it
        ff_files.write_whole(str(path), lambda f: open(tmp_path / "nowhere" / "x"))
    assert ff_files.error_text(e.value) == f"{tmp_path / 'nowhere' / 'x'}: No such file or directory"


def test_the_data_reaches_the_disk_before_the_rename(tmp_path, monkeypatch):
    calls = []
    real_fsync, real_replace = os.fsync, os.replace

    def fsync(fd):
        calls.append("fsync")
        real_fsync(fd)

    def replace(source, target):
        calls.append("replace")
        real_replace(source, target)

    monkeypatch.setattr(os, "fsync", fsync)
    monkeypatch.setattr(os, "replace", replace)
    ff_files.write_whole(str(tmp_path / "session.json"), lambda f: f.write("{}"))
    assert calls == ["fsync", "replace"]


def test_what_python_buffered_is_in_the_file_when_it_is_synced(tmp_path, monkeypatch):
    # fsync only syncs what the OS holds: Python's own buffer must be flushed first.
    sizes = []
    real_fsync = os.fsync

    def fsync(fd):
        sizes.append(os.fstat(fd).st_size)
        real_fsync(fd)

    monkeypatch.setattr(os, "fsync", fsync)
    ff_files.write_whole(str(tmp_path / "log.csv"), lambda f: f.write("t_us,x\n0,1\n"))
    assert sizes == [len("t_us,x\n0,1\n")]


def test_a_bare_file_name_is_written_in_the_current_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    ff_files.write_whole("summary.md", lambda f: f.write("new\n"))
    assert (tmp_path / "summary.md").read_text() == "new\n"
    assert os.listdir(tmp_path) == ["summary.md"]


def test_a_fifo_is_written_into_not_replaced(tmp_path):
    fifo = str(tmp_path / "pipe")
    os.mkfifo(fifo)
    received = []
    reader = threading.Thread(target=lambda: received.append(open(fifo).read()))
    reader.start()
    ff_files.write_whole(fifo, lambda f: f.write("through the pipe\n"))
    reader.join(timeout=10)
    assert received == ["through the pipe\n"]
    assert os.path.exists(fifo) and not os.path.isfile(fifo)
    assert os.listdir(tmp_path) == ["pipe"]


def _figure():
    fig, ax = plt.subplots(figsize=(2, 2))
    ax.plot([0, 1], [0, 1])
    return fig


def test_a_figure_is_a_png_written_whole_saying_what_made_it(tmp_path):
    fig = _figure()
    path = tmp_path / "fig.png"
    ff_files.save_figure(fig, str(path), "plot_replay.py", "trace: a.csv; scene: heightmap", dpi=50)
    plt.close(fig)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with Image.open(path) as image:
        assert image.text["Software"] == "plot_replay.py"
        assert image.text["Description"] == "trace: a.csv; scene: heightmap"
    assert os.listdir(tmp_path) == ["fig.png"]


def test_a_figure_takes_the_format_its_name_ends_with(tmp_path):
    fig = _figure()
    ff_files.save_figure(fig, str(tmp_path / "fig.svg"), "render_scene.py", "scene: vortex")
    ff_files.save_figure(fig, str(tmp_path / "fig.pdf"), "render_scene.py", "scene: vortex")
    ff_files.save_figure(fig, str(tmp_path / "fig.out"))  # no known ending: PNG
    plt.close(fig)
    svg = (tmp_path / "fig.svg").read_text()
    assert svg.lstrip().startswith("<?xml") and "render_scene.py" in svg and "scene: vortex" in svg
    assert (tmp_path / "fig.pdf").read_bytes()[:5] == b"%PDF-"
    assert (tmp_path / "fig.out").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_an_output_that_is_an_input_under_any_name_is_refused(tmp_path, monkeypatch):
    source = tmp_path / "trace.csv"
    source.write_text("t_us,x,y,touch\n")
    os.symlink(source, tmp_path / "soft.png")
    os.link(source, tmp_path / "hard.png")
    monkeypatch.chdir(tmp_path)
    for output in (str(source), "trace.csv", "./sub/../trace.csv", "soft.png", "hard.png"):
        with pytest.raises(ff_files.OutputIsInput) as e:
            ff_files.refuse_overwriting_inputs([str(tmp_path / "fine.png"), output], [None, str(source)])
        assert str(e.value) == f"output {output} is the input {source}: a tool never writes over its own input"
    # another file, one not yet written, standard output, a device: no input of this tool
    (tmp_path / "other.csv").write_text("t_us,x,y,touch\n")
    ff_files.refuse_overwriting_inputs(["other.csv", "new.png", "-", "/dev/null"], [str(source)])
