"""The trial screen's geometry by hand: the three paths, the start circle,
the end zone and which target a crossing chose."""
import pytest

from ffexp import geometry


def test_paths_rise_smoothly_to_their_ends():
    for target, end_y in (("top", 40.0), ("middle", 240.0), ("bottom", 440.0)):
        assert geometry.path_y(100.0, target) == 240.0
        assert geometry.path_y(700.0, target) == pytest.approx(end_y)
        # halfway, u = L/2: T (-2/8 + 3/4) = T/2
        assert geometry.path_y(400.0, target) == pytest.approx(240.0 + (end_y - 240.0) / 2)
        assert geometry.path_y(50.0, target) == 240.0 and geometry.path_y(750.0, target) == pytest.approx(end_y)
        assert geometry.target_end(target) == (700.0, pytest.approx(end_y))


def test_the_crossing_chooses_the_nearest_end():
    # ends at y = 40, 240, 440: the boundaries halfway, at 140 and 340
    assert [geometry.choice(y) for y in (-50.0, 139.9, 140.0, 339.9, 340.0, 520.0)] == \
        ["top", "top", "middle", "middle", "bottom", "bottom"]


def test_start_circle_and_end_zone():
    assert geometry.in_start(90.0, 240.0) and geometry.in_start(60.0, 210.0)
    assert not geometry.in_start(90.1, 240.0) and not geometry.in_start(82.0, 262.0)  # 31.1 px off centre
    assert geometry.in_end_zone(700.1) and not geometry.in_end_zone(700.0)
