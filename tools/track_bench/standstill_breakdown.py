#!/usr/bin/env python3
"""Where the heightmap error falls after each standstill.

Input: the tick files of `ff-track-bench --class C --dump-ticks FILE` (FILE,
FILE.1, ... one per trace). The moving ticks (touching, true speed at least
--moving-speed px/s, as the class table counts them) are binned by the time
since the truth last moved slower than that (or was lifted). Per bin:

  ticks            share of the moving ticks
  squared error    share of the heightmap's squared amplitude error
  at full length   the same error had the tracked direction been rendered at
                   full length at the true position (hm_unit_dir): where it
                   is lower, the direction was right but faded
  direction        mean length of the rendered direction (0 faded out, 1 full)
  speed ratio      mean of the tracked speed over the true speed

Both error columns are shares of the shipping error's total, so they add up
to 100 % and to (full-length RMS / RMS)^2 respectively. Generated traces,
not a sensor.

Example:
  ff-track-bench --class realistic-200hz --duration 30 --dump-ticks r200.csv
  standstill_breakdown.py r200.csv r200.csv.*
Exit codes: 0 ok, 2 bad usage or input (one line on stderr, never a traceback).
"""
import argparse
import sys

import numpy as np

COLUMNS = ("t_us", "vx_true", "vy_true", "touching", "vx", "vy", "dx", "dy", "hm", "hm_ideal", "hm_unit_dir")


class InputError(Exception):
    pass


def read_ticks(path):
    """The columns this needs, as float arrays, from one --dump-ticks file."""
    try:
        # The '#' metadata lines go first: genfromtxt would take the first of them for the header.
        with open(path) as f:
            lines = [line for line in f if not line.startswith("#")]
        data = np.genfromtxt(lines, delimiter=",", names=True)
    except (OSError, ValueError) as e:
        raise InputError(f"{path}: {e}") from None
    if data.dtype.names is None or data.size == 0:
        raise InputError(f"{path}: no ticks")
    missing = [c for c in COLUMNS if c not in data.dtype.names]
    if missing:
        raise InputError(f"{path}: not a --dump-ticks file (missing {', '.join(missing)})")
    data = np.atleast_1d(data)
    return {c: np.asarray(data[c], dtype=float) for c in COLUMNS}


def since_standstill_ms(t_us, still):
    """Per tick, ms since the last tick that was still (inf before the first)."""
    last = np.where(still, t_us, -np.inf)
    last = np.maximum.accumulate(last)
    return (t_us - last) * 1e-3


def breakdown(traces, moving_speed_px_s, edges_ms):
    """Rows (low, high, ticks, squared, full_length, direction, speed_ratio) and totals."""
    since, sq, sq_full, length, ratio = [], [], [], [], []
    for d in traces:
        speed = np.hypot(d["vx_true"], d["vy_true"])
        touching = d["touching"] == 1
        moving = touching & (speed >= moving_speed_px_s)
        s = since_standstill_ms(d["t_us"], ~moving)
        since.append(s[moving])
        sq.append((d["hm"] - d["hm_ideal"])[moving] ** 2)
        sq_full.append((d["hm_unit_dir"] - d["hm_ideal"])[moving] ** 2)
        length.append(np.hypot(d["dx"], d["dy"])[moving])
        ratio.append(np.hypot(d["vx"], d["vy"])[moving] / speed[moving])
    since, sq, sq_full, length, ratio = (np.concatenate(a) for a in (since, sq, sq_full, length, ratio))
    n, total = since.size, sq.sum()
    if n == 0 or total <= 0.0:
        raise InputError("no moving ticks with an error to break down")
    bounds = [0.0] + list(edges_ms) + [np.inf]
    rows = []
    for low, high in zip(bounds[:-1], bounds[1:]):
        m = (since >= low) & ((since < high) | np.isinf(high))  # a finger never still yet: the last bin
        k = int(m.sum())
        rows.append((low, high, k / n, sq[m].sum() / total, sq_full[m].sum() / total,
                     length[m].mean() if k else float("nan"), ratio[m].mean() if k else float("nan")))
    return rows, {"ticks": n, "rms": float(np.sqrt(total / n)), "full_length_rms": float(np.sqrt(sq_full.sum() / n))}


def format_table(rows, totals):
    out = ["| since the standstill | ticks | squared error | at full length | direction | speed ratio |",
           "|---|--:|--:|--:|--:|--:|"]
    for low, high, ticks, sq, full, length, ratio in rows:
        span = f"{low:g}-{high:g} ms" if np.isfinite(high) else f"{low:g} ms and later"
        out.append(f"| {span} | {100 * ticks:.1f} % | {100 * sq:.1f} % | {100 * full:.1f} % | {length:.2f} | {ratio:.2f} |")
    out.append("")
    out.append(f"{totals['ticks']} moving ticks; heightmap error RMS {totals['rms']:.4f}, "
               f"{totals['full_length_rms']:.4f} with the tracked direction at full length")
    return "\n".join(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("Example:")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="Example:" + __doc__.split("Example:")[1])
    parser.add_argument("ticks", nargs="+", help="--dump-ticks files, one per trace")
    parser.add_argument("--moving-speed", type=float, default=20.0,
                        help="px/s: slower (or lifted) counts as a standstill (default 20, the class table's)")
    parser.add_argument("--bins", default="40,80,160,320",
                        help="bin edges in ms since the standstill, increasing (default 40,80,160,320)")
    args = parser.parse_args(argv)
    try:
        edges = [float(x) for x in args.bins.split(",") if x.strip()]
        if not edges or any(b <= a for a, b in zip([0.0] + edges, edges)):
            raise InputError(f"--bins {args.bins}: positive and increasing edges wanted")
        if not args.moving_speed > 0.0:
            raise InputError("--moving-speed must be above 0")
        rows, totals = breakdown([read_ticks(p) for p in args.ticks], args.moving_speed, edges)
    except (InputError, ValueError) as e:
        print(f"standstill_breakdown: {e}", file=sys.stderr)
        return 2
    print(format_table(rows, totals))
    return 0


if __name__ == "__main__":
    sys.exit(main())
