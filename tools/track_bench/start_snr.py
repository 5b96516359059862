#!/usr/bin/env python3
"""How soon a constant-velocity Kalman filter can tell a start from rest.

The direction confidence fades the direction in between 2.5 and 5 sigma of a
resting finger's velocity noise through the direction filter
(docs/tracking.md#direction-confidence). This prints, for a range of the
filter's acceleration density, when the settled filter's speed on a
noiseless minimum-jerk start crosses those levels, and how far the finger
has moved by then: the evidence a velocity-based fade waits for. Then the
same for an ideal detector told when the stroke starts, its shape and where
the finger rested (a Neyman-Pearson test of the reports against that
shape), with and without the stroke's direction: no detector of starts can
see one sooner at the same rate of false alarms at rest.

Model: per axis, state (position, velocity), white acceleration of density
q (px^2/s^3), reports every T with white noise of sigma (px); the filter's
settled gains from the Riccati recursion, its resting velocity variance
from the stationary (Lyapunov) covariance of the settled filter fed noise
alone. The ideal detector's deflection is ||s|| / sigma over the reports
since the start (s their noiseless displacement); a linear filter started
from the same rest, such as the settled filter's velocity, cannot exceed it
(Cauchy-Schwarz). Not told the direction, it tests the 2-D displacement's
length, whose tail at rest is the speed's (Rayleigh, exp(-k^2 / 2) beyond k
sigma); told it, the 1-D threshold with that same tail. float64; the
tracker's own code is C++ (core/velocity_noise.cpp).

usage: start_snr.py [--rate-hz 200] [--noise-px 1] [--distance-px 300]
                    [--duration-s 0.6] [--sqrt-q 20 45 100 200 400 750]
"""
import argparse
import sys

import numpy as np
from scipy.linalg import solve_discrete_lyapunov
from scipy.stats import norm


def settled_gains(q, interval_s, noise_px):
    """The filter's gains (position, velocity) after it has settled."""
    T = interval_s
    F = np.array([[1.0, T], [0.0, 1.0]])
    Q = q * np.array([[T ** 3 / 3.0, T ** 2 / 2.0], [T ** 2 / 2.0, T]])
    P = np.diag([noise_px ** 2, 1e6])
    gains = np.zeros(2)
    for _ in range(100000):
        P = F @ P @ F.T + Q
        S = P[0, 0] + noise_px ** 2
        K = P[:, 0] / S
        P = P - np.outer(K, P[0, :])
        if np.allclose(K, gains, rtol=1e-12, atol=0.0):
            break
        gains = K
    return gains


def settled_step(gains, interval_s):
    """x' = A x + B z of the settled filter."""
    F = np.array([[1.0, interval_s], [0.0, 1.0]])
    H = np.array([[1.0, 0.0]])
    A = (np.eye(2) - np.outer(gains, H)) @ F
    return A, gains


def resting_velocity_sigma(q, interval_s, noise_px):
    """Standard deviation of the settled filter's velocity fed white noise alone."""
    A, B = settled_step(settled_gains(q, interval_s, noise_px), interval_s)
    covariance = solve_discrete_lyapunov(A, noise_px ** 2 * np.outer(B, B))
    return float(np.sqrt(covariance[1, 1]))


def minimum_jerk(t, distance_px, duration_s):
    tau = np.clip(t / duration_s, 0.0, 1.0)
    position = distance_px * (10 * tau ** 3 - 15 * tau ** 4 + 6 * tau ** 5)
    velocity = distance_px / duration_s * (30 * tau ** 2 - 60 * tau ** 3 + 30 * tau ** 4)
    return position, velocity


def filtered_speed(positions, gains, interval_s):
    """The settled filter's velocity along a noiseless trajectory, starting at rest."""
    A, B = settled_step(gains, interval_s)
    x = np.zeros(2)
    out = np.empty(len(positions))
    for k, z in enumerate(positions):
        x = A @ x + B * z
        out[k] = x[1]
    return out


def crossings(sqrt_q, rate_hz, noise_px, distance_px, duration_s, levels=(2.5, 5.0)):
    """Per level: (ms after the start, px moved, true speed px/s) when the
    filter's speed first reaches level x its resting sigma; None if never."""
    T = 1.0 / rate_hz
    q = sqrt_q ** 2
    t = np.arange(1, int(duration_s / T) + 1) * T
    position, velocity = minimum_jerk(t, distance_px, duration_s)
    snr = filtered_speed(position, settled_gains(q, T, noise_px), T) / resting_velocity_sigma(q, T, noise_px)
    result = []
    for level in levels:
        above = np.nonzero(snr >= level)[0]
        result.append(None if len(above) == 0 else (1e3 * t[above[0]], position[above[0]], velocity[above[0]]))
    return result


def ideal_deflection(positions, noise_px):
    """After each report since the start: ||s|| / sigma of the noiseless
    displacements so far, the ideal detector's mean in units of its noise."""
    return np.sqrt(np.cumsum(np.asarray(positions, dtype=float) ** 2)) / noise_px


def one_sided_level(level):
    """The 1-D one-sided threshold (sigmas) with the false-alarm rate of a 2-D
    length beyond level sigmas (Rayleigh: exp(-level^2 / 2))."""
    return float(norm.isf(np.exp(-0.5 * level ** 2)))


def ideal_crossings(rate_hz, noise_px, distance_px, duration_s, levels=(2.5, 5.0), told_direction=False):
    """As crossings(), for the ideal detector; its threshold per level is the
    speed's own (2-D), or with the direction told the 1-D one of the same tail."""
    T = 1.0 / rate_hz
    t = np.arange(1, int(duration_s / T) + 1) * T
    position, velocity = minimum_jerk(t, distance_px, duration_s)
    deflection = ideal_deflection(position, noise_px)
    result = []
    for level in levels:
        threshold = one_sided_level(level) if told_direction else level
        above = np.nonzero(deflection >= threshold)[0]
        result.append(None if len(above) == 0 else (1e3 * t[above[0]], position[above[0]], velocity[above[0]]))
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rate-hz", type=float, default=200.0, help="report rate (default 200)")
    parser.add_argument("--noise-px", type=float, default=1.0, help="white report noise, sigma px (default 1)")
    parser.add_argument("--distance-px", type=float, default=300.0, help="the stroke's length (default 300)")
    parser.add_argument("--duration-s", type=float, default=0.6, help="the stroke's duration (default 0.6)")
    parser.add_argument("--sqrt-q", type=float, nargs="+", default=[20, 45, 100, 200, 400, 750],
                        help="the filter's acceleration densities, px/s^2 (the tracker's direction filter: 45)")
    args = parser.parse_args(argv)
    if min(args.rate_hz, args.noise_px, args.distance_px, args.duration_s, *args.sqrt_q) <= 0:
        print("start_snr: every value must be > 0", file=sys.stderr)
        return 2
    print(f"# start_snr: minimum-jerk start of {args.distance_px:g} px in {args.duration_s:g} s, "
          f"{args.rate_hz:g} reports/s, {args.noise_px:g} px white noise; noiseless response of the settled filter")
    print("| sqrt q px/s² | resting sigma_v px/s | 2.5 sigma at | 5 sigma at |")
    print("|--:|--:|--:|--:|")
    for sqrt_q in args.sqrt_q:
        sigma = resting_velocity_sigma(sqrt_q ** 2, 1.0 / args.rate_hz, args.noise_px)
        cells = []
        for c in crossings(sqrt_q, args.rate_hz, args.noise_px, args.distance_px, args.duration_s):
            cells.append("never" if c is None else f"{c[0]:.0f} ms, {c[1]:.1f} px moved ({c[2]:.0f} px/s)")
        print(f"| {sqrt_q:g} | {sigma:.2f} | {cells[0]} | {cells[1]} |")
    print()
    print("# the ideal detector, told when the stroke starts, its shape and where the finger rested; "
          "its levels have the speed's false-alarm rate at rest")
    print("| told | 2.5 sigma at | 5 sigma at |")
    print("|--|--:|--:|")
    for told_direction, name in ((False, "not the direction (2-D)"),
                                 (True, f"the direction too (1-D, {one_sided_level(2.5):.2f} / "
                                        f"{one_sided_level(5.0):.2f} sigma)")):
        cells = []
        for c in ideal_crossings(args.rate_hz, args.noise_px, args.distance_px, args.duration_s,
                                 told_direction=told_direction):
            cells.append("never" if c is None else f"{c[0]:.0f} ms, {c[1]:.1f} px moved ({c[2]:.0f} px/s)")
        print(f"| {name} | {cells[0]} | {cells[1]} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
