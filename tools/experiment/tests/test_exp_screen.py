"""What the participant sees, read back pixel by pixel from the surfaces."""
import math
import os
import subprocess

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
import pygame  # noqa: E402
import pytest  # noqa: E402

from ffexp import geometry, screen  # noqa: E402

BAR_X, BAR_Y = int(geometry.END_ZONE_X) - 170, 12  # the force bar: 150 x 16 px, 1 px frame


@pytest.fixture
def scr():
    pygame.font.init()
    return screen.Screen(pygame.Surface((geometry.WIDTH, geometry.HEIGHT)))


def rgb(s, x, y):
    return tuple(s.get_at((int(x), int(y))))[:3]


def test_the_background_has_the_end_zone_the_start_circle_and_three_paths(scr):
    bg = scr.background
    assert rgb(bg, geometry.END_ZONE_X + 5, 400) == screen.LIGHT_GREY
    assert rgb(bg, geometry.END_ZONE_X - 5, 400) == screen.BLACK
    assert rgb(bg, *geometry.START_CENTRE) == screen.LIGHT_GREY
    assert rgb(bg, geometry.START_CENTRE[0] + geometry.START_RADIUS + 3, geometry.START_CENTRE[1]) == screen.BLACK
    for target in geometry.RISE:
        assert rgb(bg, 400, float(geometry.path_y(400.0, target))) == screen.WHITE
    assert rgb(bg, 400, 60) == screen.BLACK


@pytest.mark.parametrize("force, filled, colour", [(0.3, 44, screen.GREEN), (0.7, 103, screen.RED),
                                                   (2.0, 148, screen.RED), (-1.0, 0, None)])
def test_the_force_bar_fills_in_proportion_and_turns_red_above_half_a_newton(scr, force, filled, colour):
    scr.surface.fill(screen.BLACK)
    scr.force_indicator(force)
    inside = [rgb(scr.surface, BAR_X + 1 + i, BAR_Y + 8) for i in range(148)]
    limit = BAR_X + 75 - (BAR_X + 1)  # the white mark at 0.5 N
    assert inside == [screen.WHITE if i == limit else colour if i < filled else screen.BLACK for i in range(148)]
    assert rgb(scr.surface, BAR_X + 75, BAR_Y - 3) == screen.WHITE  # the limit mark sticks out above
    assert rgb(scr.surface, BAR_X, BAR_Y + 8) == screen.LIGHT_GREY  # the frame


def test_no_force_is_an_empty_bar(scr):
    scr.surface.fill(screen.BLACK)
    scr.force_indicator(math.nan)
    assert rgb(scr.surface, BAR_X + 10, BAR_Y + 8) == screen.BLACK
    assert rgb(scr.surface, BAR_X, BAR_Y + 8) == screen.LIGHT_GREY


def test_the_amplitude_bar_shows_the_simulators_amplitude_and_nothing_without_one(scr):
    y = geometry.HEIGHT - 26 + 6
    scr.surface.fill(screen.BLACK)
    scr.amplitude_bar(math.nan)
    assert rgb(scr.surface, BAR_X, y) == screen.BLACK  # not even the frame
    scr.amplitude_bar(0.5)
    assert rgb(scr.surface, BAR_X + 1 + 73, y) == (80, 140, 255) and rgb(scr.surface, BAR_X + 1 + 74, y) == screen.BLACK
    assert rgb(scr.surface, BAR_X, y) == (90, 90, 90)


def test_the_trial_screen_draws_the_amplitude_bar_only_when_given(scr):
    y = geometry.HEIGHT - 26 + 6
    scr.surface.fill(screen.WHITE)  # the last screen: all of it drawn over
    scr.trial(3, 180, 2, 0.3)
    assert rgb(scr.surface, BAR_X + 10, y) == screen.BLACK and rgb(scr.surface, 400, 60) == screen.BLACK
    assert rgb(scr.surface, BAR_X + 10, BAR_Y + 8) == screen.GREEN
    scr.trial(3, 180, 2, 0.3, amplitude=1.0)
    assert rgb(scr.surface, BAR_X + 10, y) == (80, 140, 255)
    assert any(rgb(scr.surface, x, 20) == screen.WHITE for x in range(300, 500))  # the trial and score line


def test_feedback_shows_hit_or_miss_the_cookie_and_the_field(scr):
    field = pygame.Surface((geometry.WIDTH, geometry.HEIGHT), pygame.SRCALPHA)
    field.fill((0, 0, 255, 255), pygame.Rect(200, 400, 10, 10))
    scr.feedback(5, 180, 4, 0.3, True, "top", field)
    bar_x = int(geometry.END_ZONE_X) + 30
    assert rgb(scr.surface, bar_x, 400) == screen.GREEN
    ex, ey = geometry.target_end("top")
    assert rgb(scr.surface, ex + 40, ey) == (240, 190, 90)
    assert rgb(scr.surface, 205, 405) == (0, 0, 255)
    assert rgb(scr.surface, BAR_X + 10, BAR_Y + 8) == screen.GREEN  # the force
    assert any(rgb(scr.surface, x, 20) == screen.WHITE for x in range(300, 500))  # the trial and score line
    scr.feedback(5, 180, 4, 0.3, False, "bottom")
    assert rgb(scr.surface, bar_x, 400) == screen.RED and rgb(scr.surface, 205, 405) == screen.BLACK
    assert rgb(scr.surface, ex + 40, ey) == screen.RED


def test_a_message_has_its_title_and_lines(scr):
    scr.surface.fill(screen.WHITE)
    scr.message("Pause", ["one", "two"])
    rows = {y: any(rgb(scr.surface, x, y) != screen.BLACK for x in range(300, 500)) for y in (100, 160, 220, 254, 300)}
    assert rows == {100: False, 160: True, 220: True, 254: True, 300: False}
    assert rgb(scr.surface, BAR_X, BAR_Y + 8) == screen.LIGHT_GREY


def test_the_field_overlay_is_the_scene_renderers_amplitude(tmp_path):
    binary = os.path.join(os.path.dirname(__file__), "..", "..", "..", "build", "native", "tools", "scene_render",
                          "ff-scene-render")
    if not os.access(binary, os.X_OK):
        pytest.fail(f"{binary} is missing: build the native preset first")
    out = subprocess.run([binary, "--scene", "frictionmap", "--target", "top", "--strength", "1", "--step", "8"],
                         capture_output=True, text=True, check=True).stdout
    rows = [line.split(",") for line in out.splitlines() if line and not line.startswith(("#", "x,"))]
    x, y, a = max(((float(r[0]), float(r[1]), float(r[4])) for r in rows), key=lambda r: r[2])
    surf = screen.field_surface(binary, "frictionmap", "top", 1.0)
    assert tuple(surf.get_at((int(x), int(y)))) == (60, 120, 255, int(150 * a))
    assert tuple(surf.get_at((4, 4))) == (60, 120, 255, 0)
    assert screen.field_surface(None, "frictionmap", "top", 1.0) is None
    assert screen.field_surface(str(tmp_path / "missing"), "frictionmap", "top", 1.0) is None
    assert screen.field_surface(binary, "no-such-scene", "top", 1.0) is None
