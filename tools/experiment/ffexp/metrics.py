"""Every per-trial and per-participant definition of the analysis (docs/spec.md,
the study's results: hit rate, movement time, direction changes, movement
angles, learning). One function per definition, each tested on synthetic data
with a known answer (tests/test_metrics.py)."""
import functools
import math

import numpy as np
from scipy import optimize, signal

from . import design, geometry

FRAME_RATE_HZ = 80.0
FILTER_CUTOFF_HZ = 2.0
FILTER_ORDER = 2
REVERSAL_GAP_PX = 10.0     # a stationary point is a reversal when the finger went >= 10 px (~2 mm)
MERGE_DISTANCE_PX = 15.0   # an x and a y reversal this close (~3 mm) are one direction change
BLOCK_TRIALS = 45
HALF_TRIALS = design.TRIALS // len(design.RENDERINGS)  # one rendering's trials: 90
MOVING_AVERAGE_WINDOW = 10
# The paths' directions (geometry.path_y: y' = 6T u (L - u) / L^3): every path
# starts and ends at 0 deg; the top and bottom ones are steepest mid-way, at
# +-atan(1.5 |T| / L) = +-26.6 deg (atan(|T| / L) = 18.4 deg is only their chord).
PATH_STEEPEST_DEG = math.degrees(math.atan(1.5 * abs(geometry.RISE["top"]) / geometry.PATH_LENGTH))
PATH_ANGLES_DEG = (0.0, PATH_STEEPEST_DEG, -PATH_STEEPEST_DEG)  # Fig. 14's reference lines
MIN_SPEED_PX_S = 20.0      # slower frames have no meaningful direction


def movement_samples(frames, trial):
    """The finger's path of one trial from leaving the start circle to
    crossing into the end zone (the movement time's interval), touch only."""
    t = frames["t"]
    sel = ((frames["trial"] == trial["trial"]) & (t >= trial["t_leave_start"])
           & (t <= trial["t_cross"]) & (frames["touch"] > 0)
           & np.isfinite(frames["x"]) & np.isfinite(frames["y"]))
    return t[sel], frames["x"][sel], frames["y"][sel]


def resample_uniform(t, x, y, rate_hz=FRAME_RATE_HZ):
    """Linear interpolation onto a uniform grid starting at t[0]."""
    t = np.asarray(t, float)
    if len(t) < 2:
        return t.copy(), np.asarray(x, float).copy(), np.asarray(y, float).copy()
    order = np.argsort(t, kind="stable")
    t, x, y = t[order], np.asarray(x, float)[order], np.asarray(y, float)[order]
    keep = np.concatenate([[True], np.diff(t) > 0])
    t, x, y = t[keep], x[keep], y[keep]
    grid = t[0] + np.arange(int(math.floor((t[-1] - t[0]) * rate_hz + 1e-9)) + 1) / rate_hz
    return grid, np.interp(grid, t, x), np.interp(grid, t, y)


def lowpass(values, rate_hz=FRAME_RATE_HZ, cutoff_hz=FILTER_CUTOFF_HZ):
    """2nd-order Butterworth low-pass, run forward and backward (zero phase)."""
    values = np.asarray(values, float)
    b, a = _butter(rate_hz, cutoff_hz)
    if len(values) < 4:
        return values.copy()
    return signal.filtfilt(b, a, values, padlen=min(3 * max(len(a), len(b)), len(values) - 1))


@functools.lru_cache(maxsize=8)
def _butter(rate_hz, cutoff_hz):
    return signal.butter(FILTER_ORDER, cutoff_hz / (rate_hz / 2.0))


def filtered_path(t, x, y):
    """The movement as the analysis sees it: uniform 80 Hz, low-passed."""
    _, xs, ys = resample_uniform(t, x, y)
    return lowpass(xs), lowpass(ys)  # a path too short to filter comes back as it is


def stationary_points(values):
    """Indices where the velocity changes sign (local extrema); on a flat top
    or bottom, its first sample."""
    v = np.asarray(values, float)
    out = []
    trend = 0
    turn = 0
    for i in range(1, len(v)):
        s = np.sign(v[i] - v[i - 1])
        if s == 0:
            continue
        if trend != 0 and s != trend:
            out.append(turn)
        trend = s
        turn = i
    return out


def reversals(values, gap=REVERSAL_GAP_PX):
    """Indices of the reversals of one coordinate (steering-reversal method):
    the stationary points, kept when the finger moved >= gap from the previous
    kept extremum (the start for the first) and then >= gap back."""
    v = np.asarray(values, float)
    if len(v) < 3:
        return []
    candidates = [0] + stationary_points(v) + [len(v) - 1]
    anchor = v[0]
    trend = 0
    extreme = None
    out = []
    for i in candidates[1:]:
        if trend == 0:
            if abs(v[i] - anchor) >= gap:
                trend = 1 if v[i] > anchor else -1
                extreme = i
            continue
        if (v[i] - v[extreme]) * trend > 0:
            extreme = i  # further in the same direction
        elif abs(v[i] - v[extreme]) >= gap:
            out.append(extreme)
            trend = -trend
            extreme = i
    return out


def merge_reversals(x, y, ix, iy, distance=MERGE_DISTANCE_PX):
    """Pairs of (x reversal, y reversal) that are one direction change: the
    finger positions at both are within `distance`; each reversal pairs once,
    nearest first."""
    pairs = []
    used_y = set()
    for i in ix:
        best, best_d = None, None
        for j in iy:
            if j in used_y:
                continue
            d = math.hypot(x[i] - x[j], y[i] - y[j])
            if d <= distance and (best_d is None or d < best_d):
                best, best_d = j, d
        if best is not None:
            used_y.add(best)
            pairs.append((i, best))
    return pairs


def direction_changes(t, x, y):
    """Direction changes of one trial's movement: resample to 80 Hz, filter,
    reversals in x plus reversals in y, minus the x/y pairs within 15 px.
    Returns (count, filtered x, filtered y, indices of the changes)."""
    return direction_changes_filtered(*filtered_path(t, x, y))


def direction_changes_filtered(xf, yf):
    """direction_changes() of an already filtered 80 Hz path."""
    ix, iy = reversals(xf), reversals(yf)
    pairs = merge_reversals(xf, yf, ix, iy)
    merged_y = {j for _, j in pairs}
    points = sorted(set(ix) | (set(iy) - merged_y))
    return len(ix) + len(iy) - len(pairs), xf, yf, points


def movement_angles(t, x, y, min_speed=MIN_SPEED_PX_S):
    """Direction of motion of each filtered 80 Hz step in degrees, 0 = right,
    positive = up the screen (y is down on the screen), slow steps dropped."""
    return angles_of_filtered(*filtered_path(t, x, y), min_speed=min_speed)


def angles_of_filtered(xf, yf, min_speed=MIN_SPEED_PX_S):
    if len(xf) < 3:
        return np.array([])
    dx, dy = np.diff(xf), np.diff(yf)
    fast = np.hypot(dx, dy) * FRAME_RATE_HZ >= min_speed
    return np.degrees(np.arctan2(-dy[fast], dx[fast]))


def angle_histogram(angles, bin_deg=5.0):
    """Normalised histogram (sums to 1) over [-180, 180)."""
    edges = np.arange(-180.0, 180.0 + bin_deg, bin_deg)
    counts, _ = np.histogram(np.asarray(angles, float), bins=edges)
    total = counts.sum()
    return edges, counts / total if total else counts.astype(float)


def hit_rate(trials):
    """Fraction of trials whose chosen target was the correct one (nan if none)."""
    return float(np.mean([t["hit"] for t in trials])) if trials else math.nan


def cell_table(trials, value, renderings, strengths):
    """value(list of trials) per (rendering, strength) cell."""
    return {(r, s): value([t for t in trials if t["rendering"] == r and math.isclose(t["strength"], s)])
            for r in renderings for s in strengths}


def block_hit_rates(trials, rendering, block=BLOCK_TRIALS, half=HALF_TRIALS):
    """Hit rate per block of `block` trials of one rendering, in the order
    they were presented (the thesis: 2 blocks of 45 per half). A trial's block
    comes from its number: each rendering fills one 90-trial half (1-90 or
    91-180), so trials 1-45 and 91-135 are block 1, 46-90 and 136-180 block 2,
    whichever trials are excluded. A block without trials is nan."""
    blocks = {}
    for t in trials:
        if t["rendering"] == rendering:
            blocks.setdefault((int(t["trial"]) - 1) % half // block, []).append(t)
    return [hit_rate(blocks.get(i, [])) for i in range(max(blocks) + 1)] if blocks else []


def moving_average(values, window=MOVING_AVERAGE_WINDOW):
    """Mean of each run of `window` consecutive values (len - window + 1 values;
    none for fewer than `window`)."""
    v = np.asarray(values, float)
    c = np.cumsum(np.concatenate([[0.0], v]))
    return (c[window:] - c[:-window]) / window


def power_law(x, a, b, c):
    return a * np.power(x, -b) + c


def fit_power_law(x, y):
    """Least-squares fit of y = a x^-b + c (learning curve); returns (a, b, c)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = np.isfinite(x) & np.isfinite(y) & (x > 0)
    x, y = x[ok], y[ok]
    if len(x) < 4:
        return (math.nan, math.nan, math.nan)
    c0 = float(np.min(y))
    a0 = max(float(y[0] - c0), 1e-6)
    try:
        p, _ = optimize.curve_fit(power_law, x, y, p0=(a0, 0.5, c0),
                                  bounds=([-np.inf, 0.0, -np.inf], [np.inf, 10.0, np.inf]), maxfev=20000)
    except (RuntimeError, ValueError):
        return (math.nan, math.nan, math.nan)
    return tuple(float(v) for v in p)


def path_length_excess(t, x, y, required_px=610.0):
    """Total |dx| travelled minus the least needed (start circle edge x = 90
    to the end zone x = 700), and total |dy| (appendix L panel I)."""
    if len(x) < 2:
        return 0.0, 0.0
    return float(np.sum(np.abs(np.diff(x))) - required_px), float(np.sum(np.abs(np.diff(y))))
