"""Each analysis definition on synthetic strokes with known answers."""
import math

import numpy as np
import pytest

from ffexp import metrics


def eased(waypoints, leg_s, rate=400.0, start=0.0):
    """A coordinate moving between waypoints with cosine easing (velocity 0 at each)."""
    ts, vs = [], []
    for k in range(len(waypoints) - 1):
        t = np.arange(0, leg_s, 1 / rate)
        a, b = waypoints[k], waypoints[k + 1]
        ts.append(start + k * leg_s + t)
        vs.append(a + (b - a) * (1 - np.cos(np.pi * t / leg_s)) / 2)
    ts.append([start + (len(waypoints) - 1) * leg_s])
    vs.append([waypoints[-1]])
    return np.concatenate(ts), np.concatenate(vs)


def stroke(x_points, x_leg, y_points, y_leg, y_start=0.0):
    tx, x = eased(x_points, x_leg)
    ty, y = eased(y_points, y_leg, start=y_start)
    t = np.arange(0, max(tx[-1], ty[-1]), 1 / 200.0)  # a 200 Hz sensor, not the 80 Hz grid
    return t, np.interp(t, tx, x), np.interp(t, ty, y)


def test_reversals_of_one_coordinate():
    t, x = eased([100, 300, 200, 400, 300, 700], 1.0)
    assert len(metrics.reversals(x)) == 4


def test_wiggle_below_gap_is_not_a_reversal():
    t, x = eased([100, 300, 292, 700], 1.0)  # an 8 px step back
    assert metrics.reversals(x) == []
    t, x = eased([100, 300, 289, 700], 1.0)  # 11 px
    assert len(metrics.reversals(x)) == 2  # back 11 px, then forward again: two turns


def test_four_x_and_five_y_reversals_count_nine():
    # x turns every 2 s, y every 1 s from 1.5 s: never within 0.5 s of each other
    t, x, y = stroke([100, 300, 200, 420, 300, 700], 2.0,
                     [240, 140, 320, 160, 330, 180, 400], 1.0, y_start=0.5)
    n, xf, yf, points = metrics.direction_changes(t, x, y)
    assert len(metrics.reversals(xf)) == 4
    assert len(metrics.reversals(yf)) == 5
    assert n == 9
    assert len(points) == 9


def test_simultaneous_x_and_y_reversal_counts_once():
    # both coordinates turn at the same moments (1.0 s legs): every x reversal
    # has a y reversal at the same place
    t, x, y = stroke([100, 300, 200, 420, 300, 700], 1.0,
                     [240, 140, 320, 160, 330, 180, 400], 1.0)
    n, xf, yf, _ = metrics.direction_changes(t, x, y)
    ix, iy = metrics.reversals(xf), metrics.reversals(yf)
    assert (len(ix), len(iy)) == (4, 5)
    assert n == 5  # 4 merged pairs + 1 y reversal alone


def test_merge_threshold_is_15_px():
    x = np.array([0.0, 0.0, 0.0]); y = np.array([0.0, 14.9, 15.1])
    assert metrics.merge_reversals(x, y, [0], [1]) == [(0, 1)]
    assert metrics.merge_reversals(x, y, [0], [2]) == []


def test_filter_is_zero_phase_and_minus_6_db_at_cutoff():
    t = np.arange(0, 20, 1 / 80.0)
    slow = np.sin(2 * np.pi * 0.3 * t)
    f = metrics.lowpass(slow)
    mid = slice(400, 1200)
    assert np.max(np.abs(f[mid] - slow[mid])) < 0.01  # no lag
    at_cut = metrics.lowpass(np.sin(2 * np.pi * 2.0 * t))
    # |H|^2 of a Butterworth at its cut-off is 1/2; forward+backward squares it
    assert np.max(np.abs(at_cut[mid])) == pytest.approx(0.5, abs=0.01)


def test_resample_uniform_80_hz():
    t = np.array([0.0, 0.013, 0.05, 0.1])
    g, x, y = metrics.resample_uniform(t, t * 100, t * -100)
    assert np.allclose(np.diff(g), 1 / 80)
    assert np.allclose(x, g * 100)


def test_movement_angles_along_paths():
    t = np.arange(0, 3, 1 / 80)
    up = metrics.movement_angles(t, 100 + 200 * t, 240 - 200 / 3 * t)  # straight towards the top end
    assert np.median(up) == pytest.approx(math.degrees(math.atan(200 / 600)), abs=0.1)  # the chord: 18.4 deg
    edges, h = metrics.angle_histogram(up)
    assert h.sum() == pytest.approx(1.0)


def test_the_paths_start_and_end_level_and_are_steepest_mid_way():
    # Along the top path y = 240 - 200 (3 s^2 - 2 s^3), s = (x - 100) / 600, by hand:
    # dy/dx = -200 * 6 s (1 - s) / 600, 0 at both ends, -0.5 mid-way: atan(0.5) = 26.57 deg up the screen.
    t = np.arange(0, 6 + 1e-9, 1 / 80)
    s = t / 6
    x, y = 100 + 600 * s, 240 - 200 * (3 * s ** 2 - 2 * s ** 3)
    a = metrics.movement_angles(t, x, y, min_speed=0)
    assert a[len(a) // 2] == pytest.approx(26.565, abs=0.1) and np.max(a) == pytest.approx(26.565, abs=0.1)
    assert abs(a[1]) < 1.5 and abs(a[-2]) < 1.5
    assert metrics.PATH_ANGLES_DEG == pytest.approx((0.0, 26.565, -26.565), abs=1e-3)


def test_power_law_recovered_within_one_percent():
    a, b, c = 11.7, 0.29, 4.0
    x = np.arange(1, 82, dtype=float)
    rng = np.random.default_rng(2)
    y = metrics.power_law(x, a, b, c) * (1 + rng.normal(0, 0.001, len(x)))
    fa, fb, fc = metrics.fit_power_law(x, y)
    assert fa == pytest.approx(a, rel=0.01)
    assert fb == pytest.approx(b, rel=0.01)
    assert fc == pytest.approx(c, rel=0.01)


def test_moving_average_window_10():
    v = np.arange(20, dtype=float)
    m = metrics.moving_average(v)
    assert len(m) == 11 and m[0] == pytest.approx(4.5) and m[-1] == pytest.approx(14.5)


def trials_with(hits, rendering="heightmap", strength=1.0, start=1):
    return [dict(trial=start + i, rendering=rendering, strength=strength, hit=h) for i, h in enumerate(hits)]


def test_hit_rate_and_blocks():
    tr = trials_with([True] * 45 + [False] * 45)
    assert metrics.hit_rate(tr) == 0.5
    assert metrics.block_hit_rates(tr, "heightmap") == [1.0, 0.0]
    assert math.isnan(metrics.hit_rate([]))


def test_blocks_follow_the_trial_numbers_when_trials_are_excluded():
    # block 1 (trials 1-45) all hits, block 2 (46-90) all misses; 5 block-1 trials excluded:
    # still 40/40 and 0/45, not the first 45 remaining trials (40 hits + 5 misses = 0.889)
    tr = [t for t in trials_with([True] * 45 + [False] * 45) if t["trial"] not in (3, 10, 20, 30, 40)]
    assert metrics.block_hit_rates(tr, "heightmap") == [1.0, 0.0]
    # the second half: trials 91-135 and 136-180, here with block 2's first 9 trials excluded
    tr = [t for t in trials_with([True] * 45 + [False] * 45, start=91) if not 136 <= t["trial"] <= 144]
    assert metrics.block_hit_rates(tr, "heightmap") == [1.0, 0.0]


def test_movement_samples_take_the_trial_interval_only():
    frames = dict(trial=np.array([1, 1, 1, 1, 2.0]), t=np.array([0, 1, 2, 3, 4.0]),
                  x=np.arange(5.0), y=np.arange(5.0), touch=np.array([1, 1, 0, 1, 1.0]))
    t, x, y = metrics.movement_samples(frames, dict(trial=1, t_leave_start=1, t_cross=3))
    assert list(t) == [1, 3]


def test_resample_sorts_the_samples_and_drops_repeated_stamps():
    # a log's rows out of order, one stamp twice (the first row of it kept)
    g, x, y = metrics.resample_uniform([0.025, 0.0, 0.0125, 0.0125], [30.0, 0.0, 10.0, 99.0], [3.0, 0.0, 1.0, 99.0])
    assert list(g) == [0.0, 0.0125, 0.025]
    assert list(x) == [0.0, 10.0, 30.0] and list(y) == [0.0, 1.0, 3.0]


def test_too_short_inputs_come_back_as_they_are():
    g, x, y = metrics.resample_uniform([0.5], [7], [8])
    assert (list(g), list(x), list(y)) == ([0.5], [7.0], [8.0])
    assert all(len(a) == 0 for a in metrics.resample_uniform([], [], []))  # a trial without a touching frame
    short = metrics.lowpass([1, 2, 3])  # a filtfilt needs more than its padding
    assert isinstance(short, np.ndarray) and list(short) == [1.0, 2.0, 3.0]
    assert metrics.direction_changes_filtered(np.array([1.0, 2.0]), np.array([3.0, 4.0]))[0] == 0
    assert metrics.direction_changes_filtered(np.array([1.0, 2.0]), np.array([3.0, 4.0]))[3] == []
    assert metrics.direction_changes([], [], [])[0] == 0 and metrics.reversals([]) == []
    assert len(metrics.angles_of_filtered(np.array([1.0, 2.0]), np.array([3.0, 4.0]))) == 0
    assert len(metrics.moving_average(np.arange(9.0))) == 0
    assert metrics.path_length_excess([0.0], [0.0], [5.0]) == (0.0, 0.0)


def test_a_flat_top_is_one_stationary_point_at_its_first_sample():
    assert metrics.stationary_points([0, 1, 2, 2, 2, 1, 0]) == [2]
    assert metrics.stationary_points([0, 1, 1, 2, 3]) == []  # a pause on the way up turns nothing


def test_a_reversal_is_at_the_furthest_point_of_its_run():
    # up past the gap to 20, a 1 px wiggle, on up to 40, back 15: one reversal, at the 40
    v = [0, 10, 20, 19, 30, 40, 32, 25]
    assert metrics.reversals(v) == [5]


def test_each_y_reversal_pairs_with_one_x_reversal_only():
    # along x: x reversals at 0 and 6, y reversals at 5 and -10 (all at y = 0)
    x = np.array([0.0, 6.0, 5.0, -10.0]); y = np.zeros(4)
    # x0 takes y2 (5 px; y3 is 10); y2 is then gone and y3 is 16 px from x1
    assert metrics.merge_reversals(x, y, [0, 1], [2, 3]) == [(0, 2)]
    x[3] = 18.0  # y3 18 px from x0, 12 from x1: x1 takes it
    assert metrics.merge_reversals(x, y, [0, 1], [2, 3]) == [(0, 2), (1, 3)]


def test_power_law_fit_skips_non_finite_and_non_positive_points():
    x = np.arange(0, 30, dtype=float)  # x = 0 has no power law
    y = metrics.power_law(np.maximum(x, 1), 10.0, 0.5, 2.0)
    y[5] = math.nan
    fa, fb, fc = metrics.fit_power_law(x, y)
    assert (fa, fb, fc) == pytest.approx((10.0, 0.5, 2.0), rel=1e-4)
    assert all(math.isnan(v) for v in metrics.fit_power_law([1, 2, 3, math.nan, 0], [5, 4, 3, 2, 1]))


def test_path_length_beyond_the_least_needed():
    # from the start circle's edge (x = 90) to the end zone (x = 700) is 610 px; 5 px back and forth more
    x, y = [90.0, 100.0, 95.0, 700.0], [0.0, 3.0, -1.0, -1.0]
    assert metrics.path_length_excess(None, x, y) == (10.0, 7.0)
