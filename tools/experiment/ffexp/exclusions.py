"""Trial exclusions: exclusions.csv (trial,reason) in a participant folder,
written or reviewed by a person. `ff-experiment --propose-exclusions DIR`
lists candidates the person then accepts or not:
  jump       the position moved faster than a finger can in one frame
  two-finger a jump that comes back within a few frames (a second finger on the sensor)
  device     the device was lost during the trial, or frames stopped coming
"""
import csv
import os

import numpy as np

import ff_files

from . import logs

EXCLUSION_COLUMNS = ["trial", "reason"]
JUMP_PX_PER_S = 8000.0       # ~1.5 m/s on the 7" screen: faster than an exploring finger
RETURN_FRAMES = 8            # a jump undone within 0.1 s
FRAME_GAP_S = 0.5


def read_exclusions(folder):
    """{trial: reason}; no file means no exclusions."""
    path = os.path.join(folder, "exclusions.csv")
    if not os.path.isfile(path):
        return {}
    out = {}
    # the reason may be left out; a last row without its end is a row (editors save so)
    for line, row, idx, _ in logs._rows(path, EXCLUSION_COLUMNS, written_by_hand=True):
        if len(row) <= idx["trial"]:
            raise logs.LogError(path, line, "no trial number")
        text = row[idx["trial"]].strip()
        if not (text.isascii() and text.isdigit()) or not 1 <= int(text) <= 180:  # not '²' or '٣'
            raise logs.LogError(path, line, f"'{text}' is not a trial number 1..180")
        out[int(text)] = row[idx["reason"]] if len(row) > idx["reason"] else ""
    return out


def propose(folder):
    """Candidate exclusions [(trial, reason, detail)] from the frames and events."""
    trials = logs.read_trials(folder)
    frames = logs.read_frames(folder)
    events = logs.read_events(folder)
    events_path = os.path.join(folder, "events.csv")
    for e in events:
        e["t"] = logs._number(events_path, e["line"], "t", e["t"])
    windows = event_windows(trials, [e["t"] for e in events if e["event"] == "resume"])
    device = {}  # trial -> the first thing the device did wrong in it
    for e in events:
        if e["event"] in ("device-lost", "device-error") and e["trial"] not in ("", None):
            n = logs._whole(events_path, e["line"], "trial", e["trial"])
            if n in windows and windows[n][0] < e["t"] <= windows[n][1]:
                device.setdefault(n, "device lost during the trial" if e["event"] == "device-lost"
                                  else f"device error during the trial: {e['detail']}")
    out = []
    for tr in trials:
        n = tr["trial"]
        sel = (frames["trial"] == n) & (frames["t"] >= tr["t_enter_start"]) & (frames["t"] <= tr["t_cross"])
        t, x, y, touch = frames["t"][sel], frames["x"][sel], frames["y"][sel], frames["touch"][sel]
        if n in device:
            out.append((n, "device", device[n]))
            continue
        if len(t) > 1 and np.max(np.diff(t)) > FRAME_GAP_S:
            out.append((n, "device", f"no frames for {np.max(np.diff(t)):.2f} s"))
            continue
        ok = touch > 0
        t, x, y = t[ok], x[ok], y[ok]
        dt = np.maximum(np.diff(t), 1e-3)
        step = np.hypot(np.diff(x), np.diff(y))
        jumps = np.nonzero(step / dt > JUMP_PX_PER_S)[0]
        if len(jumps) == 0:
            continue
        j = int(jumps[0])
        dx, dy = np.diff(x), np.diff(y)
        # a second finger: a jump undone by an opposite jump soon after
        back = [k for k in jumps if j < k <= j + RETURN_FRAMES and
                np.hypot(dx[j] + dx[k], dy[j] + dy[k]) < step[j] / 2]
        if back:
            out.append((n, "two-finger", f"jump of {step[j]:.0f} px at t={t[j + 1]:.3f} s and back"))
        else:
            out.append((n, "jump", f"jump of {step[j]:.0f} px in {dt[j] * 1000:.0f} ms at t={t[j + 1]:.3f} s"))
    return out


def event_windows(trials, resumes):
    """{trial: (after, until)}: a finished trial's events are those logged
    after the previous finished trial's crossing or the last resume before
    it began, whichever is later (not those of a run killed during it), up to
    its own crossing (a device lost and back before a restart counts)."""
    crossings = sorted(t["t_cross"] for t in trials)
    out = {}
    for tr in trials:
        before = [c for c in crossings if c < tr["t_enter_start"]] + [r for r in resumes if r <= tr["t_enter_start"]]
        out[tr["trial"]] = (max(before, default=-np.inf), tr["t_cross"])
    return out


def write_proposal(folder, candidates):
    """Writes exclusions.proposed.csv for a person to review (never exclusions.csv)."""
    path = os.path.join(folder, "exclusions.proposed.csv")

    def write(f):
        w = csv.writer(f, lineterminator="\n")
        w.writerow(EXCLUSION_COLUMNS + ["detail"])
        for n, reason, detail in candidates:
            w.writerow([n, reason, detail])
    ff_files.write_whole(path, write)
    return path
