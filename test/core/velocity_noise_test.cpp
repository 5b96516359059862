// The resting finger's velocity noise (velocity_noise.hpp) against a closed
// form (white noise through an alpha-beta filter) and against simulations of
// the real Tracker fed a resting finger's reports.
#include "frictionfield/core/velocity_noise.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "frictionfield/core/tracker.hpp"
#include "support/models/gauss_markov.hpp"
#include "support/random.hpp"

namespace ff {
namespace {

// The direction filter alone, no fade, no widening: its velocity is the one analysed.
TrackerConfig plain_kalman(const SensorProfile& sensor) {
  TrackerConfig c = TrackerConfig::recommended(sensor);
  c.estimator = Estimator::Kalman;
  c.maneuver_threshold = 0.0f;
  c.max_speed_px_s = 1e9f;  // no jump rejection on the noise
  return c;
}

// Variance (per axis, px^2/s^2) of the tracker's velocity for a resting finger at (400, 240)
// whose reports carry `noise(t_s)` (x, y), sampled once per report after 2 s of settling.
// The shipping estimator's direction filter, with the tremor's states when the profile has a tremor.
TrackerConfig split_kalman(const SensorProfile& sensor) {
  TrackerConfig c = plain_kalman(sensor);
  c.estimator = Estimator::SplitKalman;
  c.stroke_end_widening = 1.0f;  // no predicted ends: nothing but the filter
  return c;
}

template <typename Noise>
double simulated_velocity_variance(const SensorProfile& sensor, double seconds, Noise noise,
                                   const TrackerConfig& config) {
  Tracker tracker(config);
  const double dt = 1.0 / static_cast<double>(sensor.report_rate_hz);
  double sum = 0.0;
  long n = 0;
  for (long i = 0; i * dt < seconds; ++i) {
    const double t = static_cast<double>(i) * dt;
    const uint32_t t_us = 1000000u + static_cast<uint32_t>(std::lround(t * 1e6));
    const auto [ex, ey] = noise(t);
    tracker.on_sample({t_us, static_cast<float>(400.0 + ex), static_cast<float>(240.0 + ey), true});
    const TrackState s = tracker.on_tick(t_us);
    // The 2 kHz ticks until the next report (the tracker judges stamps by them).
    for (uint32_t k = 1; k * kTickPeriodUs < static_cast<uint32_t>(dt * 1e6); ++k) tracker.on_tick(t_us + k * kTickPeriodUs);
    if (t < 2.0) continue;
    sum += static_cast<double>(s.velocity.x) * static_cast<double>(s.velocity.x) +
           static_cast<double>(s.velocity.y) * static_cast<double>(s.velocity.y);
    n += 2;
  }
  return sum / static_cast<double>(n);
}

template <typename Noise>
double simulated_velocity_variance(const SensorProfile& sensor, double seconds, Noise noise) {
  return simulated_velocity_variance(sensor, seconds, noise, plain_kalman(sensor));
}

// A resting finger's reports, per axis: 1.5 px of wander (tau 30 ms) and 0.5 px of white noise.
struct WanderAndWhite {
  support::Random rng;
  tracegen::GaussMarkov wx{1.5, 0.03}, wy{1.5, 0.03};
  explicit WanderAndWhite(uint64_t seed) : rng(seed, support::Stream::Noise) {}
  std::pair<double, double> operator()(double t) {
    return {wx.at(t, rng) + 0.5 * rng.gaussian(), wy.at(t, rng) + 0.5 * rng.gaussian()};
  }
};

// The tremor alone, a sinusoid of peak `peak` px on one axis through the tracker: its per-axis
// velocity variance at the worst frequency of low_hz..high_hz, in 5 steps (no noise draws).
double worst_tremor_variance(const SensorProfile& sensor, double peak, const TrackerConfig& config,
                             double low_hz = 8.0, double high_hz = 12.0) {
  double worst = 0.0;
  for (int k = 0; k <= 4; ++k) {
    const double hz = low_hz + 0.25 * k * (high_hz - low_hz);
    const double v = simulated_velocity_variance(
        sensor, 30.0, [&](double t) { return std::pair<double, double>{peak * std::sin(2.0 * M_PI * hz * t), 0.0}; },
        config);
    worst = std::max(worst, 2.0 * v);  // one axis carried it: per-axis variance is twice the mean
  }
  return worst;
}

float accel_q(const TrackerConfig& c) { return c.kalman.accel_noise_px_s2 * c.kalman.accel_noise_px_s2; }

// 1 px of white noise and 1.5 px of tremor (peak), at 200 Hz unless changed.
SensorProfile trembling_finger() {
  SensorProfile sensor;
  sensor.white_noise_px = 1.0f;
  sensor.tremor_px = 1.5f;
  return sensor;
}

// What the tremor adds to the filter's resting velocity noise: the same filter, a finger without it.
double tremor_share(const SteadyStateFilter& f, const SensorProfile& sensor) {
  SensorProfile quiet = sensor;
  quiet.tremor_px = 0.0f;
  return static_cast<double>(resting_velocity_variance(f, sensor) - resting_velocity_variance(f, quiet));
}

TEST(VelocityNoise, WhiteNoiseMatchesTheAlphaBetaClosedForm) {
  SensorProfile sensor;
  sensor.white_noise_px = 1.3f;
  for (float rate : {100.0f, 200.0f, 1000.0f}) {
    sensor.report_rate_hz = rate;
    const SteadyStateFilter f = steady_state_filter(accel_q(plain_kalman(sensor)), ReportNoise::of(sensor), sensor);
    // Kalata (1984): an alpha-beta filter turns white noise of variance s^2
    // into velocity noise 2 beta^2 s^2 / (T^2 alpha (4 - 2 alpha - beta)).
    const double T = 1.0 / static_cast<double>(rate), alpha = static_cast<double>(f.gains.position),
                 beta = static_cast<double>(f.gains.velocity) * T, s2 = 1.3 * 1.3;
    const double expected = 2.0 * beta * beta * s2 / (T * T * alpha * (4.0 - 2.0 * alpha - beta));
    EXPECT_NEAR(static_cast<double>(resting_velocity_variance(f, sensor)), expected, 2e-3 * expected) << rate;
  }
}

TEST(VelocityNoise, WanderMatchesASimulationOfTheTracker) {
  for (float rate : {200.0f, 1000.0f}) {
    SensorProfile sensor;
    sensor.white_noise_px = 0.5f;
    sensor.correlated_noise_px = 1.5f;
    sensor.correlation_time_ms = 30.0f;
    sensor.report_rate_hz = rate;
    const TrackerConfig c = plain_kalman(sensor);
    const double predicted = static_cast<double>(
        resting_velocity_variance(steady_state_filter(accel_q(c), ReportNoise::of(sensor), sensor), sensor));
    const double simulated = simulated_velocity_variance(sensor, 400.0, WanderAndWhite(7));
    EXPECT_NEAR(predicted, simulated, 0.1 * simulated) << rate;
  }
}

TEST(VelocityNoise, TheWanderIsCorrelatedAsAGaussMarkovProcess) {
  SensorProfile sensor;
  sensor.correlated_noise_px = 2.0f;
  sensor.correlation_time_ms = 30.0f;
  const ReportNoise n = ReportNoise::of(sensor);
  for (double dt : {0.001, 0.005, 0.01, 0.03}) {  // up to tau: within 2 % of exp(-dt / tau)
    const double exact = std::exp(-dt / 0.03);
    EXPECT_NEAR(static_cast<double>(n.correlation(static_cast<float>(dt))), exact, 0.02 * exact) << dt;
  }
  EXPECT_EQ(ReportNoise::of(SensorProfile{}).correlation(0.005f), 0.0f);  // no wander
}

TEST(VelocityNoise, FiveTimesTheReportsOfOneWanderTellLittleMore) {
  // At 1 kHz the reports share most of their wander: the settled filter's
  // velocity noise stays near its 200 Hz value (a filter taking each report
  // as independent would see ~1/5 of the noise variance per report).
  SensorProfile sensor;
  sensor.white_noise_px = 0.5f;
  sensor.correlated_noise_px = 2.0f;
  sensor.correlation_time_ms = 30.0f;
  SensorProfile fast = sensor;
  fast.report_rate_hz = 1000.0f;
  const float q = accel_q(plain_kalman(sensor));
  const float v200 = resting_velocity_variance(steady_state_filter(q, ReportNoise::of(sensor), sensor), sensor);
  const float v1k = resting_velocity_variance(steady_state_filter(q, ReportNoise::of(fast), fast), fast);
  EXPECT_NEAR(static_cast<double>(v1k), static_cast<double>(v200), 0.25 * static_cast<double>(v200));
}

TEST(VelocityNoise, TremorMatchesASimulatedSinusoidAtTheWorstFrequency) {
  const SensorProfile sensor = trembling_finger();
  TrackerConfig c = plain_kalman(sensor);
  c.sensor.tremor_px = 0.0f;  // a filter without the tremor's states, which the sinusoid then passes through
  const double tremor_part = tremor_share(steady_state_filter(accel_q(c), ReportNoise::of(sensor), sensor), sensor);
  const double worst = worst_tremor_variance(sensor, 1.5, c);
  EXPECT_NEAR(tremor_part, worst, 0.03 * worst);
}

TEST(VelocityNoise, WithTheTremorsStatesNoiseAndTremorMatchASimulationOfTheTracker) {
  for (float rate : {200.0f, 1000.0f}) {
    SensorProfile sensor;
    sensor.white_noise_px = 0.5f;
    sensor.correlated_noise_px = 1.5f;
    sensor.correlation_time_ms = 30.0f;
    sensor.tremor_px = 1.5f;
    sensor.report_rate_hz = rate;
    SensorProfile quiet = sensor;  // the same filter, a finger without tremor
    quiet.tremor_px = 0.0f;
    const TrackerConfig c = split_kalman(sensor);
    const SteadyStateFilter f = steady_state_filter(accel_q(c), ReportNoise::with_tremor(sensor), sensor);
    ASSERT_TRUE(f.tremor);
    // The noise alone.
    const double noise = simulated_velocity_variance(sensor, 400.0, WanderAndWhite(9), c);
    const double predicted_noise = static_cast<double>(resting_velocity_variance(f, quiet));
    EXPECT_NEAR(predicted_noise, noise, 0.1 * noise) << rate;
    // The tremor alone, at its worst frequency.
    const double worst = worst_tremor_variance(sensor, 1.5, c);
    const double predicted_tremor = static_cast<double>(resting_velocity_variance(f, sensor)) - predicted_noise;
    EXPECT_NEAR(predicted_tremor, worst, 0.05 * worst + 0.01 * predicted_noise) << rate;
  }
}

TEST(VelocityNoise, AMeasuredTremorIsTakenWithinOneAndAHalfHertzOfItsFrequency) {
  for (float rate : {200.0f, 1000.0f}) {
    SensorProfile sensor = trembling_finger();
    sensor.tremor_hz = 7.3f;  // outside the unmeasured 8-12 Hz
    sensor.report_rate_hz = rate;
    const TrackerConfig c = split_kalman(sensor);
    const double predicted_tremor =
        tremor_share(steady_state_filter(accel_q(c), ReportNoise::with_tremor(sensor), sensor), sensor);
    const double worst = worst_tremor_variance(sensor, 1.5, c, 5.8, 8.8);
    EXPECT_NEAR(predicted_tremor, worst, 0.05 * worst) << rate;
  }
}

TEST(VelocityNoise, AMeasuredFrequencyKeepsMoreOfTheTremorOut) {
  // Told where the tremor is, the states resonate there: a finger trembling
  // at that frequency reads as slower than with the unmeasured model, which
  // resonates at 10 Hz.
  SensorProfile told = trembling_finger();
  told.tremor_hz = 8.6f;
  SensorProfile untold = told;
  untold.tremor_hz = 0.0f;
  auto tremor_at = [](const SensorProfile& s, double hz) {
    return worst_tremor_variance(s, 1.5, split_kalman(s), hz, hz);
  };
  EXPECT_LT(tremor_at(told, 8.6), 0.5 * tremor_at(untold, 8.6));
}

TEST(VelocityNoise, TheTremorsStatesKeepMostOfItOutOfTheVelocity) {
  // What the states are for: a trembling resting finger reads as much
  // slower, so the direction confidence's band can sit lower.
  const SensorProfile sensor = trembling_finger();
  const float q = accel_q(split_kalman(sensor));
  const float without = resting_velocity_variance(steady_state_filter(q, ReportNoise::of(sensor), sensor), sensor);
  const float with = resting_velocity_variance(steady_state_filter(q, ReportNoise::with_tremor(sensor), sensor), sensor);
  SensorProfile still = sensor;
  still.tremor_px = 0.0f;
  const float white_only = resting_velocity_variance(steady_state_filter(q, ReportNoise::of(still), still), still);
  EXPECT_LT(with, 0.25f * without);
  EXPECT_LT(with, 2.0f * white_only);
}

}  // namespace
}  // namespace ff
