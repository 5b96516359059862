"""The simulated participant (--participant sim): minimum-jerk strokes with
noise. Each trial: touch down in the start circle, move right to x = 350,
sweep up and down across the three paths there while feeling the rendered
amplitude, choose the path where it felt most slippery (plus noise, so weak
strengths give more errors), and stroke to that path's end."""
import math

import numpy as np

from . import geometry

PROBE_X = 350.0
SWEEP = (130.0, 350.0)
FORCE_N = 0.3


def min_jerk(p0, p1, duration, t):
    s = min(max(t / duration, 0.0), 1.0)
    k = 10 * s ** 3 - 15 * s ** 4 + 6 * s ** 5
    return p0[0] + (p1[0] - p0[0]) * k, p0[1] + (p1[1] - p0[1]) * k


class SimParticipant:
    def __init__(self, seed, decision_noise=0.08, speed_scale=1.0):
        self.rng = np.random.default_rng(seed)
        self.noise = decision_noise
        self.speed = speed_scale
        self.legs = []
        self.felt = []
        self.decided = None
        self.key_at = None

    # -- trial
    def begin_trial(self, t):
        """Lift, touch down in the start circle and stay there until the
        program has seen the finger there (started())."""
        start = (geometry.START_CENTRE[0] + self.rng.normal(0, 3), geometry.START_CENTRE[1] + self.rng.normal(0, 3))
        self.legs = [(t + 0.05, start, start, 0.1)]
        self.probe_end = math.inf
        self.felt = []
        self.decided = None

    def started(self, t):
        """The program saw the finger in the start circle: plan the way to the
        probe line; the rest is decided there."""
        start = self.legs[0][1]
        d = self.rng.uniform(0.8, 1.2) / self.speed
        t_leg = t + 0.15 / self.speed
        timed = [(t, start, start, 0.15 / self.speed)]
        for p0, p1, dur in ((start, (PROBE_X, 240.0), 0.5 * d),
                            ((PROBE_X, 240.0), (PROBE_X, SWEEP[0]), 0.35 * d),
                            ((PROBE_X, SWEEP[0]), (PROBE_X, SWEEP[1]), 0.6 * d)):
            timed.append((t_leg, p0, p1, dur))
            t_leg += dur
        self.legs = timed
        self.probe_end = t_leg

    def stuck(self, t):
        """The plan has ended but the program has not ended the trial (frames
        too sparse to see a crossing, say): start over."""
        if not self.legs:
            return False
        last = self.legs[-1]
        return self.decided is not None and t > last[0] + last[3] + 0.5

    def feel(self, x, y, amplitude):
        if math.isfinite(amplitude) and abs(x - PROBE_X) < 1.0 and self.legs and not self.decided:
            self.felt.append((y, amplitude))

    def choose(self):
        """The path whose crossing at the probe line felt most slippery."""
        felt = np.array(self.felt) if self.felt else np.zeros((0, 2))
        scores = {}
        for target in geometry.RISE:
            py = float(geometry.path_y(PROBE_X, target))
            near = felt[np.abs(felt[:, 0] - py) < 20.0, 1] if len(felt) else []
            scores[target] = (float(np.mean(near)) if len(near) else 0.5) + self.rng.normal(0, self.noise)
        return max(scores, key=scores.get)

    def finger(self, t):
        """(x, y, force N, touching) at time t."""
        if not self.legs or t < self.legs[0][0]:
            return geometry.START_CENTRE[0], geometry.START_CENTRE[1], 0.0, False
        if t >= self.probe_end and self.decided is None:
            self.decided = self.choose()
            end = geometry.target_end(self.decided)
            goal = (geometry.END_ZONE_X + 25.0, end[1] + self.rng.normal(0, 8))
            self.legs.append((self.probe_end, (PROBE_X, SWEEP[1]), goal, self.rng.uniform(0.6, 0.9) / self.speed))
        leg = [candidate for candidate in self.legs if t >= candidate[0]][-1]  # legs are in time order
        x, y = min_jerk(leg[1], leg[2], leg[3], t - leg[0])
        return x + self.rng.normal(0, 0.5), y + self.rng.normal(0, 0.5), FORCE_N + self.rng.normal(0, 0.02), True

    def end_trial(self):
        self.legs = []

    # -- screens that wait for a key
    def presses_key(self, t):
        if self.key_at is None:
            self.key_at = t + 0.3
        if t >= self.key_at:
            self.key_at = None
            return True
        return False
