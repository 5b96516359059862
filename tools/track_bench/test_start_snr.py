"""start_snr.py against closed forms: the alpha-beta filter's velocity noise
(variance reduction ratio 2 beta^2 / (T^2 alpha (4 - 2 alpha - beta))), a
ramp followed without steady-state error, and the CLI's table and exit codes."""
import numpy as np
import pytest

import start_snr


@pytest.mark.parametrize("sqrt_q,rate_hz", [(45.0, 200.0), (750.0, 100.0), (45.0, 1000.0)])
def test_resting_velocity_noise_is_the_alpha_beta_closed_form(sqrt_q, rate_hz):
    T = 1.0 / rate_hz
    k = start_snr.settled_gains(sqrt_q ** 2, T, 1.0)
    alpha, beta = k[0], k[1] * T
    closed_form = 2.0 * beta ** 2 / (T ** 2 * alpha * (4.0 - 2.0 * alpha - beta))
    assert start_snr.resting_velocity_sigma(sqrt_q ** 2, T, 1.0) ** 2 == pytest.approx(closed_form, rel=1e-9)


def test_the_core_computes_the_same_resting_noise():
    # core/velocity_noise.cpp for the shipping direction filter and default profile
    # (sqrt q 45, 1 px, 200 Hz): 28.3426 px^2/s^2 in float (VelocityNoise tests).
    assert start_snr.resting_velocity_sigma(45.0 ** 2, 0.005, 1.0) ** 2 == pytest.approx(28.3426, rel=3e-3)


def test_a_settled_filter_follows_a_ramp_without_lag_in_velocity():
    T = 0.005
    t = np.arange(1, 2001) * T
    filtered = start_snr.filtered_speed(120.0 * t, start_snr.settled_gains(45.0 ** 2, T, 1.0), T)
    assert filtered[-1] == pytest.approx(120.0, rel=1e-6)
    assert filtered[5] < 120.0  # but it starts from rest


def test_crossings_come_later_for_higher_levels_and_never_for_an_unreachable_one():
    low, high, never = start_snr.crossings(45.0, 200.0, 1.0, 300.0, 0.6, levels=(2.5, 5.0, 1e9))
    assert 0 < low[0] < high[0]
    assert 0 < low[1] < high[1]
    assert never is None


def test_cli_prints_a_row_per_density_and_refuses_bad_values(capsys):
    assert start_snr.main(["--sqrt-q", "45", "100"]) == 0
    rows = [line for line in capsys.readouterr().out.splitlines() if line.startswith("| ") and "ms" in line]
    assert len(rows) == 2
    assert start_snr.main(["--rate-hz", "0"]) == 2
