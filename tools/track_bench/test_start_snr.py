"""start_snr.py against closed forms: the alpha-beta filter's velocity noise
(variance reduction ratio 2 beta^2 / (T^2 alpha (4 - 2 alpha - beta))), a
ramp followed without steady-state error, the ideal detector's deflection (a
constant displacement: s sqrt(n) / sigma), its 1-D level against the speed's
tail at rest (Monte Carlo), no filter above it (Cauchy-Schwarz), and the CLI's
tables and exit codes."""
import numpy as np
import pytest

import start_snr
from plot_test_support import run_script


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
    rows = [line for line in capsys.readouterr().out.splitlines() if line.startswith("| ") and line[2].isdigit()]
    assert len(rows) == 2
    assert start_snr.main(["--rate-hz", "0"]) == 2


def test_ideal_deflection_of_a_constant_displacement_is_s_root_n_over_sigma():
    # n reports displaced by s each: ||s|| = s sqrt(n)
    assert start_snr.ideal_deflection(np.full(16, 0.5), 2.0)[-1] == pytest.approx(0.5 * 4.0 / 2.0, rel=1e-12)
    assert start_snr.ideal_deflection(np.full(16, 0.5), 2.0)[3] == pytest.approx(0.5 * 2.0 / 2.0, rel=1e-12)


def test_one_sided_level_has_the_speeds_tail_at_rest():
    # The speed of two independent axes at rest is Rayleigh; its tail beyond k sigma
    # by Monte Carlo, against the 1-D tail beyond the returned level (closed form).
    rng = np.random.default_rng(7)
    speed = np.hypot(rng.standard_normal(2_000_000), rng.standard_normal(2_000_000))
    from scipy.stats import norm
    for k in (1.5, 2.5):
        assert np.mean(speed > k) == pytest.approx(norm.sf(start_snr.one_sided_level(k)), rel=0.02)
    assert start_snr.one_sided_level(2.5) == pytest.approx(1.706, abs=1e-3)


@pytest.mark.parametrize("sqrt_q", [20.0, 45.0, 100.0, 750.0])
@pytest.mark.parametrize("distance_px,duration_s", [(300.0, 0.6), (100.0, 1.5)])
def test_no_settled_filter_sees_a_start_sooner_than_the_ideal_detector(sqrt_q, distance_px, duration_s):
    # Cauchy-Schwarz, checked with the filter's own code: its speed over its
    # resting sigma never exceeds ||s|| / sigma, report by report.
    T = 0.005
    t = np.arange(1, int(duration_s / T) + 1) * T
    position, _ = start_snr.minimum_jerk(t, distance_px, duration_s)
    gains = start_snr.settled_gains(sqrt_q ** 2, T, 1.0)
    snr = start_snr.filtered_speed(position, gains, T) / start_snr.resting_velocity_sigma(sqrt_q ** 2, T, 1.0)
    assert np.all(snr <= start_snr.ideal_deflection(position, 1.0) * (1.0 + 1e-9))
    filtered = start_snr.crossings(sqrt_q, 200.0, 1.0, distance_px, duration_s)
    ideal = start_snr.ideal_crossings(200.0, 1.0, distance_px, duration_s)
    told = start_snr.ideal_crossings(200.0, 1.0, distance_px, duration_s, told_direction=True)
    for f, i, d in zip(filtered, ideal, told):
        assert i is not None and d is not None
        assert d[0] <= i[0] and (f is None or i[0] <= f[0])


def test_cli_prints_the_ideal_detector_too(capsys):
    assert start_snr.main([]) == 0
    out = capsys.readouterr().out
    assert "| not the direction (2-D) | 55 ms, 2.0 px moved" in out
    assert "| the direction too (1-D, 1.71 / 4.48 sigma) | 50 ms, 1.5 px moved" in out


def test_cli_prints_both_tables_whole(capsys):
    assert start_snr.main(["--sqrt-q", "45"]) == 0
    # Minimum-jerk, 300 px in 0.6 s: at 55 ms (tau 0.0917) 300 (10 tau^3 - 15 tau^4 + 6 tau^5) = 2.0 px moved at
    # 500 (30 tau^2 - 60 tau^3 + 30 tau^4) = 104 px/s; at 70 ms 4.0 px, 159 px/s; at 65 ms 3.2 px, 140 px/s; at 50
    # ms 1.5 px, 88 px/s. 5.32 px/s: the settled filter's resting sigma (the alpha-beta closed form, tested above).
    assert capsys.readouterr().out.splitlines() == [
        "# start_snr: minimum-jerk start of 300 px in 0.6 s, 200 reports/s, 1 px white noise; noiseless response "
        "of the settled filter",
        "| sqrt q px/s² | resting sigma_v px/s | 2.5 sigma at | 5 sigma at |",
        "|--:|--:|--:|--:|",
        "| 45 | 5.32 | 55 ms, 2.0 px moved (104 px/s) | 70 ms, 4.0 px moved (159 px/s) |",
        "",
        "# the ideal detector, told when the stroke starts, its shape and where the finger rested; its levels have "
        "the speed's false-alarm rate at rest",
        "| told | 2.5 sigma at | 5 sigma at |",
        "|--|--:|--:|",
        "| not the direction (2-D) | 55 ms, 2.0 px moved (104 px/s) | 65 ms, 3.2 px moved (140 px/s) |",
        "| the direction too (1-D, 1.71 / 4.48 sigma) | 50 ms, 1.5 px moved (88 px/s) | 65 ms, 3.2 px moved (140 px/s) |"]


def test_a_stroke_too_short_to_stand_out_is_never_seen_and_bad_values_are_one_line(capsys):
    assert start_snr.main(["--sqrt-q", "45", "--distance-px", "1"]) == 0
    assert "| 45 | 5.32 | never | never |" in capsys.readouterr().out.splitlines()
    assert start_snr.main(["--noise-px", "-1"]) == 2
    assert capsys.readouterr() == ("", "start_snr: every value must be > 0\n")


def test_run_as_a_script_it_exits_with_mains_code():
    r = run_script("start_snr.py", "--duration-s", "0")
    assert (r.returncode, r.stdout, r.stderr) == (2, "", "start_snr: every value must be > 0\n")
