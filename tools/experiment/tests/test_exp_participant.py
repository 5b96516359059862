"""The simulated participant, by hand: its strokes, what it feels, how it
chooses, and its key presses."""
import math

import pytest

from ffexp import geometry, participant
from ffexp.participant import PROBE_X, SWEEP


def test_min_jerk_starts_ends_and_is_halfway_at_half_time():
    assert participant.min_jerk((0, 0), (10, 20), 2.0, 0.0) == (0, 0)
    assert participant.min_jerk((0, 0), (10, 20), 2.0, 1.0) == (5.0, 10.0)  # 10/8 - 15/16 + 6/32 = 1/2
    assert participant.min_jerk((0, 0), (10, 20), 2.0, 0.5) == pytest.approx((10 * 0.103515625, 20 * 0.103515625))
    assert participant.min_jerk((0, 0), (10, 20), 2.0, -1.0) == (0, 0)  # held before and after
    assert participant.min_jerk((0, 0), (10, 20), 2.0, 3.0) == (10, 20)


def _trial(p, t=10.0):
    p.begin_trial(t)
    p.started(t + 0.2)
    return p.probe_end


def test_a_trial_touches_down_in_the_start_circle_then_reaches_the_probe_line():
    p = participant.SimParticipant(seed=1, speed_scale=2.0)
    assert p.finger(0.0)[3] is False  # no trial: lifted
    p.begin_trial(10.0)
    x, y, f, touch = p.finger(10.0)
    assert not touch and (x, y) == geometry.START_CENTRE  # lifted for the first 50 ms
    x, y, f, touch = p.finger(10.06)
    assert touch and geometry.in_start(x, y) and f == pytest.approx(participant.FORCE_N, abs=0.1)
    p.started(10.2)
    # held 0.15 s / speed, then 0.5 d to the probe line, 0.35 d up, 0.6 d down: d in [0.8, 1.2] / speed
    assert 10.2 + 0.075 + 1.45 * 0.4 <= p.probe_end <= 10.2 + 0.075 + 1.45 * 0.6
    assert geometry.in_start(*p.finger(10.2 + 0.07)[:2])
    d = (p.probe_end - 10.275) / 1.45
    x, y, _, _ = p.finger(10.275 + 0.5 * d)
    assert x == pytest.approx(PROBE_X, abs=3) and y == pytest.approx(240.0, abs=3)
    x, y, _, _ = p.finger(10.275 + 0.85 * d)
    assert y == pytest.approx(SWEEP[0], abs=3)
    assert p.decided is None


def test_it_feels_only_on_the_probe_line_and_chooses_where_it_was_most_slippery():
    p = participant.SimParticipant(seed=2, decision_noise=0.0)
    end = _trial(p)
    bottom = float(geometry.path_y(PROBE_X, "bottom"))
    p.feel(PROBE_X + 5, bottom, 1.0)          # off the line
    p.feel(PROBE_X, bottom, math.nan)         # no amplitude yet
    for y in range(int(SWEEP[0]), int(SWEEP[1]), 5):
        p.feel(PROBE_X + 0.5, y, 0.9 if abs(y - bottom) < 10 else 0.4)
    assert len(p.felt) == len(range(int(SWEEP[0]), int(SWEEP[1]), 5))
    x, y, _, touch = p.finger(end)  # the plan's end: it decides
    assert p.decided == "bottom" and touch
    p.feel(PROBE_X, bottom, 0.0)  # decided: no longer feeling
    assert len(p.felt) == len(range(int(SWEEP[0]), int(SWEEP[1]), 5))
    leg = p.legs[-1]
    x, y, _, _ = p.finger(leg[0] + leg[3])
    assert x == pytest.approx(geometry.END_ZONE_X + 25, abs=3)
    assert y == pytest.approx(geometry.target_end("bottom")[1], abs=35)  # 8 px aim noise, 4 sigma
    assert not p.stuck(leg[0] + leg[3] + 0.4) and p.stuck(leg[0] + leg[3] + 0.6)
    p.end_trial()
    assert p.finger(leg[0] + leg[3])[3] is False and not p.stuck(1e9)
    # the next trial feels afresh: what the last one felt at the bottom is forgotten
    end = _trial(p, 30.0)
    assert p.decided is None and p.finger(30.25)[3] and p.decided is None  # no choice before the probe line
    top = float(geometry.path_y(PROBE_X, "top"))
    for y in range(int(SWEEP[0]), int(SWEEP[1]), 5):
        p.feel(PROBE_X, y, 0.6 if abs(y - top) < 10 else 0.4)
    p.finger(end)
    assert p.decided == "top"


def test_nothing_felt_is_a_guess_among_the_three():
    chosen = set()
    for seed in range(30):
        p = participant.SimParticipant(seed=seed)
        p.felt = []
        chosen.add(p.choose())
    assert chosen == {"top", "middle", "bottom"}


def test_a_key_is_pressed_0_3_s_after_the_screen_asks():
    p = participant.SimParticipant(seed=3)
    assert p.presses_key(5.0) is False and p.presses_key(5.29) is False
    assert p.presses_key(5.3) is True
    assert p.presses_key(6.0) is False  # the next screen waits again
    assert p.presses_key(6.3) is True
