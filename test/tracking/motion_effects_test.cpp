// The finger effects of issue 14: slow strokes, hesitations, sharp
// reversals and tremor, each checked against how it was defined (speeds,
// shares, geometry, frequency and amplitude), not against its own output.
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "support/models/sensor_model.hpp"
#include "support/models/trace_classes.hpp"
#include "trace_writer.hpp"

namespace ff::tracegen {
namespace {

MotionOptions long_motion(Strategy strategy, double duration_s = 600.0) {
  MotionOptions o;
  o.strategy = strategy;
  o.duration_s = duration_s;
  return o;
}

std::vector<const Segment*> strokes_of(const Motion& m) {
  std::vector<const Segment*> out;
  for (const Segment& s : m.segments())
    if (s.kind == SegmentKind::Stroke) out.push_back(&s);
  return out;
}

// Highest speed of a stroke, sampled every millisecond.
double sampled_peak_speed(const Motion& m, const Segment& s) {
  double peak = 0.0;
  for (double t = s.t_start_s; t < s.t_start_s + s.duration_s; t += 0.001) {
    const TrueState st = m.at(t);
    peak = std::max(peak, std::hypot(st.velocity.x, st.velocity.y));
  }
  return peak;
}

Point chord(const Segment& s) { return {s.p1.x - s.p0.x, s.p1.y - s.p0.y}; }
double dot(Point a, Point b) { return a.x * b.x + a.y * b.y; }

TEST(SlowStrokes, AllSlowPeakBetween20And70PxPerSecondAndLastAtMost2s) {
  for (Strategy strategy : {Strategy::Along, Strategy::Across}) {
    MotionOptions o = long_motion(strategy, 120.0);
    o.slow_fraction = 1.0;
    const Motion m = plan_motion(o, 5);
    const auto strokes = strokes_of(m);
    ASSERT_GT(strokes.size(), 40u);
    for (const Segment* s : strokes) {
      EXPECT_GE(s->peak_speed_px_s, 20.0);
      EXPECT_LE(s->peak_speed_px_s, 70.0);
      // Shortened to last at most 2 s; along a curved path the shortened x
      // range holds a little more or less than its share of the arc.
      EXPECT_LE(s->duration_s, s->shape == StrokeShape::Bowed ? 2.0 + 1e-9 : 2.1);
      // Minimum jerk peaks at 1.875 L / T; along a curved path the speed
      // varies along the stroke, so the sampled peak is near, not at, the plan.
      const double peak = sampled_peak_speed(m, *s);
      EXPECT_GT(peak, 0.7 * 20.0);
      EXPECT_LT(peak, 1.5 * 70.0);
    }
  }
}

TEST(SlowStrokes, AlongAPathTheyAreSizedByThePathsArc) {
  // A shortened stroke lasts 0.8-2 s when its kept share is taken of the
  // arc along the path, offsets and all; taken of another curve (no rise,
  // no starting offset) some last up to 2.2 s. 20 seeds, ~700 strokes.
  int shortened = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    MotionOptions o = long_motion(Strategy::Along, 120.0);
    o.slow_fraction = 1.0;
    const Motion m = plan_motion(o, seed);
    for (const Segment* s : strokes_of(m)) {
      if (s->shape != StrokeShape::AlongPath || s->duration_s < 0.7) continue;  // short enough unshortened
      ++shortened;
      EXPECT_LE(s->duration_s, 2.1) << "seed " << seed;
    }
  }
  EXPECT_GT(shortened, 300);
}

TEST(SlowStrokes, TheirShareIsTheOneAskedFor) {
  MotionOptions o = long_motion(Strategy::Mixed, 900.0);
  o.slow_fraction = 0.3;
  const auto m = plan_motion(o, 6);
  const auto strokes = strokes_of(m);
  size_t slow = 0;
  for (const Segment* s : strokes) slow += s->peak_speed_px_s <= 70.0 ? 1 : 0;  // the others: >= 250 px/s
  const double share = static_cast<double>(slow) / static_cast<double>(strokes.size());
  ASSERT_GT(strokes.size(), 500u);
  // Binomial: sqrt(0.3 * 0.7 / n) < 0.02; 0.06 is 3 sigma.
  EXPECT_NEAR(share, 0.3, 0.06);
}

TEST(Hesitations, StopMidStrokeAndGoOnTheSameWay) {
  MotionOptions o = long_motion(Strategy::Mixed, 300.0);
  o.hesitation_fraction = 1.0;
  const Motion m = plan_motion(o, 7);
  const auto& seg = m.segments();
  size_t hesitations = 0, same_way = 0;
  for (size_t i = 1; i + 1 < seg.size(); ++i) {
    if (!seg[i].hesitation) continue;
    ++hesitations;
    ASSERT_EQ(seg[i].kind, SegmentKind::Hold);
    ASSERT_EQ(seg[i - 1].kind, SegmentKind::Stroke);
    ASSERT_EQ(seg[i + 1].kind, SegmentKind::Stroke);
    EXPECT_GE(seg[i].duration_s, 0.08);
    EXPECT_LE(seg[i].duration_s, 0.3);
    const TrueState mid = m.at(seg[i].t_start_s + 0.5 * seg[i].duration_s);
    EXPECT_EQ(mid.velocity.x, 0.0);
    EXPECT_FALSE(mid.resting);  // a hesitation is not a rest
    same_way += dot(chord(seg[i - 1]), chord(seg[i + 1])) > 0.0 ? 1 : 0;
  }
  // Every planned stroke hesitates once: half the strokes end in a hesitation.
  EXPECT_EQ(hesitations, strokes_of(m).size() / 2);
  EXPECT_GE(same_way, hesitations * 95 / 100);
}

TEST(Reversals, TurnStraightBackForAFractionOfTheStroke) {
  for (Strategy strategy : {Strategy::Along, Strategy::Across}) {
    MotionOptions o = long_motion(strategy, 300.0);
    const Motion plain = plan_motion(o, 8);
    o.reversal_fraction = 1.0;
    const Motion m = plan_motion(o, 8);
    auto back_to_back = [](const Motion& motion, std::vector<std::pair<const Segment*, const Segment*>>* pairs) {
      size_t n = 0;
      const auto& seg = motion.segments();
      for (size_t i = 1; i < seg.size(); ++i) {
        if (seg[i].kind != SegmentKind::Stroke || seg[i - 1].kind != SegmentKind::Stroke) continue;
        ++n;
        if (pairs) pairs->push_back({&seg[i - 1], &seg[i]});
      }
      return n;
    };
    EXPECT_EQ(back_to_back(plain, nullptr), 0u);  // without reversals every stroke ends in a dwell
    std::vector<std::pair<const Segment*, const Segment*>> pairs;
    back_to_back(m, &pairs);
    EXPECT_EQ(pairs.size(), strokes_of(m).size() / 2);
    for (const auto& [stroke, flick] : pairs) {
      EXPECT_LT(dot(chord(*stroke), chord(*flick)), 0.0);
      const double share = stroke->shape == StrokeShape::AlongPath
                               ? std::fabs(chord(*flick).x / chord(*stroke).x)
                               : std::hypot(chord(*flick).x, chord(*flick).y) / std::hypot(chord(*stroke).x, chord(*stroke).y);
      EXPECT_GE(share, 0.15 - 1e-9);
      EXPECT_LE(share, 0.40 + 1e-9);
      EXPECT_DOUBLE_EQ(flick->peak_speed_px_s, stroke->peak_speed_px_s);
    }
  }
}

// Power of v at frequency f (a one-bin DFT), samples at t.
double power_at(const std::vector<double>& t, const std::vector<double>& v, double f) {
  double re = 0.0, im = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    re += v[i] * std::cos(2.0 * M_PI * f * t[i]);
    im += v[i] * std::sin(2.0 * M_PI * f * t[i]);
  }
  return re * re + im * im;
}

TEST(Tremor, InTheReportsNotInTheTruthAndReportedSeparately) {
  TraceOptions o;
  o.seed = 9;
  o.motion.duration_s = 20.0;
  o.sensor.rate_hz = 1000.0;
  o.sensor.jitter_us = 0.0;
  o.sensor.noise_px = 0.0;
  o.tremor.amplitude_px = 1.5;
  const GeneratedTrace t = generate_trace(o);
  ASSERT_TRUE(t.tremor.enabled());
  std::vector<double> times, shake_x, shake_y;
  for (const TraceSample& s : t.samples) {
    if (!s.touch) continue;
    const Point truth = t.truth_at(s.t_us).position;  // the voluntary motion
    ASSERT_EQ(s.x_true, truth.x);
    const Point tremor = t.tremor_at(s.t_us);
    ASSERT_NEAR(s.x - s.x_true, tremor.x, 1e-9);
    ASSERT_NEAR(s.y - s.y_true, tremor.y, 1e-9);
    times.push_back(static_cast<double>(s.t_us - t.start_us) * 1e-6);
    shake_x.push_back(s.x - s.x_true);
    shake_y.push_back(s.y - s.y_true);
  }
  // A sinusoid of amplitude A: RMS A / sqrt(2) on each axis.
  auto rms = [](const std::vector<double>& v) {
    double sum = 0.0;
    for (double x : v) sum += x * x;
    return std::sqrt(sum / static_cast<double>(v.size()));
  };
  EXPECT_NEAR(rms(shake_x), 1.5 / std::sqrt(2.0), 0.02);
  EXPECT_NEAR(rms(shake_y), 1.5 / std::sqrt(2.0), 0.02);
  // The spectrum of what the sensor adds peaks in 8-12 Hz, at the drawn frequency.
  double best_f = 0.0, best_p = -1.0;
  for (double f = 1.0; f <= 100.0; f += 0.05) {
    const double p = power_at(times, shake_x, f);
    if (p > best_p) best_p = p, best_f = f;
  }
  EXPECT_GE(best_f, 8.0);
  EXPECT_LE(best_f, 12.0);
  EXPECT_NEAR(best_f, t.tremor.frequency_hz(), 0.05);
  // The writer keeps it apart: its own columns, only with tremor.
  std::ostringstream with, without;
  write_trace(with, t, false);
  o.tremor.amplitude_px = 0.0;
  write_trace(without, generate_trace(o), false);
  EXPECT_EQ(with.str().substr(0, with.str().find('\n')), "t_us,x,y,touch,x_true,y_true,x_tremor,y_tremor");
  EXPECT_EQ(without.str().substr(0, without.str().find('\n')), "t_us,x,y,touch,x_true,y_true");
}

TEST(Tremor, FrequenciesAreDrawnIn8To12Hz) {
  double sum = 0.0;
  constexpr int kSeeds = 200;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    support::Random rng(static_cast<uint64_t>(seed), Stream::Tremor);
    const Tremor tremor(TremorOptions{1.0, 8.0, 12.0}, rng);
    ASSERT_GE(tremor.frequency_hz(), 8.0);
    ASSERT_LE(tremor.frequency_hz(), 12.0);
    sum += tremor.frequency_hz();
  }
  // Uniform: mean 10 Hz, standard deviation 4 / sqrt(12) / sqrt(200) = 0.08 Hz.
  EXPECT_NEAR(sum / kSeeds, 10.0, 0.33);
}

TEST(TraceClasses, NamedOnceFoundByNameAndWhite200HzIsTodaysModel) {
  for (const TraceClass& c : trace_classes()) EXPECT_EQ(find_trace_class(c.name), &c);
  EXPECT_EQ(find_trace_class("no-such-class"), nullptr);
  // white-200hz: the standard set's low noise level (1 px, zForce quantum), 200 Hz, 150 us jitter.
  TraceOptions today;
  today.seed = 4;
  today.sensor.noise_px = kNoiseLowPx;
  today.sensor.quantum_px = kZForceQuantumPx;
  TraceOptions white = today;
  // Whatever was set before, the class resets it: each effect of the finger and the sensor.
  white.motion.slow_fraction = 0.5;
  white.motion.hesitation_fraction = 0.5;
  white.motion.reversal_fraction = 0.5;
  white.tremor.amplitude_px = 2.0;
  white.sensor.correlated_noise_px = 3.0;
  find_trace_class("white-200hz")->apply(white);
  std::ostringstream a, b;
  write_trace(a, generate_trace(today), false);
  write_trace(b, generate_trace(white), false);
  EXPECT_TRUE(a.str() == b.str());
  TraceOptions fast = today;
  find_trace_class("realistic-1khz")->apply(fast);
  EXPECT_EQ(fast.sensor.rate_hz, 1000.0);
  EXPECT_GT(fast.tremor.amplitude_px, 0.0);
  EXPECT_GT(fast.sensor.correlated_noise_px, 0.0);
  EXPECT_GT(fast.motion.slow_fraction, 0.0);
  EXPECT_EQ(fast.seed, today.seed);
}

TEST(TraceClasses, EachClassHasTheNumbersDocsTrackingMdGivesIt) {
  struct Expected {
    const char* name;
    double slow, hesitation, reversal, tremor_px, latency_us, latency_spread_us, noise_px, correlated_px, tau_s,
        rate_hz, period_jitter_us, drift_px;
  };
  // docs/tracking.md#trace-classes, by hand; every class keeps the 150 us
  // stamp jitter and the 0.5 px quantum; the drift's tau is 10 s.
  const Expected table[] = {
      {"white-200hz", 0, 0, 0, 0, 0, 0, 1.0, 0, 0.03, 200, 0, 0},
      {"slow-fingers", 0.1, 0.2, 0.3, 0, 0, 0, 1.0, 0, 0.03, 200, 0, 0},
      {"tremor", 0, 0, 0, 1.5, 0, 0, 1.0, 0, 0.03, 200, 0, 0},
      {"latency", 0, 0, 0, 0, 1000, 2000, 1.0, 0, 0.03, 200, 0, 0},
      {"correlated-noise", 0, 0, 0, 0, 0, 0, 0.5, 1.5, 0.03, 200, 0, 0},
      {"realistic-100hz", 0.1, 0.2, 0.3, 1.0, 1000, 2000, 0.5, 1.5, 0.03, 100, 200, 2.0},
      {"realistic-200hz", 0.1, 0.2, 0.3, 1.0, 1000, 2000, 0.5, 1.5, 0.03, 200, 100, 2.0},
      {"realistic-1khz", 0.1, 0.2, 0.3, 1.0, 1000, 2000, 0.5, 1.5, 0.03, 1000, 20, 2.0},
  };
  ASSERT_EQ(trace_classes().size(), std::size(table));
  for (const Expected& e : table) {
    SCOPED_TRACE(e.name);
    TraceOptions o;
    const TraceClass* c = find_trace_class(e.name);
    ASSERT_NE(c, nullptr);
    c->apply(o);
    EXPECT_DOUBLE_EQ(o.motion.slow_fraction, e.slow);
    EXPECT_DOUBLE_EQ(o.motion.hesitation_fraction, e.hesitation);
    EXPECT_DOUBLE_EQ(o.motion.reversal_fraction, e.reversal);
    EXPECT_DOUBLE_EQ(o.tremor.amplitude_px, e.tremor_px);
    EXPECT_DOUBLE_EQ(o.tremor.min_hz, 8.0);
    EXPECT_DOUBLE_EQ(o.tremor.max_hz, 12.0);
    EXPECT_DOUBLE_EQ(o.sensor.latency_us, e.latency_us);
    EXPECT_DOUBLE_EQ(o.sensor.latency_spread_us, e.latency_spread_us);
    EXPECT_DOUBLE_EQ(o.sensor.noise_px, e.noise_px);
    EXPECT_DOUBLE_EQ(o.sensor.quantum_px, 0.5);
    EXPECT_DOUBLE_EQ(o.sensor.jitter_us, 150.0);
    EXPECT_DOUBLE_EQ(o.sensor.correlated_noise_px, e.correlated_px);
    EXPECT_DOUBLE_EQ(o.sensor.correlated_noise_tau_s, e.tau_s);
    EXPECT_DOUBLE_EQ(o.sensor.rate_hz, e.rate_hz);
    EXPECT_DOUBLE_EQ(o.sensor.period_jitter_us, e.period_jitter_us);
    EXPECT_DOUBLE_EQ(o.sensor.drift_px, e.drift_px);
    EXPECT_DOUBLE_EQ(o.sensor.drift_tau_s, 10.0);
  }
}

TEST(TraceClasses, TheNominalProfileIsTheClassSensorInTheProfilesTerms) {
  // By hand: white noise with the quantum's q^2/12, stamp jitter twice and
  // period jitter once in the interval's spread, the mean latency.
  const SensorProfile white = class_profile("white-200hz");
  EXPECT_FLOAT_EQ(white.white_noise_px, static_cast<float>(std::sqrt(1.0 + 0.25 / 12.0)));
  EXPECT_EQ(white.correlated_noise_px, 0.0f);
  EXPECT_EQ(white.correlation_time_ms, 0.0f);  // no wander: no correlation time either
  EXPECT_EQ(white.tremor_px, 0.0f);
  EXPECT_EQ(white.report_rate_hz, 200.0f);
  EXPECT_FLOAT_EQ(white.jitter_us, static_cast<float>(150.0 * std::sqrt(2.0)));
  EXPECT_EQ(white.latency_us, 0u);
  const SensorProfile real = class_profile("realistic-100hz");
  EXPECT_FLOAT_EQ(real.white_noise_px, static_cast<float>(std::sqrt(0.25 + 0.25 / 12.0)));
  EXPECT_EQ(real.correlated_noise_px, 1.5f);
  EXPECT_EQ(real.correlation_time_ms, 30.0f);
  EXPECT_EQ(real.tremor_px, 1.0f);
  EXPECT_EQ(real.report_rate_hz, 100.0f);
  EXPECT_FLOAT_EQ(real.jitter_us, static_cast<float>(std::sqrt(2.0 * 150.0 * 150.0 + 200.0 * 200.0)));
  EXPECT_EQ(real.latency_us, 2000u);  // 1-3 ms
}

TEST(TraceClassesDeathTest, AMisspeltClassStopsTheTestAndSaysWhich) {
  EXPECT_DEATH(class_profile("realistic-200Hz"), "no trace class \"realistic-200Hz\"");
}

}  // namespace
}  // namespace ff::tracegen
