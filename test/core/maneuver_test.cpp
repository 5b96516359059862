// Changes of motion: the direction filter's age-weighted innovation sum
// (TrackerConfig::maneuver_*), judged by its false-alarm rate against the
// chi-square tail and by what it is for: catching stops and starts.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "frictionfield/core/tracker.hpp"

namespace ff {
namespace {

constexpr uint32_t kPeriodUs = 5000;  // 200 Hz

// Reports of a finger that moves exactly as the direction filter's model
// says (white acceleration of density q, white report noise), for `settle`
// reports and then `counted` more; returns the widenings among the counted.
struct ModelFinger {
  std::mt19937_64 rng{20261124};
  std::normal_distribution<double> unit{0.0, 1.0};

  uint32_t widenings(Tracker& tracker, int settle, int counted, double q, double noise_px) {
    const double dt = kPeriodUs * 1e-6;
    // Exact discretisation of white acceleration over dt: Cholesky of
    // q [[dt^3/3, dt^2/2], [dt^2/2, dt]].
    const double l00 = std::sqrt(q * dt * dt * dt / 3.0), l10 = q * dt * dt / 2.0 / l00;
    const double l11 = std::sqrt(q * dt - l10 * l10);
    double p[2] = {static_cast<double>(kScreenMaxX) / 2.0, static_cast<double>(kScreenMaxY) / 2.0}, v[2] = {0.0, 0.0};
    uint32_t before = 0;
    tracker.reset();
    for (int i = 0; i < settle + counted; ++i) {
      if (i == settle) before = tracker.maneuvers();
      for (int a = 0; a < 2; ++a) {
        const double w0 = unit(rng), w1 = unit(rng);
        p[a] += v[a] * dt + l00 * w0;
        v[a] += l10 * w0 + l11 * w1;
      }
      tracker.on_sample({static_cast<uint32_t>(i + 1) * kPeriodUs, static_cast<float>(p[0] + noise_px * unit(rng)),
                         static_cast<float>(p[1] + noise_px * unit(rng)), true});
    }
    return tracker.maneuvers() - before;
  }
};

TEST(Maneuver, FalseAlarmsAtTheChiSquareTailWhenTheModelHolds) {
  // The age-weighted sum of independent innovations over its variance is
  // chi^2 with 2 degrees of freedom: P(> t) = exp(-t / 2) per report.
  for (float threshold : {8.0f, 12.0f}) {
    TrackerConfig c = TrackerConfig::recommended();
    c.maneuver_threshold = threshold;
    Tracker tracker(c);
    ModelFinger finger;
    const double q = static_cast<double>(c.kalman.accel_noise_px_s2) * static_cast<double>(c.kalman.accel_noise_px_s2);
    uint32_t alarms = 0;
    const int segments = 2000, counted = 200;
    for (int k = 0; k < segments; ++k) alarms += finger.widenings(tracker, 100, counted, q, 1.0);
    const double rate = static_cast<double>(alarms) / (segments * counted);
    const double expected = std::exp(-static_cast<double>(threshold) / 2.0);
    EXPECT_NEAR(rate / expected, 1.0, 0.2) << "threshold " << threshold << ": " << alarms << " alarms, rate " << rate
                                            << ", expected " << expected;
    ::testing::Test::RecordProperty("alarms_at_" + std::to_string(static_cast<int>(threshold)), static_cast<int>(alarms));
  }
}

// A stroke along x at 600 px/s (3 px per report, noiseless), then reports
// `step_after` px apart: the ticks from the stroke's last report until
// `done(direction)` holds (at most 2000).
template <typename Done>
int ticks_after_a_stroke(const TrackerConfig& c, float step_after, Done done) {
  Tracker tracker(c);
  uint32_t t = 0;
  float x = 100.0f;
  for (int i = 0; i < 100; ++i, t += kPeriodUs, x += 3.0f) tracker.on_sample({t, x, 240.0f, true});
  x -= 3.0f;
  int ticks = 0;
  for (uint32_t now = t - kPeriodUs; ticks < 2000; now += kTickPeriodUs, ++ticks) {
    while (static_cast<int32_t>(t - now) <= 0) {
      x += step_after;
      tracker.on_sample({t, x, 240.0f, true});
      t += kPeriodUs;
    }
    if (done(tracker.on_tick(now).direction)) break;
  }
  return ticks;
}

// Neither at a change of motion nor at a predicted stroke end.
TrackerConfig never_widening() {
  TrackerConfig c = TrackerConfig::recommended();
  c.maneuver_threshold = 0.0f;
  c.stroke_end_widening = 1.0f;
  return c;
}

// The detector alone: no stroke ends predicted.
TrackerConfig only_maneuvers() {
  TrackerConfig c = TrackerConfig::recommended();
  c.stroke_end_widening = 1.0f;
  return c;
}

TEST(Maneuver, AStopIsCaughtWithinAFewReports) {
  auto at_rest = [](Vec2 d) { return length(d) < 0.1f; };
  const int with = ticks_after_a_stroke(only_maneuvers(), 0.0f, at_rest);
  const int without = ticks_after_a_stroke(never_widening(), 0.0f, at_rest);
  // Measured: 30 ms with, 120 ms without.
  EXPECT_LE(with, 80) << "40 ms";
  EXPECT_GE(without, 2 * with);
}

TEST(Maneuver, AReversalIsFollowedSooner) {
  auto turned = [](Vec2 d) { return d.x < -0.9f; };
  const int with = ticks_after_a_stroke(only_maneuvers(), -3.0f, turned);
  const int without = ticks_after_a_stroke(never_widening(), -3.0f, turned);
  // Measured: 40 ms with, 60 ms without.
  EXPECT_LE(with, 90) << "45 ms";
  EXPECT_GE(without, with + 30) << "15 ms sooner";
}

// A sensor whose wander changes slowly (10 s) at 1 kHz, with tremor: each
// change of motion widens the direction filter, and the reports see only the
// finger plus the wander. Widened without bound, the two grew together
// (covariances ~5e7) until the innovation's variance, their difference, was
// rounded to 0 or below: velocities of 1e28 px/s and NaN directions, from
// one profile that is_valid() accepts. Strokes of 2 s and rests of 1 s for a
// minute, the speed a sinusoid's (up to 380 px/s).
TEST(Maneuver, RepeatedWideningsStayBoundedWithASlowWander) {
  SensorProfile slow_wander;
  slow_wander.white_noise_px = 0.52f;
  slow_wander.correlated_noise_px = 1.5f;
  slow_wander.correlation_time_ms = 10000.0f;
  slow_wander.report_rate_hz = 1000.0f;
  slow_wander.tremor_px = 1.0f;
  ASSERT_TRUE(is_valid(slow_wander));
  Tracker tracker(TrackerConfig::recommended(slow_wander));
  std::mt19937_64 rng{7};
  std::normal_distribution<double> unit{0.0, 1.0};
  double x = 100.0, wander = 0.0, heading = 1.0;
  uint32_t widenings_before = 0;
  for (uint32_t k = 0; k < 60000; ++k) {  // a report every ms
    const double t = k * 1e-3, phase = std::fmod(t, 3.0);
    const double speed = phase < 2.0 ? 380.0 * std::sin(M_PI * phase / 2.0) : 0.0;
    if (phase >= 2.0 && phase < 2.001) heading = -heading;  // back and forth
    x += heading * speed * 1e-3;
    wander = wander * std::exp(-1e-3 / 10.0) + 1.5 * std::sqrt(1.0 - std::exp(-2e-3 / 10.0)) * unit(rng);
    const double tremor = std::sin(2.0 * M_PI * 10.0 * t);
    const uint32_t t_us = 1000000 + k * 1000;
    tracker.on_sample({t_us, static_cast<float>(x + wander + tremor + 0.52 * unit(rng)),
                       static_cast<float>(240.0 + wander + 0.52 * unit(rng)), true});
    if (k == 1000) widenings_before = tracker.maneuvers() + tracker.stroke_ends();
    if (k % 2 == 0) continue;
    const TrackState& s = tracker.on_tick(t_us + 500);
    const double v = std::hypot(s.velocity.x, s.velocity.y), d = std::hypot(s.direction.x, s.direction.y);
    ASSERT_TRUE(std::isfinite(v) && v < 2000.0) << "report " << k << ": |v| " << v;
    ASSERT_TRUE(std::isfinite(d) && d <= 1.0 + 1e-5) << "report " << k << ": |direction| " << d;
  }
  EXPECT_GT(tracker.maneuvers() + tracker.stroke_ends() - widenings_before, 40u) << "the widening this is about";
}

}  // namespace
}  // namespace ff
