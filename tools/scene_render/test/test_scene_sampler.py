"""scene_sampler.py's helpers on their own: where ff-scene-render is looked
for, and the titles made from the scene words it reports."""
import os
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import scene_sampler  # noqa: E402

REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", ".."))


def test_the_binary_is_the_named_one_then_the_environments_then_the_native_builds(tmp_path, monkeypatch):
    named, from_env = tmp_path / "named", tmp_path / "env"
    for path in (named, from_env):
        path.write_text("#!/bin/sh\n")
        path.chmod(0o755)
    monkeypatch.setenv("FF_SCENE_RENDER", str(from_env))
    assert scene_sampler.find_binary(str(named)) == str(named)
    assert scene_sampler.find_binary() == str(from_env)
    monkeypatch.delenv("FF_SCENE_RENDER")
    native = os.path.join(REPO, "build", "native", "tools", "scene_render", "ff-scene-render")
    assert scene_sampler.DEFAULT_BIN == native
    if os.path.isfile(native):
        assert scene_sampler.find_binary() == native
    else:
        with pytest.raises(scene_sampler.ToolError, match="not found at " + native):
            scene_sampler.find_binary()
    (tmp_path / "plain").write_text("not executable")
    with pytest.raises(scene_sampler.ToolError, match="or pass --bin PATH"):
        scene_sampler.find_binary(str(tmp_path / "plain"))


@pytest.mark.parametrize("words, title", [
    ("--scene heightmap --target top --strength 0.66", "heightmap, target top, strength 0.66"),
    ("--scene heightmap --invert --strength 1", "heightmap, invert, strength 1"),  # a flag without a value
    ("--scene vortex --mirror", "vortex, mirror"),
    ("--scene-file '/some where/mine.txt' --strength 1", "scene file mine.txt, strength 1"),
    ("", ""),
])
def test_describe_makes_a_title_of_the_words_that_apply(words, title):
    assert scene_sampler.describe(words) == title
