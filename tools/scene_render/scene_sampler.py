"""Scenes for the Python tools, sampled by ff-scene-render: the one place a
scene's formulas live is the C++ core, so no tool here repeats them.

Shared by render_scene.py and tools/plot/plot_replay.py.
"""
import io
import os
import shlex
import subprocess

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_BIN = os.path.normpath(os.path.join(HERE, "..", "..", "build", "native", "tools", "scene_render",
                                            "ff-scene-render"))


class ToolError(Exception):
    """Bad input or a missing build: the tools print it as one line and exit 2."""


def find_binary(path=None):
    path = path or os.environ.get("FF_SCENE_RENDER") or DEFAULT_BIN
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        raise ToolError(f"ff-scene-render not found at {path}: build it (cmake --preset native && "
                        "cmake --build --preset native --target ff-scene-render) or pass --bin PATH")
    return path


def parse_metadata(lines):
    """'# key: value' lines into a dict (other lines ignored)."""
    meta = {}
    for line in lines:
        if line.startswith("#"):
            key, sep, value = line[1:].strip().partition(": ")
            if sep:
                meta[key] = value
    return meta


def sample(binary, words, step=4.0, direction=0.0):
    """(metadata, rows of x,y,gx,gy,amplitude) for the scene the words select."""
    cmd = [binary, "--step", str(step), "--direction", str(direction)] + list(words)
    out = subprocess.run(cmd, check=False, capture_output=True, text=True)
    if out.returncode != 0:
        raise ToolError(out.stderr.strip().splitlines()[0] if out.stderr.strip() else f"{binary} failed")
    lines = out.stdout.splitlines()
    meta = parse_metadata(lines)
    body = "\n".join(l for l in lines if not l.startswith("#"))
    data = np.loadtxt(io.StringIO(body), delimiter=",", skiprows=1, ndmin=2)
    return meta, data


def grid(data, column):
    """xs, ys and the column as a 2-D array (rows = y)."""
    xs, ys = np.unique(data[:, 0]), np.unique(data[:, 1])
    return xs, ys, data[:, column].reshape(len(ys), len(xs))


def describe(scene_words):
    """A title from the scene words ff-scene-render reports (only those that apply):
    '--scene heightmap --target top --strength 0.66' -> 'heightmap, target top, strength 0.66'."""
    words = shlex.split(scene_words)
    parts, i = [], 0
    while i < len(words):
        key = words[i].lstrip("-")
        value = words[i + 1] if i + 1 < len(words) and not words[i + 1].startswith("--") else None
        if key == "scene":
            parts.append(value)
        elif key == "scene-file":
            parts[-1:] = [f"scene file {os.path.basename(value)}"]
        elif value is None:
            parts.append(key.replace("-", " "))
        else:
            parts.append(f"{key.replace('-', ' ')} {value}")
        i += 1 if value is None else 2
    return ", ".join(parts)
