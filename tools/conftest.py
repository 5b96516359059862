"""Fixtures for the Python tools' tests: the native build's binaries (run
scripts/run-tests, or cmake --build --preset native, first)."""
import os
import subprocess
import sys

import pytest

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
BUILD = os.environ.get("FF_BUILD_DIR", os.path.join(ROOT, "build", "native"))


def _binary(*parts):
    path = os.path.join(BUILD, *parts)
    if not os.access(path, os.X_OK):
        pytest.fail(f"{path} is missing: build the native preset first (or set FF_BUILD_DIR)")
    return path


@pytest.fixture(scope="session")
def ff_replay():
    return _binary("tools", "replay", "ff-replay")


@pytest.fixture(scope="session")
def ff_scene_render():
    return _binary("tools", "scene_render", "ff-scene-render")


@pytest.fixture(scope="session")
def run_tool():
    """Runs a Python tool of this repository as a user would: a subprocess."""
    def run(script, *args, **kwargs):
        return subprocess.run([sys.executable, os.path.join(ROOT, script), *map(str, args)],
                              capture_output=True, text=True, **kwargs)
    return run


@pytest.fixture(scope="session")
def write_trace():
    """Writes t_us,x,y,touch rows to a CSV file."""
    def write(path, rows):
        with open(path, "w") as f:
            f.write("t_us,x,y,touch\n")
            f.writelines(f"{t},{x},{y},{touch}\n" for t, x, y, touch in rows)
        return path
    return write
