"""render_scene.py's figure, read back in the process: which panels, titles,
arrow, colour scales and axes each kind of scene gets (the samples come from
ff-scene-render, tested against the field's closed forms in the C++ tests)."""
import argparse
import os
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import render_scene  # noqa: E402


@pytest.fixture
def draw(tmp_path, monkeypatch, ff_scene_render):
    saved = []
    monkeypatch.setattr(render_scene.ff_files, "save_figure",
                        lambda fig, output, software, description, **kw: saved.append((fig, output, software, kw)))

    def run(words, direction=None, title=None):
        args = argparse.Namespace(bin=ff_scene_render, direction=direction, step=16.0, title=title,
                                  output=str(tmp_path / "s.png"))
        chosen, said = render_scene.render(args, words)
        fig, output, software, options = saved.pop()
        assert (output, software, options) == (str(tmp_path / "s.png"), "render_scene.py", {"dpi": 90})
        return chosen, said, fig
    return run


def panels(fig):
    """The scene's panels, without their colour bars."""
    return [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]


def test_a_directional_scene_has_the_amplitude_with_its_arrow_and_the_field(draw):
    direction, title, fig = draw(["--scene", "heightmap", "--target", "top"], direction=90)
    amplitude, field = panels(fig)
    assert direction == 90 and amplitude.get_title() == "amplitude moving 90°"
    (arrow,) = amplitude.texts  # from (60, 40), 40 px along the direction of motion: down
    assert arrow.xyann == (60, 40) and arrow.xy == pytest.approx((60, 80))
    assert field.get_title() == "|G_norm| and downhill arrows"
    (quiver,) = field.collections
    assert quiver.scale == pytest.approx(0.5 / (0.9 * 32))
    assert [im.get_clim() for im in (amplitude.images[0], field.images[0])] == [(0, 1), (0, 0.5)]
    bars = [ax for ax in fig.axes if ax.get_label() == "<colorbar>"]
    assert [bar.get_ylabel() for bar in bars] == ["A (1 = slippery)", "|G| / (2 max|G|)"]
    for ax in (amplitude, field):
        assert ax.get_xlim() == (0, 800) and ax.get_ylim() == (480, 0) and ax.get_aspect() == 1.0
        assert (ax.get_xlabel(), ax.get_ylabel()) == ("x [px]", "y [px]")
    assert fig._suptitle.get_text() == title == "heightmap, target top, strength 1"
    assert amplitude.get_position().x0 < 0.1  # laid out tight: matplotlib's default margin is 0.125
    assert not render_scene.plt.fignum_exists(fig.number)  # closed once written (read back all the same)


def test_a_position_scene_has_one_panel_and_a_constant_one_says_its_value(draw, tmp_path):
    _, _, fig = draw(["--scene", "frictionmap"])
    (only,) = panels(fig)
    assert only.get_title() == "amplitude (position only)" and not only.texts
    scene = tmp_path / "still.txt"
    scene.write_text("rendering constant\nconstant 0.3\n")
    direction, _, fig = draw(["--scene-file", str(scene)], title="my own title")
    (only,) = panels(fig)
    assert direction == 0.0 and only.get_title() == "constant amplitude 0.300"
    assert fig._suptitle.get_text() == "my own title"
