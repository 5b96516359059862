"""What the track bench scripts' tests share: a hand-made CSV, a run as a user runs a script, the PNG check and
the refusal of bad input (one line on stderr, exit 2, no figure)."""
import os
import subprocess
import sys


def write_csv(path, header, rows, metadata):
    with open(path, "w") as f:
        for m in metadata:
            f.write("# %s\n" % m)
        f.write(header + "\n")
        for r in rows:
            f.write(r + "\n")


def run_script(name, *args, cwd=None):
    """Runs a script of this folder as a user does: its own process, no PYTHONPATH (it finds its modules)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    tool = os.path.join(os.path.dirname(os.path.abspath(__file__)), name)
    return subprocess.run([sys.executable, tool, *map(str, args)], capture_output=True, text=True, env=env, cwd=cwd)


def assert_png_with_metadata(path, tool):
    with open(path, "rb") as f:
        png = f.read()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert tool.encode() in png  # the CSV's metadata travels into the PNG


def assert_refused(main, csv_path, out_path, capsys, message):
    assert main([str(csv_path), "-o", str(out_path)]) == 2
    err = capsys.readouterr().err
    assert message in err
    assert err.count("\n") == 1
    assert not os.path.exists(out_path)


def assert_never_writes_over_its_csv(main, tool, csv_path, capsys, monkeypatch):
    """An output that is the CSV under any name (docs/tools.md: another relative path, a symbolic or a hard link,
    a linked folder) is refused with ff_files' one line and exit 2, before anything is written."""
    folder, name = os.path.split(str(csv_path))
    os.symlink(name, os.path.join(folder, "soft.png"))
    os.link(csv_path, os.path.join(folder, "hard.png"))
    os.symlink(".", os.path.join(folder, "linked"))
    with open(csv_path, "rb") as f:
        before = f.read()
    monkeypatch.chdir(folder)
    for output in (str(csv_path), "./" + name, "soft.png", "hard.png", os.path.join("linked", name)):
        assert main([str(csv_path), "-o", output]) == 2, output
        assert capsys.readouterr().err == ("%s: output %s is the input %s: a tool never writes over its own input\n"
                                           % (tool, output, csv_path))
    with open(csv_path, "rb") as f:
        assert f.read() == before
    assert os.path.islink("soft.png") and sorted(os.listdir(folder)) == sorted([name, "hard.png", "linked", "soft.png"])
