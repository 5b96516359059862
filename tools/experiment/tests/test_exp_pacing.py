"""The pacer on a fake clock: no drift, late frames counted."""
import pytest

from ffexp.pacing import Pacer


class FakeClock:
    def __init__(self):
        self.t = 0.0
        self.work = 0.0

    def wall(self):
        return self.t

    def sleep(self, s):
        self.t += s


def test_no_drift_with_work_each_frame():
    c = FakeClock()
    p = Pacer(wall=c.wall, sleep=c.sleep)
    for _ in range(800):
        p.wait()
        c.t += 0.004  # 4 ms of work per 12.5 ms frame
    # 800 frames at 80 Hz: frame 800 starts at 799/80 s, exactly
    assert c.t == pytest.approx(799 / 80 + 0.004, abs=1e-9)
    assert p.late_frames == 0


def test_late_frame_counted_and_rate_kept():
    c = FakeClock()
    p = Pacer(wall=c.wall, sleep=c.sleep)
    p.wait()
    c.t += 0.030  # one slow frame (30 ms)
    late = p.wait()
    assert late == pytest.approx(0.0175) and p.late_frames == 1
    start = c.t
    p.wait()
    assert c.t - start == pytest.approx(1 / 80)


def test_time_scale_runs_faster_and_reports_study_time():
    c = FakeClock()
    p = Pacer(time_scale=10, wall=c.wall, sleep=c.sleep)
    for _ in range(81):
        p.wait()
    assert c.t == pytest.approx(0.1)  # 80 frames of 1/800 s


def test_a_sleep_that_overshoots_is_lateness():
    c = FakeClock()
    p = Pacer(time_scale=2, wall=c.wall, sleep=lambda s: setattr(c, "t", c.t + s + 0.005))  # the OS wakes 5 ms late
    p.wait()
    # 5 ms of wall time at 2x is 10 ms of study time; the period is 6.25 ms wall, its quarter 1.5625 ms
    assert p.wait() == pytest.approx(0.010)
    assert (p.frames, p.late_frames) == (2, 1)
    assert p.is_late(0.0032) and not p.is_late(0.0031)  # a quarter of 12.5 ms of study time: 3.125 ms
