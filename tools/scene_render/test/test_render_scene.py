"""render_scene.py as a user runs it."""
import io
import os
import subprocess

import numpy as np
import pytest
from PIL import Image

SCRIPT = "tools/scene_render/render_scene.py"
SCENES = ["heightmap", "frictionmap", "neutral", "tunnel-converging", "tunnel-diverging", "tunnel-neutral",
          "pilot-c", "familiarisation-path", "bump-map", "vortex"]


def amplitude_spread(binary, scene, direction):
    out = subprocess.run([binary, "--scene", scene, "--step", "16", "--direction", str(direction)],
                         capture_output=True, text=True, check=True).stdout
    rows = "\n".join(l for l in out.splitlines() if not l.startswith("#"))
    return float(np.std(np.loadtxt(io.StringIO(rows), delimiter=",", skiprows=1)[:, 4]))


@pytest.mark.parametrize("scene", SCENES)
def test_every_scene_draws(tmp_path, run_tool, ff_scene_render, scene):
    png = tmp_path / "s.png"
    res = run_tool(SCRIPT, "--scene", scene, "--step", "8", "-o", png, "--bin", ff_scene_render)
    assert res.returncode == 0, res.stderr
    assert png.stat().st_size > 10000
    with Image.open(png) as image:  # the PNG says what made it and which scene
        assert image.text["Software"] == "render_scene.py"
        assert f"scene: --scene {scene} " in image.text["Description"]
    assert os.listdir(tmp_path) == ["s.png"]


def test_a_tunnel_is_drawn_moving_across_it(tmp_path, run_tool, ff_scene_render):
    # Moving along a tunnel (0 degrees) its amplitude is nearly flat: little to see.
    along = amplitude_spread(ff_scene_render, "tunnel-converging", 0)
    res = run_tool(SCRIPT, "--scene", "tunnel-converging", "-o", tmp_path / "t.png", "--bin", ff_scene_render)
    assert res.returncode == 0, res.stderr
    chosen = float(res.stdout.rsplit("moving ", 1)[1].rstrip("°\n"))
    assert chosen % 180 != 0
    assert amplitude_spread(ff_scene_render, "tunnel-converging", chosen) > 3 * along


def test_titles_carry_only_words_that_apply(tmp_path, run_tool, ff_scene_render):
    res = run_tool(SCRIPT, "--scene", "vortex", "--target", "top", "-o", tmp_path / "v.png", "--bin", ff_scene_render)
    assert res.returncode == 0, res.stderr
    assert "target" not in res.stdout
    res = run_tool(SCRIPT, "--scene", "heightmap", "--target", "top", "-o", tmp_path / "h.png",
                   "--bin", ff_scene_render)
    assert "heightmap, target top, strength 1" in res.stdout
    scene = tmp_path / "mine.txt"
    scene.write_text("rendering constant\nconstant 0.3\n")
    res = run_tool(SCRIPT, "--scene-file", scene, "-o", tmp_path / "f.png", "--bin", ff_scene_render)
    assert res.returncode == 0, res.stderr
    assert "scene file mine.txt" in res.stdout


def test_a_scene_file_named_with_an_apostrophe_and_a_space_draws(tmp_path, run_tool, ff_scene_render):
    scene = tmp_path / "my scene's.txt"
    scene.write_text("rendering constant\nconstant 0.3\n")
    res = run_tool(SCRIPT, "--scene-file", scene, "-o", tmp_path / "f.png", "--bin", ff_scene_render)
    assert res.returncode == 0, res.stderr
    assert "scene file my scene's.txt" in res.stdout


def test_a_missing_build_is_one_clear_line(tmp_path, run_tool):
    res = run_tool(SCRIPT, "--scene", "heightmap", "-o", tmp_path / "x.png", "--bin", tmp_path / "nothing")
    assert res.returncode == 2
    assert "ff-scene-render not found" in res.stderr and "cmake" in res.stderr
    assert "Traceback" not in res.stderr and len(res.stderr.strip().splitlines()) == 1


def test_bad_scene_words_are_one_line_exit_2(tmp_path, run_tool, ff_scene_render):
    for words in (["--scene", "nope"], ["--strength", "3"], ["--scene-file", str(tmp_path)]):
        res = run_tool(SCRIPT, *words, "-o", tmp_path / "x.png", "--bin", ff_scene_render)
        assert res.returncode == 2, words
        assert "Traceback" not in res.stderr and len(res.stderr.strip().splitlines()) == 1, res.stderr


def test_an_output_that_is_the_scene_file_under_any_name_is_refused(tmp_path, run_tool, ff_scene_render):
    # docs/tools.md: a tool never writes over its own input, whatever its name
    scene = tmp_path / "mine.txt"
    scene.write_text("rendering constant\nconstant 0.3\n")
    os.symlink("mine.txt", tmp_path / "soft.png")
    os.link(scene, tmp_path / "hard.png")
    os.symlink(".", tmp_path / "linked")
    for words, output in ((["--scene-file", scene], scene), (["--scene-file", scene], "./mine.txt"),
                          ([f"--scene-file={scene}"], scene), (["--scene-file", scene], "soft.png"),
                          (["--scene-file", scene], "hard.png"), (["--scene-file", scene], "linked/mine.txt")):
        res = run_tool(SCRIPT, *words, "-o", output, "--bin", ff_scene_render, cwd=tmp_path)
        assert (res.returncode, res.stdout) == (2, ""), output
        assert res.stderr == (f"render_scene: output {output} is the input {scene}: "
                              "a tool never writes over its own input\n")
    assert scene.read_text() == "rendering constant\nconstant 0.3\n"
    assert os.path.islink(tmp_path / "soft.png")
    assert sorted(os.listdir(tmp_path)) == ["hard.png", "linked", "mine.txt", "soft.png"]
