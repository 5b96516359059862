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
