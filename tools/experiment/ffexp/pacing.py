"""80 Hz frames against a monotonic deadline (pygame's Clock.tick drifts: it
sleeps a period after the last frame, not until the next deadline)."""
import time

FRAME_RATE_HZ = 80.0
LATE_FRACTION = 0.25   # a frame starting > 1/4 period after its deadline is late


class Pacer:
    """wait() sleeps until the next deadline and returns the frame's lateness
    in seconds of study time. With time_scale X (the simulator's --speed),
    the frames run at 80 Hz of simulated time: 80 X per wall second."""

    def __init__(self, rate_hz=FRAME_RATE_HZ, time_scale=1.0, wall=time.monotonic, sleep=time.sleep):
        self.period = 1.0 / (rate_hz * time_scale)
        self.scale = time_scale
        self.wall, self.sleep = wall, sleep
        self.deadline = None
        self.late_frames = 0
        self.frames = 0

    def wait(self):
        now = self.wall()
        if self.deadline is None:
            self.deadline = now
        elif now < self.deadline:
            self.sleep(self.deadline - now)
            now = self.wall()
        lateness = max(0.0, now - self.deadline)
        self.frames += 1
        if lateness > LATE_FRACTION * self.period:
            self.late_frames += 1
        if lateness > self.period:
            self.deadline = now  # fell a whole frame behind: drop it, keep the rate
        self.deadline += self.period
        return lateness * self.scale

    def is_late(self, lateness_study_s):
        return lateness_study_s > LATE_FRACTION * self.period * self.scale
