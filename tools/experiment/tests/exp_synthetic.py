"""Synthetic participant folders with known answers, written through the
program's own log writer (so the reader and the analysis see real files)."""
import os

import numpy as np

from ffexp import design, geometry, logs


def straight_stroke(target_y, rng, duration, rate=80.0):
    """A minimum-jerk stroke from the start circle to the end zone at target_y."""
    t = np.arange(0, duration + 1e-9, 1 / rate)
    s = t / duration
    shape = 10 * s ** 3 - 15 * s ** 4 + 6 * s ** 5
    x = geometry.START_CENTRE[0] + (geometry.END_ZONE_X + 10 - geometry.START_CENTRE[0]) * shape
    y = geometry.PATH_Y0 + (target_y - geometry.PATH_Y0) * shape + rng.normal(0, 0.3, len(t))
    return t, x, y


def write_participant(root, number, hit_prob, movement_time=None, rng_seed=0, rate=20.0):
    """hit_prob(rendering, strength) -> probability of a hit; movement_time(rendering, index) -> s."""
    rng = np.random.default_rng(rng_seed + number)
    folder = os.path.join(root, f"P{number:02d}")
    log = logs.ParticipantLog(folder)
    logs.write_session(folder, dict(participant=number, seed=number, order=design.order_name(number),
                                    age=30, gender="x", handedness="right", program_version="test"))
    clock = 0.0
    index = {r: 0 for r in logs.RENDERINGS}
    for tr in design.plan(number):
        r = tr["rendering"]
        index[r] += 1
        hit = rng.random() < hit_prob(r, tr["strength"])
        others = [t for t in logs.TARGETS if t != tr["target"]]
        chosen = tr["target"] if hit else others[int(rng.integers(2))]
        end_y = geometry.target_end(chosen)[1]
        mt = movement_time(r, index[r]) if movement_time else 2.0
        t, x, y = straight_stroke(end_y, rng, mt, rate)
        t_enter = clock
        t_leave = clock + 0.2
        # frames in bulk (the row-by-row flushing writer is tested elsewhere)
        log.frames._file.write("".join(f"{tr['trial']},{t_leave + ti:.6f},{xi:.3f},{yi:.3f},1,0.3,0\n"
                                       for ti, xi, yi in zip(t, x, y)))
        t_cross = t_leave + t[-1]
        # appended without the per-trial fsync (thousands of fsyncs slow a busy disk)
        log.trials.append([dict(tr, choice=chosen, hit=int(hit), t_enter_start=t_enter, t_leave_start=t_leave,
                       t_cross=t_cross, movement_time=t_cross - t_leave, crossing_y=float(y[-1]),
                       late_frames=0, ack="ok")[c] for c in logs.TRIAL_COLUMNS])
        clock = t_cross + 1.0
    log.close()
    return folder
